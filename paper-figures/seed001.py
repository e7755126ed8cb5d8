#!/usr/bin/python3
"""Seed 001 (Bodrova and Osinsky) Figs 1-10: partial MSDs from DSMC (replica mean +- standard error) over
eq 17 of `granular-theory` for the same input, and the ratios of diffusion coefficients D_k/D_1 (eq 19,
long-time limit) against n_2 and the restitution.

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  seed001_fig1_msd_rescaled               msd_fig1
  seed001_fig2_msd_binary                 msd_fig2
  seed001_fig3_msd_dilute_heavy           msd_fig3, msd_fig3_late (dashed: measured from <T> = 1)
  seed001_fig6_msd_ternary                msd_fig6
  seed001_fig9_msd_viscoelastic           msd_fig9
  seed001_fig10_msd_viscoelastic_ternary  msd_fig10
  seed001_fig8_msd_ratio                  msd_ratio_theta{3,4}_t1e9 (t = 1e9), else msd_ratio_theta{3,4}
  seed001_fig4_diffusion_ratio_n2         diffusion_ratio_fig4, diffusion_ratio_fig4_sigma
  seed001_fig5_diffusion_ratio_epsilon    diffusion_ratio_fig5, diffusion_ratio_fig5_sigma
  seed001_fig7_diffusion_ratio_4species   diffusion_ratio_fig7
Figs 4, 5, 7 are theory lines (`granular-theory` with a `&sweep`, temporary namelists only) with the DSMC
points of every run whose case name starts with diffusion_ratio_ and whose masses fit the figure (e.g.
--run diffusion_ratio_mine=my-run.h5); without such runs their panel says "theory only".

Eq 17 is an approximation: DSMC lies up to ~14-16 % below it for the light species (docs/diffusion-msd.md,
validation/msd_binary/README.md), which the residual panels (DSMC/eq 17 - 1, in percent) show.
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import re

import h5py
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from figures_common import (COLUMN, figure, pick, pick_or_none, observable, run_theory, theory, save, Missing,
                            TheoryError, with_residuals, residuals)


LINE_SAMPLES = 161  # sample times of the smooth eq 17 lines (the DSMC runs have 41)
COLORS = ("C0", "C3", "C2", "C1")
MARKERS = ("o", "s", "^", "D")


# ---------------------------------------------------------------------------------------------
# MSD figures (1, 2, 6, 9, 10)
# ---------------------------------------------------------------------------------------------

def rescaled_time(t, T1):
    """t_s(t) = int_0^t sqrt(T_1(t')/T_1(0)) dt' by the trapezoid rule; t[0] = 0. Past the first interval
    the trapezoid runs in ln t on t sqrt(T_1/T_1(0)) (exact for the power laws of a log-spaced grid)."""
    w = np.sqrt(np.clip(T1 / T1[0], 0.0, None))
    ts = np.zeros_like(t)
    ts[1] = 0.5 * (w[0] + w[1]) * (t[1] - t[0])
    g = t[1:] * w[1:]
    ts[2:] = ts[1] + np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(np.log(t[1:])))
    return ts


def msd_data(path):
    """DSMC and eq 17 of one MSD case: a dict with times, values, errors, theory on the sample times and on
    a dense grid, temperatures, species parameters."""
    with h5py.File(path) as f:
        t, R, dR = observable(f, "msd")
        tT, T, _ = observable(f, "temperature")
        s = f["parameters/system"].attrs
        d = dict(t=t, R=R, dR=dR, tT=tT, T=T, mass=s["mass"], diameter=s["diameter"],
                 n=s["number_density"], N=f["parameters/dsmc"].attrs["n_particles"],
                 replicas=f["parameters/dsmc"].attrs["replicas"],
                 model=s["restitution_model"] if "restitution_model" in s else "constant")
    th = theory(path)  # on the DSMC sample times (from the MSD's start on), for the ratio panel
    late = len(d["t"]) - len(th["msd"]["time"])  # samples before a late start (output:msd_start_time)
    assert late >= 0 and np.allclose(th["msd"]["time"], d["t"][late:], rtol=1e-9), "theory and DSMC sample times differ"
    d["Rth"] = np.vstack([np.zeros((late, R.shape[1])), np.array(th["msd"]["value"]).reshape(-1, R.shape[1])])
    dense = theory(path, [f"output:n_samples={LINE_SAMPLES}"])
    d["tl"] = np.array(dense["msd"]["time"])
    d["Rl"] = np.array(dense["msd"]["value"])
    d["Tl"] = np.array(dense["temperature"]["value"])
    d["x"] = np.asarray(d["n"], float) / np.sum(d["n"])
    return d


THEORY_NAME = "Bodrova-Osinsky theory"


def species_label(d, k):
    return f"$m_{k + 1} = {d['mass'][k]:g}$, $\\sigma_{k + 1} = {d['diameter'][k]:.3g}$"


def slope_guide(ax, x0, x1, y0, power, label, ls="--", where="above"):
    x = np.array([x0, x1])
    ax.plot(x, y0 * (x / x0) ** power, ls, color="0.45", lw=1.1)
    xm = np.sqrt(x0 * x1)
    ym = y0 * (xm / x0) ** power
    if where == "left":
        ax.annotate(label, (xm, ym), textcoords="offset points", xytext=(-8, 0), ha="right", va="center")
    elif where == "below":
        ax.annotate(label, (xm, ym), textcoords="offset points", xytext=(4, -12))
    else:
        ax.annotate(label, (xm, ym), textcoords="offset points", xytext=(-14, 6))


def late_start(path):
    """The MSDs of a run whose measurement started late (output:msd_start_time) in the time of the paper's
    protocol, where the measurement starts when <T> = 1 after cooling from <T> >> 1: hard spheres of constant
    restitution are the same gas with all velocities scaled by sqrt(T), so a time t - t_start of this run
    is (t - t_start) sqrt(<T>(t_start)) there, and the displacements are unchanged. <T>(t_start) is the
    mixture temperature interpolated log-log between the samples around the start."""
    d = msd_data(path)
    with h5py.File(path) as f:
        start = float(np.mean(f["observables/msd/start_time"][()]))
        tT, T_total, _ = observable(f, "total_temperature")
    keep = tT > 0
    T_start = float(np.exp(np.interp(np.log(start), np.log(tT[keep]), np.log(T_total[keep]))))
    scale = np.sqrt(T_start)
    d["xd"], d["xl"] = (d["t"] - start) * scale, (d["tl"] - start) * scale
    d["sel"], d["sl"] = d["t"] > start, d["tl"] > start
    return d


def msd_figure(case, title, filename, total=False, rescale=False, guides=("t^2",), late_case=None):
    path = pick(case)
    d = msd_data(path)
    S = d["R"].shape[1]
    t, tl = d["t"], d["tl"]
    if rescale:  # each against its own T_1: DSMC from the measured T_1, eq 17 from the theory's T_1
        assert np.allclose(d["tT"], t)
        xd, xl = rescaled_time(t, d["T"][:, 0]), rescaled_time(tl, d["Tl"][:, 0])
    else:
        xd, xl = t, tl
    fig, ax, ar = with_residuals(width=COLUMN * 1.25, height=4.0)
    sel, sl = t > 0, tl > 0
    for k in range(S):
        c = COLORS[k]
        ax.plot(xl[sl], d["Rl"][sl, k], "-", color=c, lw=1.2, label=species_label(d, k))
        ax.errorbar(xd[sel], d["R"][sel, k], yerr=d["dR"][sel, k], fmt=MARKERS[k], mfc="none", color=c)
        residuals(ar, xd[sel], d["R"][sel, k], d["dR"][sel, k], d["Rth"][sel, k], kind="percent", fmt=MARKERS[k],
                  mfc="none", color=c, ms=2.5)
    late_path = pick_or_none(late_case) if late_case else None
    if late_path is not None:  # the paper's dashed lines: the measurement started at <T> = 1
        e = late_start(late_path)
        for k in range(S):
            c = COLORS[k]
            ax.plot(e["xl"][e["sl"]], e["Rl"][e["sl"], k], "--", color=c, lw=1.0)
            ax.errorbar(e["xd"][e["sel"]], e["R"][e["sel"], k], yerr=e["dR"][e["sel"], k], fmt=MARKERS[k], color=c,
                        ms=3)
            residuals(ar, e["xd"][e["sel"]], e["R"][e["sel"], k], e["dR"][e["sel"], k], e["Rth"][e["sel"], k],
                      kind="percent", fmt=MARKERS[k], color=c, ms=2.5)
        ax.plot([], [], "k--", lw=1.0, label="dashed, filled: started at $\\langle T\\rangle = 1$")
    if total:  # eq 16: number-fraction weighted mean of the partial MSDs
        x = d["x"]
        Rt_l = d["Rl"] @ x
        Rt_th = d["Rth"] @ x
        Rt = d["R"] @ x
        dRt = np.sqrt((d["dR"] ** 2) @ (x ** 2))  # species treated as independent
        ax.plot(xl[sl], Rt_l[sl], "--", color="k", lw=1.2, label=r"whole gas $\langle R^2\rangle$")
        ax.errorbar(xd[sel], Rt[sel], yerr=dRt[sel], fmt="x", color="k")
        residuals(ar, xd[sel], Rt[sel], dRt[sel], Rt_th[sel], kind="percent", fmt="x", color="k", ms=3)
    # slope guides, offset from the light species' line so they do not hide data
    x0 = xl[sl][0]
    y_first = d["Rl"][sl, 0][0]
    if "t^2" in guides:
        x1 = x0 * 30.0
        slope_guide(ax, x0, x1, 4.0 * y_first, 2.0, "$t_s^2$" if rescale else "$t^2$", where="left")
    xe, ye = xl[sl][-1], d["Rl"][sl][-1].max()  # late guides end 3x above the highest line
    if "t" in guides:  # normal diffusion (Fig 1, dotted as in the paper)
        slope_guide(ax, xe / 30.0, xe, 3.0 * ye / 30.0, 1.0, "$t_s$", ls=":")
    if "t^(1/6)" in guides:
        slope_guide(ax, xe / 1e3, xe, 3.0 * ye / 1e3 ** (1 / 6), 1.0 / 6.0, "$t^{1/6}$", where="below")
    ax.plot([], [], "k-", lw=1.2, label=f"lines: {THEORY_NAME}")
    ax.errorbar([], [], yerr=[], fmt="o", mfc="none", color="0.3", label="symbols: DSMC")
    ax.set(xscale="log", yscale="log", ylabel=r"$\langle R_k^2\rangle$")
    ax.set_title(title)
    ax.legend(loc="lower right")
    ar.set(xlabel=r"$t_s = \int_0^t \sqrt{T_1(t')/T_1(0)}\,dt'$" if rescale else "$t$")
    lo, hi = ar.get_ylim()
    ar.set_ylim(min(lo, -20), max(hi, 20))
    save(fig, filename)


# ---------------------------------------------------------------------------------------------
# D_k/D_1 figures (4, 5, 7): theory lines from temporary namelists with a &sweep
# ---------------------------------------------------------------------------------------------

SIGMA2_EQUAL = "1.0"
SIGMA2_MATERIAL = f"{100.0 ** (1 / 3):.9f}"
EPS_LINE = np.round(np.r_[np.arange(0.05, 0.951, 0.025), 0.96, 0.97, 0.98, 0.985, 0.99, 0.995, 1.0], 3)
N2_LINE = np.logspace(-4, 0, 41)


def sweep_namelist(mass, diameter, density, restitution, variable, values):
    """A theory-only namelist (small &dsmc, two samples) with a &sweep of `variable` over `values`."""
    fmt = lambda a: ", ".join(str(v) for v in a)  # noqa: E731
    return (f"! seed001.py: temporary theory-only input\n"
            f"&system\n  n_species = {len(mass)}\n  mass = {fmt(mass)}\n  diameter = {fmt(diameter)}\n"
            f"  number_density = {fmt(density)}\n  restitution = {restitution}\n/\n"
            f"&dsmc\n  n_particles = 100000\n  t_end = 1.0\n/\n"
            f"&output\n  file = 'unused.h5'\n  n_samples = 2\n/\n"
            f"&sweep\n  variable = '{variable}'\n  values = {', '.join(values)}\n/\n")


def ratio_line(mass, diameter, density, restitution, variable, xs, fmt):
    """(x, D_k/D_1) along xs (sweep values fmt(x)). granular-theory also solves the binary first-Sonine HCS
    and stops when that has no root in its bracket (gamma < 1e-4: heavy intruders of equal size at very
    small n_2); then the points are computed one by one and those are left out, with a note."""
    values = [fmt(x) for x in xs]
    try:
        pts = run_theory(sweep_namelist(mass, diameter, density, restitution, variable, values))["points"]
        return np.asarray(xs), np.array([p["diffusion_coefficient_ratio"] for p in pts])
    except TheoryError:
        pass
    keep, rows, dropped = [], [], []
    for x, v in zip(xs, values):
        try:
            p = run_theory(sweep_namelist(mass, diameter, density, restitution, variable, [v]))["points"][0]
        except TheoryError as e:
            dropped.append((x, e.args[0].splitlines()[-1]))
            continue
        keep.append(x)
        rows.append(p["diffusion_coefficient_ratio"])
    if dropped:
        print(f"note: granular-theory gives no point for {variable} = {', '.join(f'{x:g}' for x, _ in dropped)} "
              f"(masses {mass}, diameters {diameter}): {dropped[0][1]}")
    return np.asarray(keep), np.array(rows)


def increment_ratio(t, R, dR=None):
    """D_k/D_1 from the MSD increments over the last decade of t (as validate_diffusion_ratio does): from
    the last sample with t <= t_end/10 to t_end. <R_k^2> grows as 6 int D_k dt and in the HCS every D_k(t)
    has the same time dependence, so the increments have the ratio D_k/D_1."""
    a = max(1, int(np.searchsorted(t, t[-1] / 10.0, side="right")) - 1)
    inc = R[-1] - R[a]
    r = inc / inc[0]
    if dR is None:
        return r
    dinc = np.hypot(dR[-1], dR[a])
    return r, r * np.hypot(dinc / inc, dinc[0] / inc[0])


def dsmc_ratio_points():
    """D_k/D_1 measured by the `diffusion_ratio_*` validation cases (validation/diffusion_ratio), if any:
    a list of dicts (system parameters, sweep variable, rows of (value, DSMC ratio, its SE, eq 17's ratio
    over the same decade)). The paper tier of a case is preferred to its quick variant."""
    out = []
    for name, p in fc.cases_starting("diffusion_ratio_"):
        try:
            with h5py.File(p) as f:
                s = f["parameters/system"].attrs
                dsmc = f["parameters/dsmc"].attrs
                variable = f["sweep"].attrs["variable"]
                vals = [v.decode() if isinstance(v, bytes) else str(v) for v in f["sweep"].attrs["values"]]
                rows = []
                for i, v in enumerate(vals):
                    t, R, dR = observable(f[f"sweep/point_{i + 1}"], "msd")
                    rows.append([v, *increment_ratio(t, R, dR), t])
                m = dict(name=name, variable=variable, mass=s["mass"], diameter=s["diameter"],
                         path=p, N=dsmc["n_particles"], replicas=dsmc["replicas"])
            pts = theory(p)["points"]  # eq 17 on the same sample times, per sweep point
            for row, pt in zip(rows, pts):
                assert np.allclose(pt["msd"]["time"], row[3], rtol=1e-9), "theory and DSMC sample times differ"
                row[3] = increment_ratio(np.array(pt["msd"]["time"]), np.array(pt["msd"]["value"]))
            m["rows"] = rows
            out.append(m)
        except (KeyError, ValueError, IndexError, TheoryError) as e:
            print(f"note: {name} not understood as a D_k/D_1 measurement ({e}); not plotted")
    return out


def sweep_x(variable, value):
    """Abscissa of a DSMC sweep point: n_2 for number_density sweeps, the restitution otherwise."""
    nums = [float(x) for x in re.split(r"[,\s]+", value.strip("'\" ")) if x]
    return nums[1] if "number_density" in variable else nums[0]


def ratio_axes(measured, want, height):
    """(fig, main axes, residual axes or None): a residual panel when DSMC points will be drawn."""
    if any(want(m) is not None for m in measured):
        return with_residuals(height=height + 1.0)
    fig, ax = plt.subplots(figsize=(COLUMN, height))
    return fig, ax, None


def overlay_dsmc(fig, ax, ar, measured, want, fig_no, cases, xlabel):
    """Plots the DSMC D_k/D_1 points (and eq 17's ratio over the same decade of t) of the measurements for
    which want(m) gives (colors per k, label prefix); on `ar` (if any) DSMC against that ratio in percent.
    The legend goes below the figure."""
    shown = 0
    for m in measured:
        spec = want(m)
        if spec is None:
            continue
        colors, prefix = spec
        for v, r, e, r17 in m["rows"]:
            x = sweep_x(m["variable"], v)
            for k in range(1, len(r)):
                ax.errorbar([x], [r[k]], yerr=[e[k]], fmt=MARKERS[k - 1], ms=5, color=colors[k], mfc="none",
                            label=f"DSMC, {prefix}$D_{k + 1}/D_1$, last decade of $t$")
                ax.plot([x], [r17[k]], "+", ms=8, mew=1.2, color="0.35",
                        label="MSD theory, same decade of $t$")
                if ar is not None:
                    residuals(ar, [x], [r[k]], [e[k]], [r17[k]], kind="percent", fmt=MARKERS[k - 1], ms=4,
                              mfc="none", color=colors[k])
        shown += 1
        fc.note_used(m["path"])
        print(f"Fig {fig_no}: DSMC points from {m['name']}")
    if not shown:  # the theory lines alone: the panel says so
        fc.no_dsmc(ax, cases)
    (ar if ar is not None else ax).set_xlabel(xlabel)
    h, lab = ax.get_legend_handles_labels()
    keep = dict(zip(lab, h))  # one legend entry per label
    fig.legend(keep.values(), keep.keys(), loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=1)


def binary(m):
    return len(m["mass"]) == 2 and np.isclose(m["mass"][1] / m["mass"][0], 100.0)


def sigma_kind(m):
    return "equal" if np.isclose(m["diameter"][1], m["diameter"][0]) else "material"


@figure("seed001_fig4_diffusion_ratio_n2", "seed001_fig5_diffusion_ratio_epsilon")
def fig4_fig5():
    measured = dsmc_ratio_points()
    styles = {"equal": ("k", r"$\sigma_2 = 1$"), "material": ("C0", r"$\sigma_2 = 100^{1/3}$")}

    def want(variable):
        def f(m):
            if not (binary(m) and variable in m["variable"]):
                return None
            color, label = styles[sigma_kind(m)]
            return (None, color), label + ", "
        return f

    fig4, ax4, ar4 = ratio_axes(measured, want("number_density"), 3.0)
    fig5, ax5, ar5 = ratio_axes(measured, want("restitution"), 3.0)
    for kind, s2 in (("equal", SIGMA2_EQUAL), ("material", SIGMA2_MATERIAL)):
        color, label = styles[kind]
        x, r = ratio_line([1.0, 100.0], [1.0, s2], [0.1, 0.1], 0.5, "system:number_density", N2_LINE,
                          lambda n2: f"'0.1, {n2:.6g}'")
        note = f" (no theory below $n_2 = {x[0]:.1g}$)" if x[0] > N2_LINE[0] else ""
        ax4.plot(x, r[:, 1], "-", color=color, lw=1.2, label=f"long-time theory, {label}{note}")
        x, r = ratio_line([1.0, 100.0], [1.0, s2], [0.1, 0.1], 0.5, "system:restitution", EPS_LINE,
                          lambda e: f"{e:g}")
        ax5.plot(x, r[:, 1], "-", color=color, lw=1.2, label=f"long-time theory, {label}")
    ax4.set(xscale="log", yscale="log", ylabel=r"$D_2/D_1$", title=r"$m = 1, 100$, $\varepsilon = 0.5$")
    ax5.set(ylabel=r"$D_2/D_1$", xlim=(0.0, 1.0), yscale="log", title=r"$m = 1, 100$, $n_1 = n_2 = 0.1$")
    for ax in (ax4, ax5):
        ax.grid(alpha=0.3, which="both")
        ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())

    overlay_dsmc(fig4, ax4, ar4, measured, want("number_density"), 4,
                 ("diffusion_ratio_fig4", "diffusion_ratio_fig4_sigma"), r"$n_2$ ($n_1 = 0.1$)")
    overlay_dsmc(fig5, ax5, ar5, measured, want("restitution"), 5,
                 ("diffusion_ratio_fig5", "diffusion_ratio_fig5_sigma"), r"restitution coefficient $\varepsilon$")
    save(fig4, "seed001_fig4_diffusion_ratio_n2")
    save(fig5, "seed001_fig5_diffusion_ratio_epsilon")


@figure("seed001_fig7_diffusion_ratio_4species")
def fig7():
    measured = dsmc_ratio_points()
    mass = [1.0, 2.0, 3.0, 4.0]
    diameter = [f"{k ** (1 / 3):.9f}" for k in (1, 2, 3, 4)]
    x, r = ratio_line(mass, diameter, [0.1] * 4, 0.5, "system:restitution", EPS_LINE, lambda e: f"{e:g}")
    want = lambda m: ((None,) + COLORS[:3], "") if len(m["mass"]) == 4 and "restitution" in m["variable"] else None  # noqa: E731
    fig, ax, ar = ratio_axes(measured, want, 3.0)
    for k in range(1, 4):
        ax.plot(x, r[:, k], "-", color=COLORS[k - 1], lw=1.2, label=f"long-time theory, $D_{k + 1}/D_1$")
    ax.set(ylabel=r"$D_k/D_1$", xlim=(0.0, 1.0), title=r"$m_k = k$, $\sigma_k = k^{1/3}$, $n_k = 0.1$")
    ax.grid(alpha=0.3)
    overlay_dsmc(fig, ax, ar, measured, want, 7, ("diffusion_ratio_fig7",), r"restitution coefficient $\varepsilon$")
    save(fig, "seed001_fig7_diffusion_ratio_4species")


@figure("seed001_fig8_msd_ratio")
def fig8():
    """<R_k^2>/<R_1^2> against k at the end of the run, n_k = n_1 k^-theta (validation msd_many_species)."""
    fig, ax, ar = with_residuals()
    drawn, t_end = False, None
    for case, marker, color in (("msd_ratio_theta3", "o", "C0"), ("msd_ratio_theta4", "s", "C1")):
        path = pick_or_none(case + "_t1e9") or pick_or_none(case)  # the paper's t = 1e9 where it was run
        if path is None:
            continue
        th = theory(path)
        with h5py.File(path) as f:
            R = f["observables/msd/value"][()]
            dR = f["observables/msd/error"][()]
            theta = float(f["parameters/system"].attrs["density_exponent"])
            t_end = float(f["observables/msd/time"][-1])
        k = np.arange(1, R.shape[1] + 1)
        ratio = R[-1] / R[-1, 0]
        err = ratio * np.sqrt((dR[-1] / R[-1]) ** 2 + (dR[-1, 0] / R[-1, 0]) ** 2)
        Rth = np.array(th["msd"]["value"])[-1]
        ax.plot(k, Rth / Rth[0], "-", color=color, label=f"{THEORY_NAME}, $\\theta = {theta:g}$")
        ax.errorbar(k, ratio, yerr=err, fmt=marker, mfc="none", color=color, label=f"DSMC, $\\theta = {theta:g}$")
        residuals(ar, k, ratio, err, Rth / Rth[0], kind="percent", fmt=marker, mfc="none", color=color)
        drawn = True
    if not drawn:
        plt.close(fig)
        raise Missing("no MSD-ratio outputs", case="msd_ratio_theta3")
    ax.set(xscale="log", ylabel=r"$\langle R_k^2\rangle/\langle R_1^2\rangle$",
           title=rf"$n_k = n_1 k^{{-\theta}}$, $\varepsilon = 0.5$, $t = {fc.power_of_ten(t_end)}$ (the paper: $10^9$)")
    ar.set(xlabel=r"$k = m_k/m_1$")
    ax.legend()
    save(fig, "seed001_fig8_msd_ratio")


@figure("seed001_fig3_msd_dilute_heavy")
def fig3():
    msd_figure("msd_fig3", r"dilute heavy species $n_2 = 0.001$, $m = 1, 100$", "seed001_fig3_msd_dilute_heavy",
               late_case="msd_fig3_late")


@figure("seed001_fig1_msd_rescaled")
def fig1():
    msd_figure("msd_fig1", r"$\varepsilon = 0.5$, $m = 1, 100$, $\sigma = 1, 1$", "seed001_fig1_msd_rescaled",
               rescale=True, guides=("t^2", "t"))


@figure("seed001_fig2_msd_binary")
def fig2():
    msd_figure("msd_fig2", r"$\varepsilon = 0.5$, $m = 1, 100$, $\sigma_2 = 100^{1/3}$", "seed001_fig2_msd_binary")


@figure("seed001_fig6_msd_ternary")
def fig6():
    msd_figure("msd_fig6", r"$\varepsilon = 0.5$, $m = 1, 100, 500$", "seed001_fig6_msd_ternary", total=True)


@figure("seed001_fig9_msd_viscoelastic")
def fig9():
    msd_figure("msd_fig9", r"viscoelastic, $A\kappa^{2/5} = 0.09$, $m = 1, 100$", "seed001_fig9_msd_viscoelastic",
               guides=("t^2", "t^(1/6)"))


@figure("seed001_fig10_msd_viscoelastic_ternary")
def fig10():
    msd_figure("msd_fig10", r"viscoelastic, $m = 1, 100, 500$", "seed001_fig10_msd_viscoelastic_ternary",
               total=True, guides=("t^2", "t^(1/6)"))


if __name__ == "__main__":
    fc.main()
