#!/usr/bin/python3
"""The figure of a tutorial, from the files its commands wrote (examples/NN-name/README.md, "Running it").

usage: /usr/bin/python3 ../plot_tutorial.py      (inside examples/NN-name, after running the tutorial)
       /usr/bin/python3 plot_tutorial.py DIR      (DIR: a folder holding the outputs of tutorial NN-name,
                                                   named like the tutorial folder, e.g. 01-haff-cooling)
Writes results-NN.png in that folder: DSMC points (mean +- standard error over replicas) over the theory
lines of granular-theory. Needs h5py, numpy and matplotlib (Debian: python3-h5py, python3-matplotlib).
"""

import json
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def obs(f, name, group="/observables"):
    g = f[f"{group}/{name}"]
    value = g["value"][()]
    err = g["error"][()] if "error" in g else np.zeros_like(value)
    if value.ndim == 1 and name in ("temperature", "sonine_c", "msd", "number"):  # Nt x S with S = 1
        value, err = value[:, None], err[:, None]
    return g["time"][()], value, err


def theory(path):
    with open(path) as f:
        return json.load(f)


def curve(th, key, col=None):
    t = np.array(th[key]["time"])
    v = np.array(th[key]["value"])
    return t, (v[:, col] if col is not None else v)


def haff(ax):
    th = theory("theory.json")
    with h5py.File("haff-cooling.h5") as f:
        t, T, dT = obs(f, "total_temperature")
        _, C, dC = obs(f, "collisions_per_particle")
    z0, zs, T0 = th["cooling_rate"][0], th["cooling_rate_sonine"][0], 1.0
    tt = np.geomspace(t[1], t[-1], 200)
    ax[0].errorbar(t[1:], T[1:], dT[1:], fmt="o", ms=3, label="DSMC")
    ax[0].plot(tt, T0 / (1 + z0 * tt / 2) ** 2, "k-", lw=1, label="Haff, Maxwellian rate")
    ax[0].plot(tt, T0 / (1 + zs * tt / 2) ** 2, "r--", lw=1, label="Haff, first-Sonine rate")
    ax[0].set(xscale="log", yscale="log", xlabel="t", ylabel="T")
    ax[1].errorbar(t[1:], (T[1:] * (1 + z0 * t[1:] / 2) ** 2 - 1) * 100, dT[1:] * (1 + z0 * t[1:] / 2) ** 2 * 100,
                   fmt="o", ms=3, label="DSMC")
    ax[1].plot(tt, ((1 + z0 * tt / 2) ** 2 / (1 + zs * tt / 2) ** 2 - 1) * 100, "r--", lw=1,
               label="first-Sonine rate")
    ax[1].axhline(0, color="k", lw=1)
    ax[1].set(xscale="log", xlabel="t", ylabel="T / T_Haff,Maxwell - 1 [%]")


def binary(ax):
    th = theory("theory.json")
    with h5py.File("binary-hcs.h5") as f:
        _, T, dT = obs(f, "temperature")
        _, C, _ = obs(f, "collisions_per_particle")
        _, c, dc = obs(f, "sonine_c")
    g = T[:, 0] / T[:, 1]
    dg = g * np.hypot(dT[:, 0] / T[:, 0], dT[:, 1] / T[:, 1])
    ax[0].errorbar(C, g, dg, fmt="o", ms=3, label="DSMC")
    ax[0].axhline(th["temperature_ratio"], color="r", ls="--", lw=1, label="first Sonine")
    tm = th["hcs"]["maxwellian"]["temperature_over_mean"]
    ax[0].axhline(tm[0] / tm[1], color="k", lw=1, label="Maxwellian")
    ax[0].set(xlabel="collisions per particle", ylabel="gamma = T1/T2")
    for i, color in ((0, "C0"), (1, "C1")):
        ax[1].errorbar(C, c[:, i], dc[:, i], fmt="o", ms=3, color=color, label=f"DSMC c{i + 1}")
        ax[1].axhline(th["sonine_c"][i], color=color, ls="--", lw=1, label=f"first Sonine c{i + 1}")
    ax[1].set(xlabel="collisions per particle", ylabel="c_i")


