#!/usr/bin/python3
"""Seed 003 (Montanero and Garzo 2002) Figs 1-7 from the validation outputs: DSMC points (replica mean
+- standard error) over the first-Sonine lines of `granular-theory` for the same mixture.

usage: /usr/bin/python3 paper-figures/seed003.py [BUILD_DIR] [OUT_DIR]
Reads BUILD_DIR/validation-output/*.h5 (written by `ctest -L validation`, paper tier preferred, quick tier
otherwise) and writes OUT_DIR/seed003_fig{1..7}_*.png (default OUT_DIR: paper-figures/out). The smooth
theory lines come from `granular-theory` on the stored namelist with a dense `&sweep` of its own
(temporary files only).
"""
import re

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figures_common import pick, tier, observable, stored_input, run_theory, theory, save  # noqa: E402


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


def fig1_gamma_time():
    path = pick("temperature_ratio_time")
    th = theory(path)["points"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    with h5py.File(path) as f:
        n = f["parameters/dsmc"].attrs["n_particles"]
        for k, (ax, (value, g)) in enumerate(zip(axes, sweep_points(f))):
            _, T, dT = observable(g, "temperature")
            _, C, _ = observable(g, "collisions_per_particle")
            gam = T[:, 0] / T[:, 1]
            err = gam * np.hypot(dT[:, 0] / T[:, 0], dT[:, 1] / T[:, 1])
            ax.errorbar(C, gam, yerr=err, fmt="o", ms=3.5, color="C0", capsize=2,
                        label=f"DSMC, N = {n}")
            gs = th[k]["temperature_ratio"]
            ax.axhline(gs, color="k", ls=":", lw=1.5, label=f"first Sonine HCS, gamma = {gs:.4f}")
            ax.set(xlabel="collisions per particle", ylabel="gamma(t) = T1 / T2",
                   title=f"({'ab'[k]}) alpha = {value}")
            if abs(gs - 1.0) < 1e-12:
                ax.set_ylim(0.96, 1.04)
            ax.legend(fontsize=8, loc="lower right" if gs > 1 else "upper right")
    fig.suptitle(f"Seed 003 Fig 1: gamma(t), mu = 10, delta = 2, w = 1, n* = 0 ({tier(path)})")
    save(fig, "seed003_fig1_gamma_time.png")


def one_component_dsmc():
    """2 a2 = c of one-species HCS runs in the validation outputs (seed 000's Haff cases), averaged past
    SCALING_START collisions per particle: [(alpha, c, se)]. Missing runs are skipped."""
    out = []
    for case in ("haff_cooling_alpha0.5", "haff_cooling_alpha0.9"):
        try:
            path = pick(case)
        except SystemExit:
            continue
        with h5py.File(path) as f:
            if "sonine_c" not in f["observables"]:
                continue
            alpha = f["parameters/system"].attrs["restitution"][0]
            _, c, dc = observable(f, "sonine_c")
            _, C, _ = observable(f, "collisions_per_particle")
        c, dc = np.ravel(c), np.ravel(dc)
        sel = C >= SCALING_START
        if sel.any():
            out.append((alpha, c[sel].mean(), dc[sel].mean()))
    return out


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

    fig, ax = plt.subplots(figsize=(6, 4.5))
    with h5py.File(path) as f:
        n = f["parameters/dsmc"].attrs["n_particles"]
        rows = []
        for value, g in sweep_points(f):
            _, c, dc = observable(g, "sonine_c")
            _, C, _ = observable(g, "collisions_per_particle")
            sel = C >= SCALING_START
            # mean over the scaling regime; the mean of the per-sample SEs bounds the SE of that mean
            rows.append((float(value), *c[sel].mean(axis=0), *dc[sel].mean(axis=0)))
    rows = np.array(rows)
    ax.plot(alpha_line, c_line[:, 0], "-", color="C0", label="c1, first Sonine")
    ax.plot(alpha_line, c_line[:, 1], "--", color="C1", label="c2, first Sonine")
    ax.plot(alpha_line, c_one, ":", color="C2", lw=1.8, label="one component 2 a2, first Sonine")
    ax.errorbar(rows[:, 0], rows[:, 1], yerr=rows[:, 3], fmt="o", color="C0", capsize=3,
                label=f"c1, DSMC (N = {n})")
    ax.errorbar(rows[:, 0], rows[:, 2], yerr=rows[:, 4], fmt="s", color="C1", capsize=3, label="c2, DSMC")
    one_dsmc = one_component_dsmc()
    if one_dsmc:
        a = np.array(one_dsmc)
        ax.errorbar(a[:, 0], a[:, 1], yerr=a[:, 2], fmt="^", color="C2", capsize=3,
                    label="one component, DSMC (seed 000 Haff runs)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set(xlabel="alpha", ylabel="c_i", xlim=(0.1, 1.0),
           title=f"Seed 003 Fig 2: c1, c2 vs alpha, mu = 2, delta = 1, w = 1 ({tier(path)})")
    ax.title.set_fontsize(10)
    ax.legend(fontsize=8)
    save(fig, "seed003_fig2_cumulants.png")


def reduced_distribution(path):
    with h5py.File(path) as f:
        g = f["observables/reduced_distribution"]
        s = g["species_1"]
        edges = g["bin_edges"][()]
        d = {k: s[k][()] for k in ("value", "error", "delta", "delta_error", "g", "g_error")}
        d.update(v=0.5 * (edges[1:] + edges[:-1]), lam=s.attrs["lambda"], c=s.attrs["sonine_c"],
                 beta=s.attrs["tail_beta"], zeta=g.attrs["cooling_rate_reduced"],
                 alpha=f["parameters/system"].attrs["restitution"][0],
                 n=f["parameters/dsmc"].attrs["n_particles"])
    return d


def fig3_delta():
    path = pick("hcs_distribution_alpha0.5")
    d = reduced_distribution(path)
    lam = d["lam"]
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 4.2))
    for ax, vmax in ((axes[0], 1.4), (axes[1], 2.05)):
        sel = d["v"] <= vmax
        x = np.linspace(0.0, vmax, 400)
        ax.plot(x, 0.5 * lam**2 * x**4 - 2.5 * lam * x**2 + 15.0 / 8.0, "k--",
                label="Sonine polynomial, eq 28")
        ax.errorbar(d["v"][sel], d["delta"][sel], yerr=d["delta_error"][sel], fmt="o", ms=3.5, color="C0",
                    capsize=2, label=f"DSMC, N = {d['n']}")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set(xlabel="v*", ylabel="Delta_1(v*)", xlim=(0.0, vmax))
        ax.legend(fontsize=8, loc="upper left")
    axes[0].set_ylim(-1.6, 3.2)
    axes[0].set_title("(a) thermal speeds (the paper's scale)", fontsize=10)
    axes[1].set_title("(b) up to v* = 2: the tail leaves eq 28", fontsize=10)
    fig.suptitle(f"Seed 003 Fig 3: Delta_1(v*), alpha = {d['alpha']:g}, mu = 4, delta = 1/2, w = 1 "
                 f"(lambda_1 = {lam:.3f}, {tier(path)})", fontsize=11)
    save(fig, "seed003_fig3_delta.png")


