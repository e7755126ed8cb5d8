#!/usr/bin/python3
"""Rough spheres and the white-noise thermostat. Figure rough_theta_alpha (docs/rough-spheres.md):
theta = T_rot/T_tr of the homogeneous cooling state against the normal restitution alpha at several
tangential restitutions beta, DSMC beside the Maxwellian theory (Luding et al. 1998) and the Sonine
theory (Santos, Kremer and dos Santos 2011), for uniform spheres (kappa = 0.4) and thin shells
(kappa = 2/3). The Sonine curve is left out where that theory has no
solution (granular-theory says why: a cumulant above 1).

The DSMC values are theta at the last sample (c = 80 collisions per particle) of every point of the
sweep of validation/rough_spheres/theta_alpha.nml, with the standard error from the two temperatures'.

Figure white_noise_a2 (docs/white-noise.md): the cumulant a2 = c/2 of smooth spheres heated by white noise
against alpha, DSMC (averaged over the samples from t = 600 on, error = the mean of their SEs) beside van
Noije and Ernst's first-Sonine value for the driven state and, for contrast, that of the cooling state.

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  rough_theta_alpha  rough_theta_alpha, rough_theta_alpha_kappa0.67 (one panel each)
  white_noise_a2     white_noise_alpha
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import h5py
import matplotlib.pyplot as plt
import numpy as np
from figures_common import PAGE, Missing, figure, pick, stored_input, run_theory, save

CASES = (("rough_theta_alpha", r"$\kappa = 0.4$"), ("rough_theta_alpha_kappa0.67", r"$\kappa = 2/3$"))
ALPHAS = np.linspace(0.3, 1.0, 15)


def sweep_points(path):
    """{beta: [(alpha, theta, error), ...]} of the sweep's last samples."""
    out = {}
    with h5py.File(path) as f:
        values = f["sweep/values"][()]
        for k, (alpha, beta) in enumerate(values):
            g = f[f"sweep/point_{k + 1}/observables"]
            t, dt = g["total_temperature/value"][()].ravel(), g["total_temperature/error"][()].ravel()
            r, dr = g["rotational_temperature/value"][()].ravel(), g["rotational_temperature/error"][()].ravel()
            theta = r[-1] / t[-1]
            out.setdefault(float(beta), []).append((float(alpha), theta, theta * np.hypot(dr[-1] / r[-1], dt[-1] / t[-1])))
    return out


def theory_curves(path, beta):
    """(alpha, Maxwellian theta, Sonine theta or NaN) from granular-theory on the stored input."""
    text, overrides = stored_input(path)
    overrides = [o for o in overrides if not o.startswith(("system:restitution", "system:roughness"))]
    text = text[:text.index("&sweep")] if "&sweep" in text else text
    maxwell, sonine = [], []
    for alpha in ALPHAS:
        th = run_theory(text, overrides + [f"system:restitution={alpha}", f"system:roughness={beta}"])["rough_hcs"]
        maxwell.append(th["maxwellian"]["theta"])
        sonine.append(th["sonine"]["theta"] if isinstance(th["sonine"], dict) else np.nan)
    return np.array(maxwell), np.array(sonine)


@figure("rough_theta_alpha")
def theta_alpha():
    fig, axes = plt.subplots(1, 2, figsize=(PAGE, 3.2), sharey=True)
    drawn = False
    for ax, (case, title) in zip(axes, CASES):
        ax.set(xlabel=r"$\alpha$", title=title)
        try:
            path = pick(case)
        except Missing:
            fc.no_dsmc(ax, case, theory_drawn=False)
            continue
        drawn = True
        points = sweep_points(path)
        for n, beta in enumerate(sorted(points)):
            color = f"C{n}"
            maxwell, sonine = theory_curves(path, beta)
            ax.plot(ALPHAS, maxwell, "--", color=color, lw=0.9)
            ax.plot(ALPHAS, sonine, "-", color=color, lw=1.2)
            a, th, dth = np.array(points[beta]).T
            ax.errorbar(a, th, yerr=dth, fmt="o", mfc="none", color=color, label=fr"$\beta = {beta:g}$")
        ax.set_yscale("log")
    if not drawn:
        raise Missing(f"no run of {CASES[0][0]} or {CASES[1][0]}", case=CASES[0][0])
    axes[0].set_ylabel(r"$\theta = T_{\mathrm{rot}}/T_{\mathrm{tr}}$")
    axes[0].legend(loc="upper right")
    proxies = [axes[1].plot([], [], "-", color="k", lw=1.2, label="Sonine")[0],
               axes[1].plot([], [], "--", color="k", lw=0.9, label="Maxwellian")[0],
               axes[1].plot([], [], "o", mfc="none", color="k", label="DSMC")[0]]
    axes[1].legend(handles=proxies, loc="upper right")
    save(fig, "rough_theta_alpha")


STEADY_FROM = 600.0  # as validation/white_noise/validate_white_noise_alpha.cpp


@figure("white_noise_a2")
def white_noise_a2():
    path = pick("white_noise_alpha")
    alphas, a2, da2 = [], [], []
    with h5py.File(path) as f:
        for k, row in enumerate(f["sweep/values"][()]):
            g = f[f"sweep/point_{k + 1}/observables/sonine_c"]
            t, c, dc = g["time"][()].ravel(), g["value"][()].ravel(), g["error"][()].ravel()
            sel = t >= STEADY_FROM
            alphas.append(float(row[0]))
            a2.append(0.5 * c[sel].mean())
            da2.append(0.5 * dc[sel].mean())
    text, overrides = stored_input(path)
    text = text[:text.index("&sweep")] if "&sweep" in text else text
    overrides = [o for o in overrides if not o.startswith(("system:restitution", "initial:temperature"))]
    curve = np.linspace(0.3, 0.99, 24)  # alpha = 1: no steady state
    driven, cooling = [], []
    for alpha in curve:
        th = run_theory(text, overrides + [f"system:restitution={alpha}"])
        driven.append(th["white_noise"]["sonine"]["a20"])
        cooling.append(th["sonine_a2"])
    fig, ax = plt.subplots(figsize=(fc.COLUMN, 2.8))
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.plot(curve, driven, "-", color="C0", label="white noise, first Sonine")
    ax.plot(curve, cooling, "--", color="C1", label="cooling state, first Sonine")
    ax.errorbar(alphas, a2, yerr=da2, fmt="o", mfc="none", color="C0", label="DSMC, white noise")
    ax.set(xlabel=r"$\alpha$", ylabel=r"$a_2$")
    ax.legend(loc="upper right")
    save(fig, "white_noise_a2")


if __name__ == "__main__":
    fc.main()
