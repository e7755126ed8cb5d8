#!/usr/bin/python3
"""Seed 000 Figs 1-6: DSMC points (replica mean +- standard error) over the theory lines of
`granular-theory` for the same input, with residual panels (DSMC minus theory) below.

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  seed000_fig1_fig3_haff        Haff cooling T(t)/T_0       haff_cooling_alpha{0.9,0.5}
  seed000_fig2_fig4_collisions  N_c against T/T_0           haff_cooling_alpha{0.9,0.5}
  seed000_fig1_fig2_n2000       Figs 1-2 at N = 2000        haff_cooling_n2000_alpha0.9
  seed000_fig5_velocity         velocity distribution       velocity_shell, velocity_cube, velocity_shell_n2000
  seed000_fig6_polydisperse     polydisperse T_k(t)         polydisperse
A figure with one of its cases drawn is made (partial); e.g. one Haff run of your own at any restitution:
  seed000.py BUILD_DIR --run haff_cooling_alpha0.9=my-haff.h5 --out OUT_DIR
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import h5py
import numpy as np
from figures_common import figure, pick, pick_some, observable, theory, save, with_residuals, residuals


@figure("seed000_fig1_fig3_haff", "seed000_fig2_fig4_collisions")
def haff_figures():
    fig_t, ax_t, ar_t = with_residuals()
    fig_c, ax_c, ar_c = with_residuals()
    styles = {"haff_cooling_alpha0.9": ("C0", "o"), "haff_cooling_alpha0.5": ("C1", "s")}
    for case, path in pick_some(list(styles)):
        color, marker = styles[case]
        th = theory(path)
        with h5py.File(path) as f:
            t, T, dT = observable(f, "total_temperature")
            _, C, dC = observable(f, "collisions_per_particle")
            alpha = float(np.ravel(f["parameters/system"].attrs["restitution"])[0])  # a user's run: any alpha
            n_particles = int(f["parameters/dsmc"].attrs["n_particles"])
        tt, TT = np.array(th["temperature"]["time"]), np.array(th["temperature"]["value"])[:, 0]
        CC = np.array(th["collisions_per_particle"]["value"], float).reshape(len(tt), -1)[:, 0]
        # Figs 2 and 4 count collisions: N_c = (N/2) x collisions per particle (each collision counts for two particles)
        C, dC, CC = C * n_particles / 2, dC * n_particles / 2, CC * n_particles / 2
        name = fc.approximation(th, "temperature")
        s = slice(1, None)
        ax_t.errorbar(t[s], T[s], yerr=dT[s], fmt=marker, mfc="none", color=color,
                      label=rf"DSMC, $\alpha = {alpha:g}$")
        ax_t.plot(tt[s], TT[s], "-", color=color)
        residuals(ar_t, t[s], T[s], dT[s], fc.on_times(t[s], tt[s], TT[s]), kind="percent", fmt=marker,
                  mfc="none", color=color)
        ax_c.errorbar(T, C, yerr=dC, fmt=marker, mfc="none", color=color,
                      label=rf"DSMC, $\alpha = {alpha:g}$, $N = {n_particles:.0e}$".replace("e+0", "e"))
        ax_c.plot(TT, CC, "-", color=color)
        cname = fc.approximation(th, "collisions_per_particle")
        # at the same temperature: the theory line C(T) interpolated in ln T (T falls with t)
        inside = (T >= TT.min()) & (T <= TT.max())  # no extrapolation of the line
        inside[0] = False
        C_at_T = np.interp(-np.log(T[inside]), -np.log(TT), CC)
        residuals(ar_c, T[inside], C[inside], dC[inside], C_at_T, kind="percent", fmt=marker, mfc="none",
                  color=color)
    ax_t.plot([], [], "k-", label=f"Haff's law, {name} cooling rate")
    ax_c.plot([], [], "k-", label=f"{cname} collision rate along Haff's law")
    ax_t.set(xscale="log", yscale="log", ylabel=r"$T(t)/T_0$")
    ar_t.set(xscale="log", xlabel=r"$t$")
    ax_t.legend()
    ax_c.set(xscale="log", ylabel=r"number of collisions $N_c$ (one replica)")
    ar_c.set(xscale="log", xlabel=r"$T/T_0$")
    ax_c.legend()
    save(fig_t, "seed000_fig1_fig3_haff")
    save(fig_c, "seed000_fig2_fig4_collisions")


@figure("seed000_fig1_fig2_n2000")
def small_n_figure():
    """Figs 1 and 2 are printed for N = 2000, where one run scatters about Haff's law: the mean of the
    replicas +- its standard error (points), and the scatter of a single run, the replicas' standard
    deviation sqrt(R) SE (band), over Haff's law (left: T/T_0 against t; right: N_c against T/T_0)."""
    path = pick("haff_cooling_n2000_alpha0.9")
    th = theory(path)
    with h5py.File(path) as f:
        t, T, dT = observable(f, "total_temperature")
        _, C, dC = observable(f, "collisions_per_particle")
        n_particles = int(f["parameters/dsmc"].attrs["n_particles"])
        replicas = int(f["parameters/dsmc"].attrs["replicas"])
        alpha = float(np.ravel(f["parameters/system"].attrs["restitution"])[0])
    C, dC = C * n_particles / 2, dC * n_particles / 2  # the number of collisions N_c of one run
    tt, TT = np.array(th["temperature"]["time"]), np.array(th["temperature"]["value"])[:, 0]
    CC = np.array(th["collisions_per_particle"]["value"], float).reshape(len(tt), -1)[:, 0] * n_particles / 2
    spread = np.sqrt(replicas)
    fig, axes, ars = with_residuals(ncols=2, width=fc.PAGE, height=3.2)
    s = slice(1, None)
    axes[0].fill_between(t[s], T[s] - spread * dT[s], T[s] + spread * dT[s], color="C0", alpha=0.25, lw=0,
                         label=f"one run (standard deviation of {replicas} runs)")
    axes[0].errorbar(t[s], T[s], yerr=dT[s], fmt="o", mfc="none", color="C0", label=f"DSMC, mean of {replicas} runs")
    axes[0].plot(tt[s], TT[s], "k-", lw=1, label=f"Haff's law, {fc.approximation(th, 'temperature')} cooling rate")
    T_th = fc.on_times(t[s], tt[s], TT[s])
    ars[0].fill_between(t[s], -100 * spread * dT[s] / T_th, 100 * spread * dT[s] / T_th, color="C0", alpha=0.25, lw=0)
    residuals(ars[0], t[s], T[s], dT[s], T_th, kind="percent", fmt="o", mfc="none", color="C0")
    axes[0].set(xscale="log", yscale="log", ylabel=r"$T(t)/T_0$", title=f"Fig. 1: $N = {n_particles}$, $\\alpha = {alpha:g}$")
    ars[0].set(xscale="log", xlabel=r"$t$")
    axes[1].fill_between(T, C - spread * dC, C + spread * dC, color="C0", alpha=0.25, lw=0)
    axes[1].errorbar(T, C, yerr=dC, fmt="o", mfc="none", color="C0")
    axes[1].plot(TT, CC, "k-", lw=1)
    inside = (T >= TT.min()) & (T <= TT.max())
    inside[0] = False
    C_th = np.interp(-np.log(T[inside]), -np.log(TT), CC)
    ars[1].fill_between(T[inside], -100 * spread * dC[inside] / C_th, 100 * spread * dC[inside] / C_th, color="C0",
                        alpha=0.25, lw=0)  # (the scatter of one run shows at this scale only)
    residuals(ars[1], T[inside], C[inside], dC[inside], C_th, kind="percent", fmt="o", mfc="none", color="C0")
    axes[1].set(xscale="log", ylabel=r"number of collisions $N_c$", title=f"Fig. 2: $N = {n_particles}$")
    ars[1].set(xscale="log", xlabel=r"$T/T_0$")
    ars[1].set_ylabel("")
    axes[0].legend()
    save(fig, "seed000_fig1_fig2_n2000")