def polydisperse(ax):
    th = theory("theory.json")
    with h5py.File("polydisperse.h5") as f:
        t, T, dT = obs(f, "temperature")
        _, Tt, dTt = obs(f, "total_temperature")
    tt, TT = curve(th, "total_temperature")
    for k, color in ((0, "C0"), (9, "C1"), (49, "C2"), (199, "C3")):
        _, Tk = curve(th, "temperature", k)
        ax[0].errorbar(t[1:], T[1:, k] / Tt[1:], dT[1:, k] / Tt[1:], fmt="o", ms=3, color=color,
                       label=f"k = {k + 1}")
        ax[0].plot(tt[1:], Tk[1:] / TT[1:], color=color, lw=1)
    ax[0].set(xscale="log", xlabel="t", ylabel="T_k / T (lines: ODEs)")
    k = np.arange(1, T.shape[1] + 1)
    ax[1].errorbar(k, T[-1] / Tt[-1], dT[-1] / Tt[-1], fmt="o", ms=2, label=f"DSMC, t = {t[-1]:g}")
    ax[1].plot(k, np.array(th["temperature"]["value"])[-1] / TT[-1], "k-", lw=1, label="ODEs")
    ax[1].plot(k, th["hcs"]["first_sonine"]["temperature_over_mean"], "r--", lw=1, label="HCS, first Sonine")
    ax[1].set(xscale="log", xlabel="species k (m_k = k m_1)", ylabel="T_k / T")


def msd(ax):
    independent = {10: (33.46, 2.490), 100: (120.9, 83.68), 1000: (308.8, 445.7)}
    for a, h5, js, title in ((ax[0], "msd-binary.h5", "theory.json", "alpha = 0.5"),
                             (ax[1], "msd-viscoelastic.h5", "theory-visco.json", "viscoelastic")):
        th = theory(js)
        with h5py.File(h5) as f:
            t, R, dR = obs(f, "msd")
        for i, color in ((0, "C0"), (1, "C1")):
            tt, RR = curve(th, "msd", i)
            a.errorbar(t[1:], R[1:, i], dR[1:, i], fmt="o", ms=4, color=color, label=f"DSMC, m = {(1, 100)[i]}")
            a.plot(tt[1:], RR[1:], color=color, lw=1, label="eq. (17)" if i == 0 else None)
            if h5 == "msd-binary.h5":
                a.plot(list(independent), [v[i] for v in independent.values()], "x", color="k",
                       label="independent DSMC" if i == 0 else None)
        a.set(xscale="log", yscale="log", xlabel="t", ylabel="<R_k^2>", title=title)


def sweep(ax):
    th = theory("theory.json")
    path = "serial/sweep.h5" if os.path.exists("serial/sweep.h5") else "sweep.h5"
    alphas, cs, es = [], [], []
    with h5py.File(path) as f:
        for k in range(1, len(th["points"]) + 1):
            grp = f"/sweep/point_{k}/observables"
            _, C, _ = obs(f, "collisions_per_particle", grp)
            _, c, dc = obs(f, "sonine_c", grp)
            sel = C >= 10
            alphas.append(float(f[f"/sweep/point_{k}"].attrs["value"].decode()
                                if isinstance(f[f"/sweep/point_{k}"].attrs["value"], bytes)
                                else f[f"/sweep/point_{k}"].attrs["value"]))
            cs.append(c[sel, 0].mean())
            es.append(dc[sel, 0].mean())
    al = np.linspace(0.25, 1, 200)
    a2 = 16 * (1 - al) * (1 - 2 * al ** 2) / (81 - 17 * al + 30 * al ** 2 * (1 - al))
    ax[0].errorbar(alphas, cs, es, fmt="o", ms=4, label="DSMC (sweep, 2 MPI ranks = serial)")
    ax[0].plot(al, 2 * a2, "r--", lw=1, label="first Sonine 2 a2")
    ax[0].plot([0.3, 0.5], [0.2078, 0.0959], "kx", label="exact DSMC (reference)")
    ax[0].axhline(0, color="k", lw=0.5)
    ax[0].set(xlabel="alpha", ylabel="c = 2 a2")
    ax[1].axis("off")
    ax[1].text(0.0, 0.5, "serial:        3.9 s\nmpirun -np 2:  2.1 s\nkilled at 3 s, restarted: 0.6 s\n"
               "all three files identical (cmp)", family="monospace", va="center")


