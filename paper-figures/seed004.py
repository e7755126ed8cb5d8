#!/usr/bin/python3
"""Seed 004 (Montanero): Fig 6, the shear viscosity eta/eta_0 of a one-component granular gas against
alpha in uniform shear flow with the Gaussian thermostat (DSMC, time average over replicas +- standard
error) over the first-Sonine theory of `granular-theory` for the steady state the protocol measures
(HSS) and, for contrast, the freely cooling gas (HCS); Figs 7-9, eta/eta_0 of mixtures against mass
ratio, size ratio and concentration at alpha = 0.9, 0.8, 0.7 over the mixture theory; Figs 10-12, the
Enskog binary mixture in the paper's units (kinetic part eta_k* and total eta* = nu eta/(n T) against
the solid fraction, eta* against the mass ratio); and Figs 1-5's check, the HSS temperature ratio and
cumulants against the HCS first-Sonine values, and Fig 2, Delta_1(v*) of the steady state against the
Sonine polynomial. Residual panels (DSMC/theory - 1 in percent, or DSMC
minus theory in standard errors) below each comparison.

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  seed004_fig6_viscosity    viscosity_alpha{1.0,0.9,0.8,0.7,0.6,0.5}
  seed004_fig7_9_mixtures   viscosity_fig7_mu{1.5,3.0,6.0,10.0}_alpha{0.9,0.8,0.7},
                            viscosity_fig8_w{1,2,3,4,5}_alpha{0.9,0.8,0.7} (mu = 4),
                            viscosity_fig9_d{2,3,4,5}_alpha{0.9,0.8,0.7} (mu = 4; delta = 1 is fig8_w1)
  seed004_fig10_12_enskog   viscosity_fig10_phi{0.1,0.2,0.3}_alpha{0.9,0.8,0.7},
                            viscosity_fig12_mu{2,8}_alpha{0.9,0.8,0.7} (in eta_k*, eta* as printed)
  seed004_fig1_5_hss        hss_one, hss_binary (the one-point check at alpha = 0.5)
  seed004_fig2_delta        hss_fig2_alpha0.5 (Delta_1(v*) of the HSS, mu = 4, delta = 1/2, as printed)
  seed004_fig1_5_curves     Figs 1, 3, 4, 5: hss_fig1_alpha{0.5,0.6,0.7,0.8,0.9},
                            hss_fig3_mu{0.1,2.0,10.0}_alpha{0.5,0.6,0.7,0.8,0.9},
                            hss_fig4_delta{0.25,1,4}_alpha{0.5,0.6,0.7,0.8,0.9},
                            hss_fig5_alpha{0.6,0.8}_phi{0,0.05,0.1,0.15,0.2,0.25}
Each figure is made from any of its cases; a panel left without DSMC data says so.
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import h5py
import matplotlib.pyplot as plt
import numpy as np
from figures_common import (COLUMN, PAGE, Missing, figure, pick, pick_or_none, reduced_distribution, theory, save,
                            with_residuals, residuals)


@figure("seed004_fig6_viscosity")
def fig6():
    alphas, eta, err, last = [], [], [], None
    for alpha in ("1.0", "0.9", "0.8", "0.7", "0.6", "0.5"):
        path = pick_or_none(f"viscosity_alpha{alpha}")
        if path is None:  # the quick tier has alpha = 1 and 0.7 only
            continue
        with h5py.File(path) as f:
            a = f["observables/shear_viscosity"].attrs
            alphas.append(float(np.ravel(f["parameters/system"].attrs["restitution"])[0]))
            eta.append(a["time_average"])
            err.append(a["time_average_error"])
        last = path
    if last is None:
        raise Missing("no shear viscosity outputs", case="viscosity_alpha1.0")
    grid = np.linspace(0.5, 1.0, 26)
    hss, hcs = [], []
    for a in grid:
        th = theory(last, [f"system:restitution={a:.4f}"])
        hss.append(th["shear_viscosity_ratio"]["hss"])
        hcs.append(th["shear_viscosity_ratio"]["hcs"])
    at_points = [theory(last, [f"system:restitution={a:.4f}"])["shear_viscosity_ratio"]["hss"] for a in alphas]
    fig, ax, ar = with_residuals()
    ax.errorbar(alphas, eta, yerr=err, fmt="o", mfc="none", color="C0", label="DSMC, sheared, thermostatted")
    ax.plot(grid, hss, "-", color="k", lw=1, label="first Sonine, steady state")
    ax.plot(grid, hcs, "--", color="0.5", lw=1, label="first Sonine, cooling state")
    ax.plot([1.0], [1.016], "*", color="C1", ms=7, label=r"converged Chapman-Enskog, $\alpha = 1$")
    residuals(ar, alphas, eta, err, at_points, kind="percent", fmt="o", mfc="none", color="C0")
    ax.set(ylabel=r"$\eta/\eta_0$")
    ar.set(xlabel=r"$\alpha$")
    ax.legend()
    save(fig, "seed004_fig6_viscosity")


def time_average(path):
    with h5py.File(path) as f:
        a = f["observables/shear_viscosity"].attrs
        return a["time_average"], a["time_average_error"], a.get("time_average_kinetic"), a.get("time_average_kinetic_error")


@figure("seed004_fig7_9_mixtures")
def fig7_9():
    """Figs 7-9: eta/eta_0 (over the elastic dilute mixture) against the mass ratio mu at equal sizes and
    numbers (Fig 7), and at mu = 4 against the size ratio omega = sigma1/sigma2 at equal numbers (Fig 8) and
    the concentration ratio delta = n1/n2 at equal sizes (Fig 9), at alpha = 0.9, 0.8, 0.7; the lines are
    the HSS first-Sonine theory over the paper's ranges."""
    def fig9_case(d):  # delta = 1 is Fig 8's omega = 1
        return "viscosity_fig8_w1" if d == 1 else f"viscosity_fig9_d{d}"

    def fig9_density(d):  # n1, n2 at total n = 0.01 (eta/eta_0 of a dilute gas does not depend on n)
        return f"system:number_density={0.01 * d / (1 + d):.6f},{0.01 / (1 + d):.6f}"

    panels = (("Fig. 7", (1.5, 3.0, 6.0, 10.0), lambda x: f"viscosity_fig7_mu{x}", r"mass ratio $\mu = m_1/m_2$",
               np.linspace(1.0, 10.0, 19), lambda x: [f"system:mass={x:.4f},1.0"]),
              ("Fig. 8", (1, 2, 3, 4, 5), lambda x: f"viscosity_fig8_w{x}", r"size ratio $\omega = \sigma_1/\sigma_2$",
               np.linspace(1.0, 5.0, 17), lambda x: [f"system:diameter={x:.4f},1.0"]),
              ("Fig. 9", (1, 2, 3, 4, 5), fig9_case, r"concentration ratio $\delta = n_1/n_2$",
               np.linspace(1.0, 5.0, 17), lambda x: [fig9_density(x)]))
    fig, axes, ars = with_residuals(ncols=3, width=PAGE, height=3.2)
    drawn = False
    empty = []  # (axes, the cases it lacks)
    for ax, ar, (title, xs, case, label, grid, at) in zip(axes, ars, panels):
        alphas = ("0.9", "0.8", "0.7")
        empty.append((ax, [f"{case(x)}_alpha{a}" for a in alphas for x in xs]))
        for k, (alpha, marker) in enumerate(zip(alphas, "os^")):
            pts = []
            for x in xs:
                path = pick_or_none(f"{case(x)}_alpha{alpha}")
                if path is None:
                    continue
                eta, err, _, _ = time_average(path)
                th = theory(path)["shear_viscosity_ratio"]["hss"]
                pts.append((float(x), eta, err, th))
            if not pts:
                continue
            drawn = True
            empty[-1] = None
            x, eta, err, th = map(np.array, zip(*pts))
            ax.errorbar(x, eta, yerr=err, fmt=marker, mfc="none", color=f"C{k}", label=f"DSMC, $\\alpha = {alpha}$")
            line = [theory(path, [f"system:restitution={alpha}"] + at(g))["shear_viscosity_ratio"]["hss"] for g in grid]
            ax.plot(grid, line, ("-", "--", ":")[k], color=f"C{k}", lw=1)  # the paper's solid, dashed, dotted
            residuals(ar, x, eta, err, th, kind="percent", fmt=marker, mfc="none", color=f"C{k}")
        ax.set_title(title + (r": $\omega = \delta = 1$" if title == "Fig. 7" else
                              r": $\mu = 4$, $\delta = 1$" if title == "Fig. 8" else r": $\mu = 4$, $\omega = 1$"))
        ar.set(xlabel=label)
        ar.set_ylabel("")
        ax.set(ylabel=r"$\eta/\eta_0$" if title == "Fig. 7" else "")
    if not drawn:
        plt.close(fig)
        raise Missing("no shear viscosity outputs of mixtures", case="viscosity_fig7_mu3.0_alpha0.9")
    for ax, cases in filter(None, empty):
        fc.no_dsmc(ax, cases, theory_drawn=False)
    ars[0].set_ylabel(fc.PERCENT_LABEL)
    axes[0].plot([], [], "k-", lw=1, label="first Sonine, steady state")
    axes[0].legend()
    save(fig, "seed004_fig7_9_mixtures")