# the legend names the start the file records (&initial distribution), so a user's run is named right
START_NAMES = {"shell": "shell start", "cube": "cube start", "maxwell": "Maxwellian start"}


@figure("seed000_fig5_velocity")
def velocity_figure():
    fig, ax, ar = with_residuals()
    # velocity_shell_n2000(_quick): the paper's N = 2000 after N_c = 1.5e5 collisions (150 per particle)
    styles = {"velocity_shell": ("C0", "o"), "velocity_cube": ("C1", "s"), "velocity_shell_n2000": ("C2", "^")}
    for case, path in pick_some(list(styles)):
        color, marker = styles[case]
        with h5py.File(path) as f:
            g = f["observables/velocity_histogram"]
            edges = g["bin_edges"][()]
            h = g["species_1/value"][()]
            err = g["species_1/error"][()] if "error" in g["species_1"] else None
            start = f["parameters/initial"].attrs["distribution"]
            n_particles = int(f["parameters/dsmc"].attrs["n_particles"])
        mid = 0.5 * (edges[1:] + edges[:-1])
        maxwell = np.exp(-mid * mid / 2) / np.sqrt(2 * np.pi)
        ax.errorbar(mid, h[-1], yerr=None if err is None else err[-1], fmt=marker, mfc="none", color=color,
                    label=f"DSMC, {START_NAMES.get(start, start + ' start')}"
                    + (f", N = {n_particles}" if n_particles <= 10000 else ""))
        ax.plot(mid, h[0], ":", lw=1, color=color)
        if err is not None:
            residuals(ar, mid, h[-1], err[-1], maxwell, kind="se", fmt=marker, mfc="none", color=color)
    x = np.linspace(edges[0], edges[-1], 400)
    ax.plot(x, np.exp(-x * x / 2) / np.sqrt(2 * np.pi), "k-", lw=1, label="Maxwellian")
    ax.plot([], [], "k:", lw=1, label="initial distributions")
    ax.set(ylabel="probability density", yscale="log", ylim=(1e-6, 30))
    ar.set(xlabel=r"$v_x/\sqrt{T/m}$")
    ax.legend(loc="upper center", ncol=2, columnspacing=1.0)
    save(fig, "seed000_fig5_velocity")