def gamma_alpha_figure(cases, title, filename, log=False):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (case, label), (ls, marker), color in zip(cases, (("-", "o"), ("--", "s"), (":", "^")), ("C0", "C1", "C2")):
        path = pick(case)
        alpha_line, pts = theory_alpha_line(path)
        ax.plot(alpha_line, [p["temperature_ratio"] for p in pts], ls, color=color, lw=1.6,
                label=f"{label}, first Sonine")
        rows = []
        with h5py.File(path) as f:
            for value, g in sweep_points(f):
                _, T, dT = observable(g, "temperature")
                rows.append((float(value), *gamma_of(T, dT, -1)))
        rows = np.array(rows)
        ax.errorbar(rows[:, 0], rows[:, 1], yerr=rows[:, 2], fmt=marker, color=color, capsize=3, ms=5,
                    label=f"{label}, DSMC ({tier(path)})")
    ax.set(xlabel="alpha", ylabel="gamma = T1 / T2", xlim=(0.1, 1.0), title=title)
    if log:  # gamma spans 0.1 .. 7 (mu = 1/10 .. 10)
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 3.0, 5.0)))
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.title.set_fontsize(10)
    ax.legend(fontsize=8, ncol=2)
    save(fig, filename)


def fig4_gamma_mu():
    gamma_alpha_figure((("gamma_alpha_fig4_mu10", "mu = 10"), ("gamma_alpha_fig4_mu2", "mu = 2"),
                        ("gamma_alpha_fig4_mu0.1", "mu = 1/10")),
                       "Seed 003 Fig 4: gamma vs alpha, delta = 2, w = 1, n* = 0",
                       "seed003_fig4_gamma_alpha_mu.png", log=True)