@figure("seed004_fig10_12_enskog")
def fig10_12():
    """Seed 004 Figs 10-12 are for a binary Enskog mixture (equal sizes and numbers): Fig 10 the kinetic
    part and Fig 11 the total viscosity against the solid fraction at mass ratio 4, Fig 12 the total
    against the mass ratio at phi = 0.2, each at alpha = 0.9, 0.8, 0.7. Drawn as printed, in Montanero
    2003's units eta_k* and eta* = nu eta/(n T), nu = sqrt(pi) n sigma_12^2 v0: the DSMC's eta/eta_0 times
    nu eta_0/(n T) of its own mixture (granular-theory shear_viscosity_reduced over shear_viscosity_ratio,
    a number of the parameters only), the lines granular-theory's shear_viscosity_(kinetic_)reduced."""
    fig, axes, ars = with_residuals(ncols=3, width=PAGE, height=3.2)
    drawn = False
    filled = [False, False, False]  # the panels with DSMC points
    phis = (0.1, 0.2, 0.3)
    grid = np.linspace(0.005, 0.3, 14)

    def enskog_theory(path, alpha, phi=None, mu=None):
        """eta_k*, eta* and nu eta_0/(n T) of the first-Sonine HSS at (alpha, phi or the file's, mu or the file's)."""
        extra = [f"system:restitution={alpha}"]
        if phi is not None:
            n = 3.0 * phi / np.pi  # each species: (pi/6) 2 n sigma^3 = phi
            # (a shear rate that keeps a* small at every density: the theory's viscosity does not depend on it)
            extra += [f"system:number_density={n:.6f},{n:.6f}", "shear:rate=0.0001"]
        if mu is not None:
            extra.append(f"system:mass={mu:.4f},1.0")
        th = theory(path, extra)
        factor = th["shear_viscosity_reduced"]["hss"] / th["shear_viscosity_ratio"]["hss"]
        return th["shear_viscosity_kinetic_reduced"]["hss"], th["shear_viscosity_reduced"]["hss"], factor

    for k, (alpha, marker) in enumerate(zip(("0.9", "0.8", "0.7"), "os^")):
        color, style = f"C{k}", ("-", "--", ":")[k]  # the paper's solid, dashed, dotted lines
        pts = []
        for phi in phis:
            path = pick_or_none(f"viscosity_fig10_phi{phi}_alpha{alpha}")
            if path is None:
                continue
            eta, err, kin, kin_err = time_average(path)
            th_kin, th_tot, factor = enskog_theory(path, alpha)
            pts.append((phi, factor * eta, factor * err, factor * kin, factor * kin_err, th_kin, th_tot))
        if pts:
            drawn = filled[0] = filled[1] = True
            phi, eta, err, kin, kin_err, th_kin, th_tot = map(np.array, zip(*pts))
            axes[0].errorbar(phi, kin, yerr=kin_err, fmt=marker, mfc="none", color=color,
                             label=f"DSMC, $\\alpha = {alpha}$")
            axes[1].errorbar(phi, eta, yerr=err, fmt=marker, mfc="none", color=color)
            residuals(ars[0], phi, kin, kin_err, th_kin, kind="percent", fmt=marker, mfc="none", color=color)
            residuals(ars[1], phi, eta, err, th_tot, kind="percent", fmt=marker, mfc="none", color=color)
            lines = np.array([enskog_theory(path, alpha, phi=p)[:2] for p in grid])
            axes[0].plot(grid, lines[:, 0], style, color=color)
            axes[1].plot(grid, lines[:, 1], style, color=color)
        pts = []
        for mu in ("2", "4", "8"):
            path = pick_or_none(f"viscosity_fig12_mu{mu}_alpha{alpha}" if mu != "4" else f"viscosity_fig10_phi0.2_alpha{alpha}")
            if path is None:
                continue
            eta, err, _, _ = time_average(path)
            _, th_tot, factor = enskog_theory(path, alpha, mu=float(mu))
            pts.append((float(mu), factor * eta, factor * err, th_tot))
        if pts:
            drawn = filled[2] = True
            mu, eta, err, th_tot = map(np.array, zip(*pts))
            axes[2].errorbar(mu, eta, yerr=err, fmt=marker, mfc="none", color=color)
            residuals(ars[2], mu, eta, err, th_tot, kind="percent", fmt=marker, mfc="none", color=color)
            mus = np.linspace(1.0, 10.0, 19)
            axes[2].plot(mus, [enskog_theory(path, alpha, mu=m)[1] for m in mus], style, color=color)
    if not drawn:
        plt.close(fig)
        raise Missing("no Enskog mixture viscosity outputs", case="viscosity_fig10_phi0.2_alpha0.9")
    lacking = ([f"viscosity_fig10_phi{phi}_alpha{a}" for a in ("0.9", "0.8", "0.7") for phi in phis],) * 2 + \
        ([f"viscosity_fig12_mu{mu}_alpha{a}" for a in ("0.9", "0.8", "0.7") for mu in ("2", "8")],)
    for ax, has_points, cases in zip(axes, filled, lacking):
        if not has_points:
            fc.no_dsmc(ax, cases, theory_drawn=False)
    axes[0].set(ylabel=r"$\eta_k^* = \nu\eta_k/(nT)$")
    axes[0].set_title(r"Fig. 10: $\mu = 4$, $\omega = \delta = 1$")
    axes[1].set(ylabel=r"$\eta^* = \nu\eta/(nT)$")
    axes[1].set_title(r"Fig. 11: $\mu = 4$, $\omega = \delta = 1$")
    axes[2].set(ylabel=r"$\eta^*$")
    axes[2].set_title(r"Fig. 12: $\phi = 0.2$, $\omega = \delta = 1$")
    ars[0].set(xlabel=r"solid fraction $\phi$")
    ars[1].set(xlabel=r"solid fraction $\phi$")
    ars[2].set(xlabel=r"mass ratio $\mu = m_1/m_2$")
    for ar in ars[1:]:
        ar.set_ylabel("")
    axes[1].plot([], [], "k-", label="Enskog first Sonine, steady state")
    for ax in axes[:2]:
        ax.legend()
    save(fig, "seed004_fig10_12_enskog")