def agg_frag(ax):
    th = theory("theory.json")
    with h5py.File("agg-frag.h5") as f:
        t, N, dN = obs(f, "number")
        _, T, dT = obs(f, "total_temperature")
        _, E, dE = obs(f, "kinetic_energy")
    N0 = N[0, 0]
    for k, color in ((0, "C0"), (1, "C1"), (4, "C2"), (9, "C3")):
        tt, NN = curve(th, "number", k)
        ax[0].errorbar(t[1:], N[1:, k] / N0, dN[1:, k] / N0, fmt="o", ms=4, color=color, label=f"k = {k + 1}")
        ax[0].plot(tt[1:], NN[1:] / N0, color=color, lw=1)
    ax[0].set(xscale="log", yscale="log", xlabel="t", ylabel="N_k / N_0 (lines: Smoluchowski)")
    tt, TT = curve(th, "total_temperature")
    _, EE = curve(th, "kinetic_energy")
    ax[1].errorbar(t, T, dT, fmt="o", ms=4, label="DSMC, T per cluster")
    ax[1].plot(tt, TT, "k-", lw=1, label="theory")
    ax[1].errorbar(t, E / 1.5, dE / 1.5, fmt="s", ms=4, label="DSMC, (2/3) E_kin per monomer")
    ax[1].plot(tt, np.array(EE) / 1.5, "k--", lw=1)
    ax[1].set(xscale="log", xlabel="t", ylabel="temperature")


def usf(ax):
    th = theory("theory.json")
    with h5py.File("usf.h5") as f:
        t, eta, deta = obs(f, "shear_viscosity")
        avg = f["/observables/shear_viscosity"].attrs["time_average"]
        avg_err = f["/observables/shear_viscosity"].attrs["time_average_error"]
        _, T, dT = obs(f, "total_temperature")
    ax[0].errorbar(t[1:], eta[1:], deta[1:], fmt="o", ms=3, label="DSMC, per sample")
    ax[0].axhspan(avg - avg_err, avg + avg_err, color="C0", alpha=0.3, label=f"time average {avg:.3f}")
    ax[0].axhline(th["shear_viscosity_ratio"]["hss"], color="r", ls="--", lw=1, label="first Sonine, HSS")
    ax[0].axhline(th["shear_viscosity_ratio"]["hcs"], color="k", ls=":", lw=1, label="first Sonine, HCS")
    ax[0].set(xlabel="t", ylabel="eta / eta_0(T)")
    ax[1].errorbar(t, T, dT, fmt="o", ms=3)
    ax[1].set(xlabel="t", ylabel="T (viscous heating)")


PLOTS = {"01": haff, "02": binary, "03": polydisperse, "04": msd, "05": sweep, "06": agg_frag, "07": usf}


def main():
    folder = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    key = os.path.basename(folder)[:2]
    if key not in PLOTS:
        sys.exit(__doc__)
    os.chdir(folder)
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
    PLOTS[key](ax)
    for a in ax:
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7)
    fig.suptitle(os.path.basename(folder), fontsize=9)
    fig.tight_layout()
    fig.savefig(f"results-{key}.png", dpi=80)
    print(f"wrote {os.path.join(folder, f'results-{key}.png')}")


if __name__ == "__main__":
    main()
