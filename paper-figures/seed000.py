#!/usr/bin/python3
"""Seed 000 Figs 1-6 from the validation outputs: DSMC points (replica mean +- standard error) over
the theory lines of `granular-theory` for the same input.

usage: /usr/bin/python3 paper-figures/seed000.py [BUILD_DIR] [OUT_DIR]
Reads BUILD_DIR/validation-output/*.h5 (written by `ctest -L validation`, paper tier preferred,
quick tier otherwise) and writes OUT_DIR/seed000_fig{1..6}.png (default OUT_DIR: paper-figures/out).
"""

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figures_common import pick, observable, theory, save  # noqa: E402


def haff_figures():
    fig_t, ax_t = plt.subplots(figsize=(5.5, 4))
    fig_c, ax_c = plt.subplots(figsize=(5.5, 4))
    for alpha, color in (("0.9", "C0"), ("0.5", "C1")):
        path = pick(f"haff_cooling_alpha{alpha}")
        th = theory(path)
        with h5py.File(path) as f:
            t, T, dT = observable(f, "total_temperature")
            _, C, dC = observable(f, "collisions_per_particle")
            n = f["parameters/dsmc"].attrs["n_particles"]
        ax_t.errorbar(t[1:], T[1:], yerr=dT[1:], fmt="o", ms=3, color=color, label=f"DSMC, alpha = {alpha}, N = {n}")
        tt, TT = np.array(th["temperature"]["time"]), np.array(th["temperature"]["value"])[:, 0]
        ax_t.plot(tt[1:], TT[1:], "-", color=color, label="Haff's law (ERRATA §3)")
        ax_c.errorbar(T, C, yerr=dC, fmt="o", ms=3, color=color, label=f"DSMC, alpha = {alpha}")
        ax_c.plot(TT, th["collisions_per_particle"]["value"], "-", color=color, label="eq 36 along Haff")
    ax_t.set(xscale="log", yscale="log", xlabel="t", ylabel="T(t) / T0", title="Seed 000 Figs 1, 3: Haff cooling")
    ax_t.legend(fontsize=8)
    ax_c.set(xscale="log", xlabel="T / T0", ylabel="collisions per particle",
             title="Seed 000 Figs 2, 4: collisions against temperature")
    ax_c.legend(fontsize=8)
    save(fig_t, "seed000_fig1_fig3_haff.png")
    save(fig_c, "seed000_fig2_fig4_collisions.png")


def velocity_figure():
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for case, marker in (("velocity_shell", "o"), ("velocity_cube", "s")):
        path = pick(case)
        with h5py.File(path) as f:
            g = f["observables/velocity_histogram"]
            edges = g["bin_edges"][()]
            h = g["species_1/value"][()]
            err = g["species_1/error"][()] if "error" in g["species_1"] else None
        mid = 0.5 * (edges[1:] + edges[:-1])
        ax.errorbar(mid, h[-1], yerr=None if err is None else err[-1], fmt=marker, ms=3,
                    label=f"DSMC, start '{case.split('_')[1]}', end of run")
        ax.plot(mid, h[0], ":", lw=1, label=f"start '{case.split('_')[1]}', t = 0")
    x = np.linspace(edges[0], edges[-1], 400)
    ax.plot(x, np.exp(-x * x / 2) / np.sqrt(2 * np.pi), "k-", label="Maxwellian")
    ax.set(xlabel="v_x / sqrt(T/m)", ylabel="probability density", yscale="log", ylim=(1e-6, 1),
           title="Seed 000 Fig 5: velocity distribution (elastic)")
    ax.legend(fontsize=8)
    save(fig, "seed000_fig5_velocity.png")


def polydisperse_figure():
    path = pick("polydisperse")
    th = theory(path)
    fig, ax = plt.subplots(figsize=(5.5, 4))
    with h5py.File(path) as f:
        t, T, dT = observable(f, "temperature")
        masses = f["parameters/system"].attrs["mass"]
    tt, TT = np.array(th["temperature"]["time"]), np.array(th["temperature"]["value"])
    for k in range(T.shape[1]):
        ax.errorbar(t[1:], T[1:, k], yerr=dT[1:, k], fmt="o", ms=3, color=f"C{k}", label=f"DSMC, m = {masses[k]:g}")
        ax.plot(tt[1:], TT[1:, k], "-", color=f"C{k}", label="ODE (ERRATA §4, CVODE)")
    ax.set(xscale="log", yscale="log", xlabel="t", ylabel="T_k(t)", title="Seed 000 Fig 6: polydisperse cooling")
    ax.legend(fontsize=8)
    save(fig, "seed000_fig6_polydisperse.png")


if __name__ == "__main__":
    haff_figures()
    velocity_figure()
    polydisperse_figure()