@figure("seed004_fig2_delta")
def fig2_delta():
    """Delta_1(v*) of the HSS (mu = 4, delta = 1/2, w = 1, alpha = 0.5) on the paper's axes, v* to 1.5 and
    Delta_1 from -2.5 to 10, against the first Sonine polynomial (Montanero and Garzo 2002, eq 28)."""
    d = reduced_distribution(pick("hss_fig2_alpha0.5"))
    lam = d["lam"]
    sonine = lambda v: 0.5 * lam**2 * v**4 - 2.5 * lam * v**2 + 15.0 / 8.0  # noqa: E731
    fig, ax, ar = with_residuals(height=3.4)
    sel = d["v"] <= 1.5
    x = np.linspace(0.0, 1.5, 400)
    ax.plot(x, sonine(x), "k--", lw=1, label="first Sonine polynomial")
    ax.errorbar(d["v"][sel], d["delta"][sel], yerr=d["delta_error"][sel], fmt="o", mfc="none", color="C0",
                label="DSMC, steady state")
    residuals(ar, d["v"][sel], d["delta"][sel], d["delta_error"][sel], sonine(d["v"][sel]), kind="se", fmt="o",
              mfc="none", color="C0")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set(ylabel=r"$\Delta_1(v^*)$", xlim=(0.0, 1.5), ylim=(-2.5, 10.0))
    ar.set(xlabel=r"$v^*$")
    ax.legend(loc="upper left")
    ax.set_title(f"$\\alpha = {d['alpha']:g}$, $\\mu = 4$, $\\delta = 1/2$, $w = 1$, $\\phi = 0$")
    save(fig, "seed004_fig2_delta")


