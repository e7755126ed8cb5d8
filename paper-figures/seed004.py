#!/usr/bin/python3
"""Seed 004 (Montanero) from the validation outputs: Fig 6, the shear viscosity eta/eta_0 of a
one-component granular gas against alpha in uniform shear flow with the Gaussian thermostat (DSMC, time
average over replicas +- standard error) over the first-Sonine theory of `granular-theory` for the
steady state the protocol measures (HSS) and, for contrast, the freely cooling gas (HCS); and Figs 1-5's
check, the HSS temperature ratio and cumulants against the HCS first-Sonine values.

usage: /usr/bin/python3 paper-figures/seed004.py [BUILD_DIR] [OUT_DIR]
Reads BUILD_DIR/validation-output/viscosity_alpha*.h5 and hss_*.h5 (ctest -L validation; paper tier
preferred, quick otherwise) and writes OUT_DIR/seed004_fig6_viscosity.png, seed004_fig7_9_mixtures.png
(eta/eta_0 against mass ratio, size ratio and concentration at alpha = 0.9, 0.8, 0.7, over the mixture
theory), seed004_fig10_12_enskog.png (Enskog binary mixture: kinetic and total eta/eta_0 against the solid
fraction, total against the mass ratio; one-component Enskog points beside them) and
seed004_fig1_5_hss.png (the HSS gamma and c against the HCS values).
"""

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figures_common import RUNS, Missing, pick, theory, save, tier  # noqa: E402


def fig6():
    alphas, eta, err, tiers = [], [], [], set()
    for alpha in ("1.0", "0.9", "0.8", "0.7", "0.6"):
        try:
            path = pick(f"viscosity_alpha{alpha}")
        except Missing:  # the quick tier has alpha = 1 and 0.7 only
            continue
        with h5py.File(path) as f:
            a = f["observables/shear_viscosity"].attrs
            alphas.append(float(f["parameters/system"].attrs["restitution"][0]))
            eta.append(a["time_average"])
            err.append(a["time_average_error"])
        tiers.add(tier(path))
    if not alphas:
        raise Missing(f"no viscosity outputs in {RUNS}")
    grid = np.linspace(0.5, 1.0, 26)
    hss, hcs = [], []
    for a in grid:
        th = theory(path, [f"system:restitution={a:.4f}"])
        hss.append(th["shear_viscosity_ratio"]["hss"])
        hcs.append(th["shear_viscosity_ratio"]["hcs"])
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.errorbar(alphas, eta, yerr=err, fmt="o", ms=4, label="DSMC, USF + thermostat")
    ax.plot(grid, hss, "-", label="first Sonine, HSS (ERRATA §10)")
    ax.plot(grid, hcs, "--", label="first Sonine, HCS (contrast)")
    ax.plot([1.0], [1.016], "k*", ms=8, label="converged Chapman-Enskog, alpha = 1")
    ax.set(xlabel="alpha", ylabel="eta / eta_0", title=f"Seed 004 Fig 6: shear viscosity ({', '.join(sorted(tiers))})")
    ax.legend(fontsize=8)
    save(fig, "seed004_fig6_viscosity.png")


def time_average(path):
    with h5py.File(path) as f:
        a = f["observables/shear_viscosity"].attrs
        return a["time_average"], a["time_average_error"], a.get("time_average_kinetic"), a.get("time_average_kinetic_error")


def fig7_9():
    panels = (("fig7_mu", (1.5, 3.0, 6.0, 10.0), "mass ratio m1/m2", "system:mass={x},1.0"),
              ("fig8_w", (1.5, 2.0), "size ratio sigma1/sigma2", "system:mass=1.0,1.0 system:diameter={x},1.0"),
              ("fig9_x", (0.25, 0.75), "concentration x1", None))
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    drawn = False
    for ax, (stem, xs, label, override) in zip(axes, panels):
        for k, alpha in enumerate(("0.9", "0.8", "0.7")):
            pts = []
            for x in xs:
                try:
                    path = pick(f"viscosity_{stem}{x}_alpha{alpha}")
                except Missing:
                    continue
                eta, err, _, _ = time_average(path)
                th = theory(path)["shear_viscosity_ratio"]["hss"]
                pts.append((x, eta, err, th))
            if not pts:
                continue
            drawn = True
            x, eta, err, th = map(np.array, zip(*pts))
            ax.errorbar(x, eta, yerr=err, fmt="o", ms=4, color=f"C{k}", label=f"DSMC, alpha = {alpha}")
            ax.plot(x, th, "--", color=f"C{k}", label="first Sonine HSS")
        ax.set(xlabel=label, ylabel="eta / eta_0 (elastic mixture)")
        ax.legend(fontsize=7)
    if drawn:
        fig.suptitle("Seed 004 Figs 7-9: shear viscosity of binary mixtures")
        save(fig, "seed004_fig7_9_mixtures.png")


