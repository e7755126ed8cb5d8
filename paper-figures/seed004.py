#!/usr/bin/python3
"""Seed 004 (Montanero) from the validation outputs: Fig 6, the shear viscosity eta/eta_0 of a
one-component granular gas against alpha in uniform shear flow with the Gaussian thermostat (DSMC, time
average over replicas +- standard error) over the first-Sonine theory of `granular-theory` for the
steady state the protocol measures (HSS) and, for contrast, the freely cooling gas (HCS); and Figs 1-5's
check, the HSS temperature ratio and cumulants against the HCS first-Sonine values.

usage: /usr/bin/python3 paper-figures/seed004.py [BUILD_DIR] [OUT_DIR]
Reads BUILD_DIR/validation-output/viscosity_alpha*.h5 and hss_*.h5 (ctest -L validation; paper tier
preferred, quick otherwise) and writes OUT_DIR/seed004_fig6_viscosity.png.
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


if __name__ == "__main__":
    fig6()