def fig5_gamma_delta():
    gamma_alpha_figure((("gamma_alpha_fig5_delta4", "delta = 4"), ("gamma_alpha_fig5_delta1", "delta = 1"),
                        ("gamma_alpha_fig5_delta0.25", "delta = 1/4")),
                       "Seed 003 Fig 5: gamma vs alpha, mu = 4, w = 1, n* = 0",
                       "seed003_fig5_gamma_alpha_delta.png")


def fig6_gamma_density():
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for alpha, ls, marker, color in (("0.6", "-", "o", "C0"), ("0.8", "--", "s", "C1")):
        path = pick(f"gamma_density_alpha{alpha}")
        with h5py.File(path) as f:
            sysp = f["parameters/system"].attrs
            sigma12 = 0.5 * (sysp["diameter"][0] + sysp["diameter"][1])
            x1 = sysp["number_density"][0] / sum(sysp["number_density"])
            rows = []
            for value, g in sweep_points(f):
                n1, n2 = (float(s) for s in value.strip("'\" ").split(","))
                _, T, dT = observable(g, "temperature")
                rows.append(((n1 + n2) * sigma12**3, *gamma_of(T, dT, -1)))
        rows = np.array(rows)
        # dilute first-Sonine gamma(alpha, 0): the same mixture without the Enskog factors
        dilute = theory_sweep(path, "system:restitution", [alpha], extra=["system:enskog=.false."])
        g0 = dilute[0]["temperature_ratio"]
        nstar = np.round(np.arange(0.01, 0.5001, 0.01), 3)
        pairs = [f"'{x1 * s / sigma12**3:.7g}, {(1 - x1) * s / sigma12**3:.7g}'" for s in nstar]
        pts = theory_sweep(path, "system:number_density", pairs)
        ratio = np.array([p["temperature_ratio"] for p in pts]) / g0
        ax.plot(np.r_[0.0, nstar], np.r_[1.0, ratio], ls, color=color, lw=1.6,
                label=f"alpha = {alpha}, first Sonine (Enskog)")
        ax.errorbar(rows[:, 0], rows[:, 1] / g0, yerr=rows[:, 2] / g0, fmt=marker, color=color, capsize=3,
                    label=f"alpha = {alpha}, DSMC / dilute Sonine ({tier(path)})")
    ax.set(xlabel="n* = n sigma_12^3", ylabel="gamma(alpha, n*) / gamma(alpha, 0)", xlim=(0.0, 0.52),
           title="Seed 003 Fig 6: gamma vs density, mu = 2, delta = 1/2, w = 2")
    ax.title.set_fontsize(10)
    ax.legend(fontsize=8)
    save(fig, "seed003_fig6_gamma_density.png")


def fig7_tail():
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for alpha, marker, color in (("0.3", "s", "C1"), ("0.5", "o", "C0")):
        path = pick(f"hcs_distribution_alpha{alpha}")
        d = reduced_distribution(path)
        # bins where Phi_1 is measured (to 50 % or better): G_1 > 0 and its error bar stays above zero
        sel = (d["value"] > 0) & (d["error"] < 0.5 * d["value"])
        ax.errorbar(d["v"][sel], d["g"][sel], yerr=d["g_error"][sel], fmt=marker, ms=3.5, color=color,
                    capsize=2, label=f"alpha = {alpha}, DSMC (N = {d['n']})")
        x = np.linspace(0.0, d["v"][sel].max(), 400)
        g_mb = np.exp(2 * d["beta"] * x / d["zeta"]) * (d["lam"] / np.pi) ** 1.5 * np.exp(-d["lam"] * x * x)
        ax.plot(x, g_mb, "--", color=color, lw=1.4, label=f"alpha = {alpha}, Maxwellian")
    ax.set(xlabel="v*", ylabel="G_1(v*)", yscale="log",
           title="Seed 003 Fig 7: G_1(v*), mu = 4, delta = 1/2, w = 1, n* = 0")
    ax.title.set_fontsize(10)
    ax.legend(fontsize=8)
    save(fig, "seed003_fig7_tail.png")


if __name__ == "__main__":
    fig1_gamma_time()
    fig2_cumulants()
    fig3_delta()
    fig4_gamma_mu()
    fig5_gamma_delta()
    fig6_gamma_density()
    fig7_tail()