@figure("seed004_fig1_5_hss")
def fig1_5():
    """The steady state under the thermostat against the cooling state's first-Sonine values: the
    cumulants (left) and the temperature ratio (right); the last half of the samples averaged."""
    rows_c, rows_g = [], []  # (tick label, DSMC, SE, first Sonine)
    for name in ("hss_one", "hss_binary"):
        path = pick_or_none(name)
        if path is None:
            continue
        th = theory(path)
        with h5py.File(path) as f:
            n = len(f["observables/sonine_c/time"][()])
            T = f["observables/temperature/value"][()].reshape(n, -1)
            dT = f["observables/temperature/error"][()].reshape(n, -1)
            c = f["observables/sonine_c/value"][()].reshape(n, -1)
            dc = f["observables/sonine_c/error"][()].reshape(n, -1)
        half = len(c) // 2
        for k in range(c.shape[1]):
            label = r"$c$, one species" if c.shape[1] == 1 else f"$c_{k + 1}$, binary"
            rows_c.append((label, c[half:, k].mean(), dc[half:, k].mean(), th["sonine_c"][k]))
        if T.shape[1] == 2:
            g = T[half:, 0] / T[half:, 1]
            dg = g * np.hypot(dT[half:, 0] / T[half:, 0], dT[half:, 1] / T[half:, 1])
            rows_g.append((r"$\gamma = T_1/T_2$, binary", g.mean(), dg.mean(), th["temperature_ratio"]))
    if not rows_c:
        raise Missing("no steady-state outputs", case="hss_one")
    fig, axes, ars = with_residuals(ncols=2, width=COLUMN * 1.6, height=3.0, sharex=False)
    for ax, ar, rows in zip(axes, ars, (rows_c, rows_g)):
        if not rows:  # only the temperature ratio of the binary can be missing here
            fc.no_dsmc(ax, "hss_binary", theory_drawn=False)
            ar.set_visible(False)
            continue
        labels, y, dy, th = zip(*rows)
        x = np.arange(len(rows))
        ax.errorbar(x, y, yerr=dy, fmt="o", mfc="none", color="C0", label="DSMC, steady state")
        ax.plot(x, th, "x", color="k", ms=6, label="first Sonine, cooling state")
        residuals(ar, x, y, dy, th, kind="se", fmt="o", mfc="none", color="C0")
        ar.set_xticks(x, labels)
        ax.set_xticks(x)
        ax.set_xlim(-0.5, len(rows) - 0.5)
        ar.set_xlim(-0.5, len(rows) - 0.5)
        ax.minorticks_off()
        ar.minorticks_off()
    axes[0].set(ylabel="cumulant")
    axes[1].set(ylabel="temperature ratio")
    ars[1].set_ylabel("")
    axes[0].legend()
    save(fig, "seed004_fig1_5_hss")


