#!/usr/bin/python3
"""Aggregation and fragmentation (seed 000 eqs 8-14, ERRATA §12) from the validation outputs: DSMC
points (replica mean +- standard error) over the Smoluchowski rate equations of `granular-theory` for
the same input, for pure sticking, rare reactions in a nearly elastic gas, and the full model.

usage: /usr/bin/python3 paper-figures/agg_frag.py [BUILD_DIR] [OUT_DIR]
Reads BUILD_DIR/validation-output/agg_frag_{sticking,rare,full}*.h5 (ctest -L validation; paper tier
preferred, quick otherwise) and writes OUT_DIR/agg_frag_<case>.png: N_k(t) for k = 1..4, the monomer
fraction, the mean cluster size <k> and the temperature per cluster T(t).
"""

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figures_common import pick, observable, theory, save, tier  # noqa: E402

CASES = (("sticking", "pure sticking"), ("rare", "rare reactions, alpha = 0.99"), ("full", "full model"))


def figure(case, title):
    path = pick(f"agg_frag_{case}")
    th = theory(path)
    with h5py.File(path) as f:
        t, number, dnumber = observable(f, "number")
        _, mono, dmono = observable(f, "monomer_fraction")
        _, size, dsize = observable(f, "mean_size")
        _, temp, dtemp = observable(f, "total_temperature")
        n0 = f["parameters/dsmc"].attrs["n_particles"]
    tt = np.array(th["number"]["time"])
    tn = np.array(th["number"]["value"])
    fig, axes = plt.subplots(2, 2, figsize=(9, 7))
    ax = axes[0, 0]
    for k in range(min(4, number.shape[1])):
        ax.errorbar(t[1:], number[1:, k] / n0, yerr=dnumber[1:, k] / n0, fmt="o", ms=3, color=f"C{k}",
                    label=f"DSMC, k = {k + 1}")
        if k < tn.shape[1]:
            ax.plot(tt[1:], tn[1:, k] / n0, "-", color=f"C{k}")
    ax.set(xscale="log", yscale="log", xlabel="t", ylabel="N_k / N_0", title="clusters of size k (lines: theory)")
    ax.legend(fontsize=7)
    for ax, (y, dy, key, label) in zip(
        (axes[0, 1], axes[1, 0], axes[1, 1]),
        ((mono, dmono, "monomer_fraction", "N_1 / N_0"), (size, dsize, "mean_size", "<k> = N_0 / N"),
         (temp, dtemp, "total_temperature", "T per cluster"))):
        ax.errorbar(t[1:], y[1:], yerr=dy[1:], fmt="o", ms=3, label="DSMC")
        ax.plot(th[key]["time"][1:], th[key]["value"][1:], "-", label="Smoluchowski, Maxwellian kernels")
        ax.set(xscale="log", xlabel="t", ylabel=label)
        ax.legend(fontsize=7)
    fig.suptitle(f"Aggregation and fragmentation: {title} (N_0 = {n0}, {tier(path)})")
    save(fig, f"agg_frag_{case}.png")


if __name__ == "__main__":
    for case, title in CASES:
        figure(case, title)
