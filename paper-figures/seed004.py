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
theory), seed004_fig10_12_enskog.png (Enskog: total and kinetic eta/eta_0 against the solid fraction) and
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
    cases = (("viscosity_alpha1.0", 0.0, "1.0"), ("viscosity_enskog_phi0.1", 0.1, "1.0"),
             ("viscosity_enskog_phi0.2", 0.2, "1.0"), ("viscosity_enskog_phi0.2_alpha0.8", 0.2, "0.8"))
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for name, phi, alpha in cases:
        try:
            path = pick(name)
        except Missing:
            continue
        eta, err, kin, kin_err = time_average(path)
        color = "C0" if alpha == "1.0" else "C1"
        ax.errorbar([phi], [eta], yerr=[err], fmt="o", color=color)
        if kin is not None:
            ax.errorbar([phi], [kin], yerr=[kin_err], fmt="s", mfc="none", color=color)
    grid = np.linspace(0.01, 0.25, 13)
    try:
        path = pick("viscosity_enskog_phi0.2")
        for alpha, color in (("1.0", "C0"), ("0.8", "C1")):
            tot = [theory(path, [f"system:restitution={alpha}", f"system:number_density={6 * p / np.pi:.6f}"])
                   ["shear_viscosity_ratio"]["hss"] for p in grid]
            ax.plot(grid, tot, "-", color=color, label=f"Enskog first Sonine, total, alpha = {alpha}")
    except Missing:
        pass
    ax.set(xlabel="solid fraction phi", ylabel="eta / eta_0",
           title="Seed 004 Figs 10-12: Enskog (circles total, squares kinetic)")
    ax.legend(fontsize=7)
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