def hss_state(path):
    """(c_1, c_2, their SE, gamma = T1/T2, its SE) of an HSS run: each replica's average past scaling_start,
    SE over the replicas (/observables/scaling_state); gamma = x2 s1/(1 - x1 s1) from s1 = T_1/T."""
    with h5py.File(path) as f:
        g = f["observables/scaling_state"]
        c, dc = g["sonine_c"][()], g["sonine_c_error"][()]
        s1, ds1 = g["temperature_over_mean"][0], g["temperature_over_mean_error"][0]
        n = np.ravel(f["parameters/system"].attrs["number_density"])
    x1, x2 = n[0] / n.sum(), n[1] / n.sum()
    return c, dc, x2 * s1 / (1 - x1 * s1), x2 / (1 - x1 * s1) ** 2 * ds1


@figure("seed004_fig1_5_curves")
def fig1_5_curves():
    """Figs 1, 3, 4 and 5 as printed, in the steady state under the thermostat (its c_i and gamma are the
    cooling state's): (1) c_1, c_2 against alpha at mu = 2, omega = delta = 1, with the one-component c;
    (3) gamma against alpha at omega = 1, delta = 2 for mu = 1/10, 2, 10; (4) gamma against alpha at mu = 4,
    omega = 1 for delta = 1/4, 1, 4; (5) gamma(alpha, phi)/gamma(alpha, 0) against the packing fraction at
    mu = omega = 2, delta = 1/2 (Enskog), alpha = 0.6, 0.8, the DSMC over its own phi = 0 run. Lines: first
    Sonine (granular-theory); residuals DSMC/theory - 1 in percent (Fig 1: in standard errors, as c
    crosses zero)."""
    alphas = ("0.5", "0.6", "0.7", "0.8", "0.9")
    grid = np.linspace(0.5, 1.0, 11)
    styles = (("^", ":"), ("s", "--"), ("o", "-"))  # the paper's triangles dotted, squares dashed, circles solid
    fig, axes, ars = with_residuals(ncols=4, width=PAGE * 1.25, height=3.3)
    empty = []

    def curve(ax, ar, cases, value, line, k, label, kind="percent"):
        """DSMC points of `cases` (alpha -> case) and the theory line over `grid`; value(path) -> (y, dy)."""
        marker, style = styles[k]
        pts, last = [], None
        for a in alphas:
            path = pick_or_none(cases(a))
            if path is None:
                continue
            y, dy = value(path)
            pts.append((float(a), y, dy, line(path, float(a))))
            last = path
        if last is None:
            return False
        ax.plot(grid, [line(last, a) for a in grid], style, color=f"C{k}", lw=1)
        x, y, dy, th = map(np.array, zip(*pts))
        ax.errorbar(x, y, yerr=dy, fmt=marker, mfc="none", color=f"C{k}", label=label)
        residuals(ar, x, y, dy, th, kind=kind, fmt=marker, mfc="none", color=f"C{k}")
        return True

    def theory_at(path, alpha, key, index=None, extra=()):
        th = theory(path, [f"system:restitution={alpha:.4f}", *extra])
        return th[key] if index is None else th[key][index]

    # Fig 1
    drawn = False
    for k, (species, sty) in enumerate(((0, 2), (1, 1))):
        drawn |= curve(axes[0], ars[0], lambda a: f"hss_fig1_alpha{a}",
                       lambda p, i=species: (hss_state(p)[0][i], hss_state(p)[1][i]),
                       lambda p, a, i=species: theory_at(p, a, "sonine_c", i), sty, f"$c_{species + 1}$", kind="se")
    if drawn:
        one = ["system:n_species=1", "system:mass=1.0", "system:diameter=1.0", "system:number_density=0.03",
               "initial:temperature=1.0"]
        path = pick("hss_fig1_alpha0.5")
        axes[0].plot(grid, [theory(path, [f"system:restitution={a:.4f}", *one])["hcs"]["first_sonine"]["sonine_c"][0]
                            for a in grid], ":", color="C0", lw=1, label="one component")
    else:
        empty.append((axes[0], [f"hss_fig1_alpha{a}" for a in alphas]))
    axes[0].set(ylabel=r"$c_i$", title=r"Fig. 1: $\mu = 2$, $\omega = \delta = 1$")
    # Figs 3 and 4
    for ax, ar, title, variants in (
            (axes[1], ars[1], r"Fig. 3: $\omega = 1$, $\delta = 2$",
             (("mu0.1", r"$\mu = 1/10$"), ("mu2.0", r"$\mu = 2$"), ("mu10.0", r"$\mu = 10$"))),
            (axes[2], ars[2], r"Fig. 4: $\mu = 4$, $\omega = 1$",
             (("delta0.25", r"$\delta = 1/4$"), ("delta1", r"$\delta = 1$"), ("delta4", r"$\delta = 4$")))):
        stem = "hss_fig3_" if title.startswith("Fig. 3") else "hss_fig4_"
        drawn = False
        for k, (tag, label) in enumerate(variants):
            drawn |= curve(ax, ar, lambda a, t=tag: f"{stem}{t}_alpha{a}", lambda p: hss_state(p)[2:],
                           lambda p, a: theory_at(p, a, "temperature_ratio"), k, label)
        if not drawn:
            empty.append((ax, [f"{stem}{t}_alpha{a}" for t, _ in variants for a in alphas]))
        ax.set(ylabel=r"$\gamma = T_1/T_2$", title=title)
    # Fig 5
    phis = ("0.05", "0.1", "0.15", "0.2", "0.25")
    drawn = False
    for k, alpha in ((2, "0.6"), (1, "0.8")):
        marker, style = styles[k]
        dilute_run = pick_or_none(f"hss_fig5_alpha{alpha}_phi0")
        if dilute_run is None:
            continue
        _, _, g0, dg0 = hss_state(dilute_run)
        pts = []
        for phi in phis:
            path = pick_or_none(f"hss_fig5_alpha{alpha}_phi{phi}")
            if path is None:
                continue
            _, _, g, dg = hss_state(path)
            dilute = theory(path, ["system:enskog=.false."])["temperature_ratio"]
            pts.append((float(phi), g / g0, g / g0 * np.hypot(dg / g, dg0 / g0),
                        theory(path)["temperature_ratio"] / dilute))
        if not pts:
            continue
        drawn = True
        x, y, dy, th = map(np.array, zip(*pts))
        line = []
        for p in np.linspace(0.01, 0.25, 13):
            n2 = 6 * p / (5 * np.pi)
            dens = [f"system:number_density={n2 / 2:.6f},{n2:.6f}"]
            line.append(theory(path, dens)["temperature_ratio"] / theory(path, dens + ["system:enskog=.false."])["temperature_ratio"])
        axes[3].plot(np.linspace(0.01, 0.25, 13), line, style, color=f"C{k}", lw=1)
        axes[3].errorbar(x, y, yerr=dy, fmt=marker, mfc="none", color=f"C{k}", label=f"$\\alpha = {alpha}$")
        residuals(ars[3], x, y, dy, th, kind="percent", fmt=marker, mfc="none", color=f"C{k}")
    if not drawn:
        empty.append((axes[3], [f"hss_fig5_alpha{a}_phi{p}" for a in ("0.6", "0.8") for p in ("0",) + phis]))
    axes[3].set(ylabel=r"$\gamma(\alpha, \phi)/\gamma(\alpha, 0)$", title=r"Fig. 5: $\mu = \omega = 2$, $\delta = 1/2$")
    if len(empty) == 4:
        plt.close(fig)
        raise Missing("no steady-state curves", case="hss_fig1_alpha0.5")
    for ax, cases in empty:
        fc.no_dsmc(ax, cases, theory_drawn=False)
    for ar in ars[:3]:
        ar.set(xlabel=r"$\alpha$")
    ars[3].set(xlabel=r"solid fraction $\phi$")
    for ar in ars[1:]:
        ar.set_ylabel("")
    for ax in axes:
        ax.legend(fontsize="small")
    save(fig, "seed004_fig1_5_curves")


if __name__ == "__main__":
    fc.main()
