#!/usr/bin/python3
"""Seed 003 (Montanero and Garzo 2002) Figs 1-7: DSMC points (replica mean +- standard error) over the
first-Sonine lines of `granular-theory` for the same mixture, with residual panels (DSMC minus theory)
below where the two overlap. The smooth theory lines come from `granular-theory` on the stored namelist
with a dense `&sweep` of its own (temporary files only).

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  seed003_fig1_gamma_time         temperature_ratio_time
  seed003_fig2_cumulants          sonine_cumulants_fig2 (one-component points: haff_cooling_alpha{0.5,0.9})
  seed003_fig3_delta              hcs_distribution_alpha0.5
  seed003_fig4_gamma_alpha_mu     gamma_alpha_fig4_mu{10,2,0.1}
  seed003_fig5_gamma_alpha_delta  gamma_alpha_fig5_delta{4,1,0.25}
  seed003_fig6_gamma_density      gamma_density_alpha{0.6,0.8}, gamma_density_alpha{0.6,0.8}_dilute
                                  (gamma(alpha, 0): the same mixture as a dilute gas)
  seed003_fig7_tail               hcs_distribution_alpha{0.3,0.5}
Figs 1, 4, 5, 6 read &sweep runs (one point per sweep value).
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import re

import h5py
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from figures_common import (COLUMN, PAGE, figure, pick, pick_or_none, pick_some, observable, reduced_distribution, stored_input,
                            run_theory, theory, save, with_residuals, residuals)


ALPHA_LINE = np.round(np.arange(0.1, 1.0001, 0.02), 2)  # alpha grid of the theory lines
SCALING_START = 10.0  # collisions per particle after which the HCS is reached (Fig 2 averages)


def sweep_points(f):
    """[(value string, point group)] of a sweep run, in order point_1, point_2, ..."""
    values = [v.decode() if isinstance(v, bytes) else str(v) for v in f["sweep"].attrs["values"]]
    return [(v, f[f"sweep/point_{k + 1}"]) for k, v in enumerate(values)]


def gamma_of(T, dT, i):
    """gamma = T1/T2 at sample i and its standard error (propagated from those of T1, T2)."""
    g = T[i, 0] / T[i, 1]
    return g, g * np.hypot(dT[i, 0] / T[i, 0], dT[i, 1] / T[i, 1])


def theory_sweep(path, variable, values, extra=(), stored=None):
    """granular-theory on the stored input (or `stored` = (namelist text, overrides)) with its &sweep
    replaced by `variable` over `values` (strings, written as given); a small run size since only the
    theory is computed. Returns the list of points."""
    text, overrides = stored if stored is not None else stored_input(path)
    text = re.sub(r"^\s*&sweep\b.*?^\s*/\s*$", "", text, flags=re.S | re.M | re.I)
    text += f"\n&sweep\n  variable = '{variable}'\n  values   = {', '.join(values)}\n/\n"
    small = ["dsmc:n_particles=100", "dsmc:collisions_per_particle=1.0", "output:n_samples=2"]
    sets = [o for o in overrides if not o.startswith("dsmc:n_particles")] + small + list(extra)
    return run_theory(text, sets)["points"]


def theory_alpha_line(path):
    points = theory_sweep(path, "system:restitution", [f"{a:.2f}" for a in ALPHA_LINE])
    return ALPHA_LINE, points


def line_at(x_line, y_line, x):
    """The theory line y(x) at the DSMC abscissae x (linear interpolation on the dense grid)."""
    return np.interp(np.asarray(x, float), np.asarray(x_line, float), np.asarray(y_line, float))


@figure("seed003_fig1_gamma_time")
def fig1_gamma_time():
    path = pick("temperature_ratio_time")
    th = theory(path)["points"]
    fig, axes, ars = with_residuals(ncols=2, width=PAGE, height=3.0, sharex="col")
    with h5py.File(path) as f:
        # Time in the paper's unit t0 = lambda_11/v01(0), lambda_11 = 1/(sqrt2 pi n1 sigma_11^2) (n* = 0:
        # chi_11 = 1), v01(0) = sqrt(2 T1(0)/m1) (Montanero and Garzo 2002, Sec. 3 and Fig. 1's caption).
        p = f["parameters/system"].attrs
        n1, sigma1, m1 = (float(np.ravel(p[key])[0]) for key in ("number_density", "diameter", "mass"))
        T1 = float(np.ravel(f["parameters/initial"].attrs["temperature"])[0])
        t0 = 1.0 / (np.sqrt(2.0) * np.pi * n1 * sigma1**2) / np.sqrt(2.0 * T1 / m1)
        for k, (ax, ar, (value, g)) in enumerate(zip(axes, ars, sweep_points(f))):
            t, T, dT = observable(g, "temperature")
            _, C, _ = observable(g, "collisions_per_particle")
            gam = T[:, 0] / T[:, 1]
            err = gam * np.hypot(dT[:, 0] / T[:, 0], dT[:, 1] / T[:, 1])
            x = t / t0
            ax.errorbar(x, gam, yerr=err, fmt="o", mfc="none", color="C0", label="DSMC")
            gs = th[k]["temperature_ratio"]
            ax.axhline(gs, color="k", ls=":", lw=1, label=f"first Sonine, $\\gamma = {gs:.4f}$")
            late = C >= SCALING_START  # the HCS: the residual of the settled ratio
            residuals(ar, x[late], gam[late], err[late], np.full(late.sum(), gs), kind="percent", fmt="o",
                      mfc="none", color="C0")
            ax.set(ylabel=r"$\gamma(t) = T_1/T_2$")
            ax.set_title(f"({'ab'[k]}) $\\alpha = {float(value):g}$")
            ar.set(xlabel=r"$t/t_0$, $t_0 = \lambda_{11}/v_{01}(0)$")
            if abs(gs - 1.0) < 1e-12:
                ax.set_ylim(0.96, 1.04)
            ax.legend(loc="lower right" if gs > 1 else "upper right")
    fig.suptitle(r"$\mu = 10$, $\delta = 2$, $w = 1$, $n^* = 0$")
    save(fig, "seed003_fig1_gamma_time")


def one_component_dsmc():
    """2 a2 = c of one-species HCS runs in the validation outputs (the Haff cases of validation/haff_cooling), averaged past
    SCALING_START collisions per particle: [(alpha, c, se)]. Missing runs are skipped."""
    out = []
    try:
        found = pick_some(["haff_cooling_alpha0.5", "haff_cooling_alpha0.9"])
    except fc.Missing:
        return out
    for case, path in found:
        with h5py.File(path) as f:
            if "sonine_c" not in f["observables"]:
                continue
            alpha = float(np.ravel(f["parameters/system"].attrs["restitution"])[0])
            _, c, dc = observable(f, "sonine_c")
            _, C, _ = observable(f, "collisions_per_particle")
        c, dc = np.ravel(c), np.ravel(dc)
        sel = C >= SCALING_START
        if sel.any():
            out.append((alpha, c[sel].mean(), dc[sel].mean()))
    return out


@figure("seed003_fig2_cumulants")
def fig2_cumulants():
    path = pick("sonine_cumulants_fig2")
    alpha_line, pts = theory_alpha_line(path)
    c_line = np.array([p["sonine_c"] for p in pts])
    # the one-component first-Sonine value 2 a2 (granular-theory on a one-species namelist)
    text, _ = stored_input(path)
    one = re.sub(r"^\s*&system\b.*?^\s*/\s*$",
                 "&system\n  n_species = 1\n  mass = 1.0\n  diameter = 1.0\n  number_density = 0.01\n"
                 "  restitution = 0.5\n/", text, count=1, flags=re.S | re.M | re.I)
    one_pts = theory_sweep(None, "system:restitution", [f"{a:.2f}" for a in ALPHA_LINE], stored=(one, []))
    c_one = np.array([p["sonine_c"][0] for p in one_pts])

    fig, ax, ar = with_residuals(height=3.6)
    with h5py.File(path) as f:
        rows = []
        for value, g in sweep_points(f):
            _, c, dc = observable(g, "sonine_c")
            _, C, _ = observable(g, "collisions_per_particle")
            sel = C >= SCALING_START
            # mean over the scaling regime; the mean of the per-sample SEs bounds the SE of that mean
            rows.append((float(value), *c[sel].mean(axis=0), *dc[sel].mean(axis=0)))
    rows = np.array(rows)
    ax.plot(alpha_line, c_line[:, 0], "-", color="C0", label=r"$c_1$, first Sonine")
    ax.plot(alpha_line, c_line[:, 1], "--", color="C1", label=r"$c_2$, first Sonine")
    ax.plot(alpha_line, c_one, ":", color="C2", lw=1.5, label=r"one component $2a_2$, first Sonine")
    ax.errorbar(rows[:, 0], rows[:, 1], yerr=rows[:, 3], fmt="o", mfc="none", color="C0", label=r"$c_1$, DSMC")
    ax.errorbar(rows[:, 0], rows[:, 2], yerr=rows[:, 4], fmt="s", mfc="none", color="C1", label=r"$c_2$, DSMC")
    for i, (fmt, color) in enumerate((("o", "C0"), ("s", "C1"))):
        residuals(ar, rows[:, 0], rows[:, 1 + i], rows[:, 3 + i], line_at(alpha_line, c_line[:, i], rows[:, 0]),
                  kind="se", fmt=fmt, mfc="none", color=color)
    one_dsmc = one_component_dsmc()
    if one_dsmc:
        a = np.array(one_dsmc)
        ax.errorbar(a[:, 0], a[:, 1], yerr=a[:, 2], fmt="^", mfc="none", color="C2", label="one component, DSMC")
        residuals(ar, a[:, 0], a[:, 1], a[:, 2], line_at(alpha_line, c_one, a[:, 0]), kind="se", fmt="^",
                  mfc="none", color="C2")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set(ylabel=r"$c_i$", xlim=(0.1, 1.0))
    ar.set(xlabel=r"$\alpha$")
    ax.set_title(r"$\mu = 2$, $\delta = 1$, $w = 1$")
    ax.legend(ncol=2)
    save(fig, "seed003_fig2_cumulants")


@figure("seed003_fig3_delta")
def fig3_delta():
    path = pick("hcs_distribution_alpha0.5")
    d = reduced_distribution(path)
    lam = d["lam"]
    fig, axes, ars = with_residuals(ncols=2, width=PAGE, height=3.2)
    sonine = lambda v: 0.5 * lam**2 * v**4 - 2.5 * lam * v**2 + 15.0 / 8.0  # noqa: E731
    for ax, ar, vmax in ((axes[0], ars[0], 1.5), (axes[1], ars[1], 2.05)):  # (a): the paper's axes, v* to 1.5
        sel = d["v"] <= vmax
        x = np.linspace(0.0, vmax, 400)
        ax.plot(x, sonine(x), "k--", lw=1, label="first Sonine polynomial")
        ax.errorbar(d["v"][sel], d["delta"][sel], yerr=d["delta_error"][sel], fmt="o", mfc="none", color="C0",
                    label="DSMC")
        residuals(ar, d["v"][sel], d["delta"][sel], d["delta_error"][sel], sonine(d["v"][sel]), kind="se",
                  fmt="o", mfc="none", color="C0")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set(ylabel=r"$\Delta_1(v^*)$", xlim=(0.0, vmax))
        ar.set(xlabel=r"$v^*$")
        ax.legend(loc="upper left")
    axes[0].set_ylim(-1.6, max(3.2, 1.05 * sonine(1.5)))  # the paper's Delta_1 axis reaches the polynomial at 1.5
    axes[0].set_title("(a) thermal speeds, as printed")
    axes[1].set_title(r"(b) up to $v^* = 2$: the tail leaves the polynomial")
    fig.suptitle(f"$\\alpha = {d['alpha']:g}$, $\\mu = 4$, $\\delta = 1/2$, $w = 1$, $\\lambda_1 = {lam:.3f}$")
    save(fig, "seed003_fig3_delta")


def gamma_alpha_figure(cases, title, stem, log=False):
    fig, ax, ar = with_residuals(height=3.6)
    styles = {case: (label, ls, marker, color) for (case, label), (ls, marker), color
              in zip(cases, (("-", "o"), ("--", "s"), (":", "^")), ("C0", "C1", "C2"))}
    for case, path in pick_some(list(styles)):
        label, ls, marker, color = styles[case]
        alpha_line, pts = theory_alpha_line(path)
        g_line = [p["temperature_ratio"] for p in pts]
        ax.plot(alpha_line, g_line, ls, color=color, lw=1.2, label=f"{label}, first Sonine")
        rows = []
        with h5py.File(path) as f:
            for value, g in sweep_points(f):
                _, T, dT = observable(g, "temperature")
                rows.append((float(value), *gamma_of(T, dT, -1)))
        rows = np.array(rows)
        ax.errorbar(rows[:, 0], rows[:, 1], yerr=rows[:, 2], fmt=marker, mfc="none", color=color,
                    label=f"{label}, DSMC")
        residuals(ar, rows[:, 0], rows[:, 1], rows[:, 2], line_at(alpha_line, g_line, rows[:, 0]), kind="percent",
                  fmt=marker, mfc="none", color=color)
    ax.set(ylabel=r"$\gamma = T_1/T_2$", xlim=(0.1, 1.0))
    ar.set(xlabel=r"$\alpha$")
    ax.set_title(title)
    if log:  # gamma spans 0.1 .. 7 (mu = 1/10 .. 10)
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 3.0, 5.0)))
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.legend(ncol=2)
    save(fig, stem)


@figure("seed003_fig4_gamma_alpha_mu")
def fig4_gamma_mu():
    gamma_alpha_figure((("gamma_alpha_fig4_mu10", r"$\mu = 10$"), ("gamma_alpha_fig4_mu2", r"$\mu = 2$"),
                        ("gamma_alpha_fig4_mu0.1", r"$\mu = 1/10$")),
                       r"$\delta = 2$, $w = 1$, $n^* = 0$", "seed003_fig4_gamma_alpha_mu", log=True)


@figure("seed003_fig5_gamma_alpha_delta")
def fig5_gamma_delta():
    gamma_alpha_figure((("gamma_alpha_fig5_delta4", r"$\delta = 4$"), ("gamma_alpha_fig5_delta1", r"$\delta = 1$"),
                        ("gamma_alpha_fig5_delta0.25", r"$\delta = 1/4$")),
                       r"$\mu = 4$, $w = 1$, $n^* = 0$", "seed003_fig5_gamma_alpha_delta")


@figure("seed003_fig6_gamma_density")
def fig6_gamma_density():
    fig, ax, ar = with_residuals(height=3.6)
    styles = {"0.6": ("-", "o", "C0"), "0.8": ("--", "s", "C1")}
    for case, path in pick_some([f"gamma_density_alpha{alpha}" for alpha in styles]):
        ls, marker, color = styles[case[len("gamma_density_alpha"):]]
        with h5py.File(path) as f:
            sysp = f["parameters/system"].attrs
            alpha = f"{float(np.ravel(sysp['restitution'])[0]):g}"  # a user's run may have another one
            sigma12 = 0.5 * (sysp["diameter"][0] + sysp["diameter"][1])
            x1 = sysp["number_density"][0] / sum(sysp["number_density"])
            rows = []
            for value, g in sweep_points(f):
                n1, n2 = (float(s) for s in value.strip("'\" ").split(","))
                _, T, dT = observable(g, "temperature")
                rows.append(((n1 + n2) * sigma12**3, *gamma_of(T, dT, -1)))
        rows = np.array(rows)
        # gamma(alpha, 0): the theory's from the same mixture without the Enskog factors; the DSMC's from
        # its dilute run (gamma_density_alpha*_dilute), as the paper divides its measured gamma(n*)
        dilute = theory_sweep(path, "system:restitution", [alpha], extra=["system:enskog=.false."])
        g0 = dilute[0]["temperature_ratio"]
        dilute_path = pick_or_none(f"{case}_dilute")
        if dilute_path is None:
            m0, dm0, over = g0, 0.0, "dilute first Sonine"
        else:
            with h5py.File(dilute_path) as f:
                (_, g), = sweep_points(f)
                _, T, dT = observable(g, "temperature")
            m0, dm0 = gamma_of(T, dT, -1)
            over = "its dilute DSMC"
        ratio_err = rows[:, 1] / m0 * np.hypot(rows[:, 2] / rows[:, 1], dm0 / m0)
        nstar = np.round(np.arange(0.01, 0.5001, 0.01), 3)
        pairs = [f"'{x1 * s / sigma12**3:.7g}, {(1 - x1) * s / sigma12**3:.7g}'" for s in nstar]
        pts = theory_sweep(path, "system:number_density", pairs)
        ratio = np.array([p["temperature_ratio"] for p in pts]) / g0
        xl, yl = np.r_[0.0, nstar], np.r_[1.0, ratio]
        ax.plot(xl, yl, ls, color=color, lw=1.2, label=f"$\\alpha = {alpha}$, first Sonine (Enskog)")
        ax.errorbar(rows[:, 0], rows[:, 1] / m0, yerr=ratio_err, fmt=marker, mfc="none", color=color,
                    label=f"$\\alpha = {alpha}$, DSMC over {over}")
        residuals(ar, rows[:, 0], rows[:, 1] / m0, ratio_err, line_at(xl, yl, rows[:, 0]), kind="percent",
                  fmt=marker, mfc="none", color=color)
    ax.set(ylabel=r"$\gamma(\alpha, n^*)/\gamma(\alpha, 0)$", xlim=(0.0, 0.52))
    ar.set(xlabel=r"$n^* = n\sigma_{12}^3$")
    ax.set_title(r"$\mu = 2$, $\delta = 1/2$, $w = 2$")
    ax.legend()
    save(fig, "seed003_fig6_gamma_density")


@figure("seed003_fig7_tail")
def fig7_tail():
    # The Maxwellian lines are the contrast the flattening tail leaves: no residual panel.
    fig, ax = plt.subplots(figsize=(COLUMN, 2.8))
    styles = {"hcs_distribution_alpha0.3": ("s", "C1"), "hcs_distribution_alpha0.5": ("o", "C0")}
    for case, path in pick_some(list(styles)):
        marker, color = styles[case]
        d = reduced_distribution(path)
        alpha = f"{d['alpha']:g}"  # from the file: a user's run may have another restitution
        # bins where Phi_1 is measured (to 50 % or better): G_1 > 0 and its error bar stays above zero
        sel = (d["value"] > 0) & (d["error"] < 0.5 * d["value"])
        ax.errorbar(d["v"][sel], d["g"][sel], yerr=d["g_error"][sel], fmt=marker, mfc="none", color=color,
                    label=f"DSMC, $\\alpha = {alpha}$")
        x = np.linspace(0.0, d["v"][sel].max(), 400)
        g_mb = np.exp(2 * d["beta"] * x / d["zeta"]) * (d["lam"] / np.pi) ** 1.5 * np.exp(-d["lam"] * x * x)
        ax.plot(x, g_mb, "--", color=color, lw=1.1, label=f"Maxwellian, $\\alpha = {alpha}$")
    ax.set(xlabel=r"$v^*$", ylabel=r"$G_1(v^*)$", yscale="log")
    ax.set_title(r"$\mu = 4$, $\delta = 1/2$, $w = 1$, $n^* = 0$")
    ax.legend()
    save(fig, "seed003_fig7_tail")


if __name__ == "__main__":
    fc.main()