@figure("seed000_fig6_polydisperse")
def polydisperse_figure():
    path = pick("polydisperse")
    th = theory(path)
    fig, ax, ar = with_residuals(height=3.6)
    with h5py.File(path) as f:
        t, T, dT = observable(f, "temperature")
        masses = f["parameters/system"].attrs["mass"]
    tt, TT = np.array(th["temperature"]["time"]), np.array(th["temperature"]["value"])
    name = fc.approximation(th, "temperature")
    s = slice(1, None)
    for k, marker in zip(range(T.shape[1]), "os^D"):
        c = f"C{k}"
        ax.errorbar(t[s], T[s, k], yerr=dT[s, k], fmt=marker, mfc="none", color=c,
                    label=rf"DSMC, $m_{k + 1} = {masses[k]:g}$")
        ax.plot(tt[s], TT[s, k], "-", color=c)
        residuals(ar, t[s], T[s, k], dT[s, k], fc.on_times(t[s], tt[s], TT[s, k]), kind="percent", fmt=marker,
                  mfc="none", color=c, ms=2.5)
    ax.plot([], [], "k-", label=f"{name} temperature equations")
    ax.set(xscale="log", yscale="log", ylabel=r"$T_k(t)$")
    ar.set(xscale="log", xlabel=r"$t$")
    ax.legend()
    save(fig, "seed000_fig6_polydisperse")


if __name__ == "__main__":
    fc.main()
