#!/usr/bin/python3
"""Aggregation and fragmentation (DSMC notes, eqs. (8)-(14); docs/agg-frag.md): DSMC points (replica
mean +- standard error) over the Smoluchowski rate equations of `granular-theory` for the same input,
for pure sticking, rare reactions in a nearly elastic gas, and the full model, with the residuals
(DSMC/theory - 1, in percent) below: the closure's drift is visible there. Each figure shows N_k(t) for
k = 1..4, the monomer fraction, the mean cluster size <k> and the temperature per cluster T(t).

figures (OUT_DIR/<figure>.pdf and .png) and the validation cases they draw:
  agg_frag_sticking  agg_frag_sticking
  agg_frag_rare      agg_frag_rare
  agg_frag_full      agg_frag_full
"""
import figures_common as fc  # first: it answers --help before matplotlib is loaded
import h5py
import matplotlib.pyplot as plt
import numpy as np
from figures_common import PAGE, figure, pick, observable, theory, save, residuals

CASES = (("sticking", "pure sticking"), ("rare", r"rare reactions, $\alpha = 0.99$"), ("full", "full model"))


def draw(case, title):
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
    fig, axes = plt.subplots(2, 4, figsize=(PAGE, 3.3), sharex=True,
                             gridspec_kw=dict(height_ratios=(3.0, 1.3)))
    fig._gdsmc_hspace = 0.06
    s = slice(1, None)
    ax, ar = axes[:, 0]
    for k, marker in zip(range(min(4, number.shape[1])), "os^D"):
        c = f"C{k}"
        ax.errorbar(t[s], number[s, k] / n0, yerr=dnumber[s, k] / n0, fmt=marker, mfc="none", color=c,
                    label=f"$k = {k + 1}$")
        if k < tn.shape[1]:
            ax.plot(tt[s], tn[s, k] / n0, "-", color=c)
            # in standard errors: the rare large clusters of early times have relative errors of 100 %
            residuals(ar, t[s], number[s, k], dnumber[s, k], fc.on_times(t[s], tt[s], tn[s, k]), kind="se",
                      fmt=marker, mfc="none", color=c, ms=2.5)
    ax.set(xscale="log", yscale="log", ylabel=r"$N_k/N_0$")
    ax.legend(title="DSMC", title_fontsize="small")
    for (ax, ar), (y, dy, key, label) in zip(
        (axes[:, 1], axes[:, 2], axes[:, 3]),
        ((mono, dmono, "monomer_fraction", r"$N_1/N_0$"), (size, dsize, "mean_size", r"$\langle k\rangle = N_0/N$"),
         (temp, dtemp, "total_temperature", r"$T$ per cluster"))):
        y, dy = np.ravel(y), np.ravel(dy)
        yt, yv = np.array(th[key]["time"]), np.ravel(th[key]["value"])
        ax.errorbar(t[s], y[s], yerr=dy[s], fmt="o", mfc="none", color="C0", label="DSMC")
        ax.plot(yt[s], yv[s], "-", color="k", lw=1, label="Smoluchowski,\nMaxwellian kernels")
        residuals(ar, t[s], y[s], dy[s], fc.on_times(t[s], yt[s], yv[s]), kind="percent", fmt="o", mfc="none",
                  color="C0", ms=2.5)
        ax.set(xscale="log", ylabel=label)
    axes[0, 2].legend(loc="upper left")
    for ar in axes[1]:
        ar.set(xlabel=r"$t$")
        ar.set_ylabel("")
    for ax in axes[0]:
        ax.tick_params(labelbottom=False)
    axes[1, 0].set_ylabel(fc.SE_LABEL)
    axes[1, 1].set_ylabel(fc.PERCENT_LABEL)
    fig.suptitle(f"{title}, $N_0 = {n0}$")
    save(fig, f"agg_frag_{case}")


@figure("agg_frag_sticking")
def sticking():
    draw(*CASES[0])


@figure("agg_frag_rare")
def rare():
    draw(*CASES[1])


@figure("agg_frag_full")
def full():
    draw(*CASES[2])


if __name__ == "__main__":
    fc.main()
