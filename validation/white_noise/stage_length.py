#!/usr/bin/env python3
"""The white noise's stage-length bias, measured by hand (docs/white-noise.md, "Stage length").

usage: stage_length.py GRANULAR_DSMC [STAGE_STEPS [RUNS]]   (default 0.125,0.5,1.0 and 8)

For alpha = 0.5 and 0.9 (one species, chi^2 = 0.001, n sigma^3 = 0.01, 16 replicas of 1e4, each started at
its Maxwellian steady temperature, t_end = 1800) and each stage_step, RUNS runs of different seeds; each run's
T_tr and a2 = c/2 averaged over the samples at t >= 600; printed: the mean over the runs +- its standard error.
Needs h5py. Takes about 2 minutes on 2 cores at the defaults.
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

NAMELIST = """&system
  mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = {alpha}
/
&initial
  temperature = {t0}
/
&dsmc
  n_particles = 10000, replicas = 16, seed = {seed}, t_end = 1800.0, stage_step = {step}
/
&thermostat
  kind = 'white_noise', noise_strength = 0.001
/
&output
  file = 'run.h5', n_samples = 31
/
"""
START = {0.5: 0.1471, 0.9: 0.3674}  # the Maxwellian steady T_tr (validation/white_noise/alpha.nml)


def main():
    exe = os.path.abspath(sys.argv[1])
    steps = [float(x) for x in (sys.argv[2] if len(sys.argv) > 2 else "0.125,0.5,1.0").split(",")]
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    with tempfile.TemporaryDirectory() as work:
        for alpha, t0 in START.items():
            for step in steps:
                temperatures, a2 = [], []
                for seed in range(100, 100 + runs):
                    with open(os.path.join(work, "in.nml"), "w") as f:
                        f.write(NAMELIST.format(alpha=alpha, t0=t0, seed=seed, step=step))
                    subprocess.run([exe, "in.nml", "--quiet", "--force"], cwd=work, check=True)
                    with h5py.File(os.path.join(work, "run.h5"), "r") as h:
                        t = h["observables/total_temperature/time"][:]
                        steady = t >= 600.0
                        temperatures.append(h["observables/total_temperature/value"][:][steady].mean())
                        a2.append(0.5 * h["observables/sonine_c/value"][:][steady].mean())
                mean = lambda x: (np.mean(x), np.std(x, ddof=1) / np.sqrt(len(x)))
                (tm, te), (am, ae) = mean(temperatures), mean(a2)
                print(f"alpha = {alpha}, stage_step = {step}: T_tr = {tm:.5f} +- {te:.5f}, a2 = {am:.4f} +- {ae:.4f} "
                      f"({runs} runs of 16 replicas)", flush=True)


if __name__ == "__main__":
    main()