def fig10_12():
    """Seed 004 Figs 10-12 are for a binary Enskog mixture (equal sizes and numbers): Fig 10 the kinetic
    part and Fig 11 the total viscosity against the solid fraction at mass ratio 4, Fig 12 the total
    against the mass ratio at phi = 0.2, each at alpha = 0.9, 0.8, 0.7. Drawn as eta/eta_0 over the
    elastic dilute mixture (seed 004's eta* = nu eta/(n T) is that times nu eta_0/n, which does not
    depend on phi), with the one-component Enskog points (alpha = 1, 0.8) in the first two panels."""
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    drawn = False
    phis = (0.1, 0.2, 0.3)
    grid = np.linspace(0.02, 0.32, 16)
    for k, alpha in enumerate(("0.9", "0.8", "0.7")):
        color = f"C{k}"
        pts = []
        for phi in phis:
            try:
                path = pick(f"viscosity_fig10_phi{phi}_alpha{alpha}")
            except Missing:
                continue
            pts.append((phi,) + tuple(time_average(path)))
        if pts:
            drawn = True
            phi, eta, err, kin, kin_err = map(np.array, zip(*pts))
            axes[0].errorbar(phi, kin, yerr=kin_err, fmt="s", color=color, label=f"DSMC, alpha = {alpha}")
            axes[1].errorbar(phi, eta, yerr=err, fmt="o", color=color, label=f"DSMC, alpha = {alpha}")
            kinetic, total = [], []
            for p in grid:
                n = 3.0 * p / np.pi  # each species: (pi/6) 2 n sigma^3 = phi
                th = theory(path, [f"system:restitution={alpha}", f"system:number_density={n:.6f},{n:.6f}"])
                kinetic.append(th["shear_viscosity_kinetic_ratio"]["hss"])
                total.append(th["shear_viscosity_ratio"]["hss"])
            axes[0].plot(grid, kinetic, "-", color=color)
            axes[1].plot(grid, total, "-", color=color, label="Enskog first Sonine, HSS" if k == 0 else None)
        pts = []
        for mu in ("2", "4", "8"):
            try:
                path = pick(f"viscosity_fig12_mu{mu}_alpha{alpha}" if mu != "4" else f"viscosity_fig10_phi0.2_alpha{alpha}")
            except Missing:
                continue
            eta, err, _, _ = time_average(path)
            pts.append((float(mu), eta, err))
        if pts:
            drawn = True
            mu, eta, err = map(np.array, zip(*pts))
            axes[2].errorbar(mu, eta, yerr=err, fmt="o", color=color, label=f"DSMC, alpha = {alpha}")
            mus = np.linspace(1.0, 9.0, 17)
            th = [theory(path, [f"system:restitution={alpha}", f"system:mass={m:.4f},1.0"])["shear_viscosity_ratio"]["hss"]
                  for m in mus]
            axes[2].plot(mus, th, "-", color=color)
    for name, alpha, marker in (("viscosity_enskog_phi0.1", "1.0", "^"), ("viscosity_enskog_phi0.2", "1.0", "^"),
                                ("viscosity_enskog_phi0.2_alpha0.8", "0.8", "v")):
        try:
            path = pick(name)
        except Missing:
            continue
        eta, err, kin, kin_err = time_average(path)
        phi = 0.1 if "phi0.1" in name else 0.2
        axes[0].errorbar([phi], [kin], yerr=[kin_err], fmt=marker, mfc="none", color="k")
        axes[1].errorbar([phi], [eta], yerr=[err], fmt=marker, mfc="none", color="k",
                         label=f"one species, alpha = {alpha}" if phi == 0.2 else None)
    axes[0].set(xlabel="solid fraction phi", ylabel="kinetic part eta_k / eta_0", title="Fig 10 (m1/m2 = 4)")
    axes[1].set(xlabel="solid fraction phi", ylabel="eta / eta_0", title="Fig 11 (m1/m2 = 4)")
    axes[2].set(xlabel="mass ratio m1/m2", ylabel="eta / eta_0", title="Fig 12 (phi = 0.2)")
    for ax in axes:
        ax.legend(fontsize=7)
    if drawn:
        fig.suptitle("Seed 004 Figs 10-12: shear viscosity of a dense (Enskog) binary mixture")
        save(fig, "seed004_fig10_12_enskog.png")


def fig1_5():
    fig, ax = plt.subplots(figsize=(5.5, 4))
    labels, measured, errors, expected = [], [], [], []
    for name in ("hss_one", "hss_binary"):
        try:
            path = pick(name)
        except Missing:
            continue
        th = theory(path)
        with h5py.File(path) as f:
            n = len(f["observables/sonine_c/time"][()])
            T = f["observables/temperature/value"][()].reshape(n, -1)
            c = f["observables/sonine_c/value"][()].reshape(n, -1)
            dc = f["observables/sonine_c/error"][()].reshape(n, -1)
        half = len(c) // 2
        for k in range(c.shape[1]):
            labels.append(f"{name} c_{k + 1}")
            measured.append(c[half:, k].mean())
            errors.append(dc[half:, k].mean())
            expected.append(th["sonine_c"][k])
        if T.shape[1] == 2:
            labels.append(f"{name} gamma/10")
            measured.append((T[half:, 0] / T[half:, 1]).mean() / 10)
            errors.append(0.0)
            expected.append(th["temperature_ratio"] / 10)
    if not labels:
        return
    x = np.arange(len(labels))
    ax.errorbar(x, measured, yerr=errors, fmt="o", label="DSMC, HSS (thermostat)")
    ax.plot(x, expected, "x", ms=8, label="first Sonine, HCS")
    ax.set_xticks(x, labels, rotation=30, fontsize=7)
    ax.set(title="Seed 004 Figs 1-5: HSS = HCS (gamma, c_i)")
    ax.legend(fontsize=8)
    save(fig, "seed004_fig1_5_hss.png")


if __name__ == "__main__":
    fig6()
    fig7_9()
    fig10_12()
    fig1_5()
