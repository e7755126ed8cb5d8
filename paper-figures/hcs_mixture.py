#!/usr/bin/python3
"""The homogeneous cooling state of mixtures of s species (issue 17): the temperature ratios T_k/T
(T = sum_k n_k T_k / n) and the cumulants c_k of DSMC against the first-Sonine theory for s species and
the Maxwellian approximation of `granular-theory`, for the ternary (masses 1:3:10, alpha = 0.7) and
five-species cases of validation/hcs_mixture, with residuals (DSMC/theory - 1 in percent) below.

The DSMC values are the averages over the samples past `&output scaling_start` collisions per particle,
with the standard error of the average taken as the mean of the samples' (an upper bound), as
`granular-dsmc --compare` and the validation program compute them (src/analysis/compare.cpp).

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  hcs_mixture_temperature_ratios  hcs_ternary, hcs_five (one panel each)
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import h5py
import numpy as np
from figures_common import PAGE, Missing, figure, pick, observable, theory, save, with_residuals, residuals

CASES = (("hcs_ternary", "three species"), ("hcs_five", "five species"))


def scaling_state(path):
    """(masses, T_k/T, its standard error, c_k, its standard error) averaged over the scaling state."""
    with h5py.File(path) as f:
        _, T, dT = observable(f, "temperature")
        _, Tt, dTt = observable(f, "total_temperature")
        _, c, dc = observable(f, "sonine_c")
        _, C, _ = observable(f, "collisions_per_particle")
        start = float(f["parameters/output"].attrs["scaling_start"])
        masses = f["parameters/system"].attrs["mass"]
        alpha = float(np.ravel(f["parameters/system"].attrs["restitution"])[0])
    Tt, dTt, C = np.ravel(Tt), np.ravel(dTt), np.ravel(C)
    r = T / Tt[:, None]
    dr = r * np.hypot(dT / T, (dTt / Tt)[:, None])
    sel = C >= start
    if not sel.any():
        raise ValueError(f"{path}: no sample past scaling_start = {start}")
    return masses, alpha, r[sel].mean(axis=0), dr[sel].mean(axis=0), c[sel].mean(axis=0), dc[sel].mean(axis=0)


@figure("hcs_mixture_temperature_ratios")
def temperature_ratios():
    fig, axes, ars = with_residuals(ncols=2, width=PAGE, height=3.2, sharex=False)
    drawn = False
    for ax, ar, (case, title) in zip(axes, ars, CASES):
        try:
            path = pick(case)
        except Missing:
            fc.no_dsmc(ax, case, theory_drawn=False)
            ar.set_visible(False)
            continue
        drawn = True
        th = theory(path)["hcs"]
        masses, alpha, r, dr, _, _ = scaling_state(path)
        sonine = np.array(th["first_sonine"]["temperature_over_mean"])
        maxwell = np.array(th["maxwellian"]["temperature_over_mean"])
        k = np.arange(1, len(r) + 1)
        ax.plot(k, sonine, "x", color="k", ms=6, mew=1.2, label="first Sonine")
        ax.plot(k, maxwell, "+", color="C1", ms=7, mew=1.2, label="Maxwellian")
        ax.errorbar(k, r, yerr=dr, fmt="o", mfc="none", color="C0", label="DSMC")
        residuals(ar, k - 0.08, r, dr, sonine, kind="percent", fmt="o", mfc="none", color="C0")
        residuals(ar, k + 0.08, r, dr, maxwell, kind="percent", fmt="s", mfc="none", color="C1", ms=2.5)
        ax.set(ylabel=r"$T_k/T$")
        ax.set_title(f"{title}: $m_k = " + ", ".join(f"{m:g}" for m in masses) + f"$, $\\alpha = {alpha:g}$")
        for a in (ax, ar):
            a.set_xticks(k)
            a.set_xlim(0.5, len(k) + 0.5)
            a.tick_params(axis="x", which="minor", bottom=False, top=False)
        ar.set(xlabel=r"species $k$")
    if not drawn:
        raise Missing(f"no run of {CASES[0][0]} or {CASES[1][0]}", case=CASES[0][0])
    ars[1].set_ylabel("")
    if axes[0].get_legend_handles_labels()[0]:  # the first panel may be marked as without data
        axes[0].legend(loc="upper left")
    proxies = [axes[1].plot([], [], "o", mfc="none", color="C0", label="DSMC against first Sonine")[0],
               axes[1].plot([], [], "s", mfc="none", color="C1", ms=2.5, label="DSMC against Maxwellian")[0]]
    axes[1].legend(handles=proxies, loc="upper left", title="residual panels", title_fontsize="small")
    save(fig, "hcs_mixture_temperature_ratios")


if __name__ == "__main__":
    fc.main()
