"""What every paper-figure script shares: where the validation outputs are, how to pick a case's
file (paper tier, else quick tier), how to read an observable, how to run `granular-theory` on the
input stored in an output file, and how to save a figure.

Command line of every script: [BUILD_DIR] [OUT_DIR] (defaults: build/, paper-figures/out/).
"""
import json
import os
import subprocess
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build")
OUT = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else os.path.join(ROOT, "paper-figures", "out")
RUNS = os.path.join(BUILD, "validation-output")
THEORY = os.path.join(BUILD, "bin", "granular-theory")


class Missing(SystemExit):
    """A validation output is missing; uncaught, it ends the script with its message."""


class TheoryError(RuntimeError):
    pass


def pick(name):
    """The paper-tier file of a validation case, or its quick variant."""
    for candidate in (name, name + "_quick"):
        path = os.path.join(RUNS, candidate + ".h5")
        if os.path.exists(path):
            return path
    raise Missing(f"no output for {name} in {RUNS}: run `ctest --test-dir {BUILD} -L validation` first")


def tier(path):
    return "quick tier" if path.endswith("_quick.h5") else "paper tier"


def observable(group, name):
    """(time, value, error or None) of /observables/NAME under `group` (a file or a sweep point)."""
    g = group["observables"][name]
    err = g["error"][()] if "error" in g else None
    return g["time"][()], g["value"][()], err


def stored_input(path):
    """Namelist text and overrides (without output:) stored in an output file's /parameters."""
    with h5py.File(path) as f:
        p = f["parameters"].attrs
        text = p["namelist"]
        overrides = [o for o in p["overrides"].split("\n") if o and not o.startswith("output:")]
    return text, overrides


def run_theory(text, overrides=()):
    """granular-theory on a namelist text (in a temporary directory) with --set overrides."""
    with tempfile.TemporaryDirectory(prefix="gdsmc-theory-") as tmp:
        nml = os.path.join(tmp, "theory.nml")
        with open(nml, "w") as out:
            out.write(text)
        cmd = [THEORY, nml]
        for o in overrides:
            cmd += ["--set", o]
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp)
        if r.returncode:
            raise TheoryError(f"granular-theory failed on\n{text}\n{r.stderr.strip()}")
        return json.loads(r.stdout)


def theory(path, extra=()):
    """granular-theory on the namelist and overrides stored in the output file (plus `extra`)."""
    text, overrides = stored_input(path)
    return run_theory(text, overrides + list(extra))


def save(fig, name):
    os.makedirs(OUT, exist_ok=True)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, name), dpi=120, bbox_inches="tight")
    plt.close(fig)
    print("wrote", os.path.join(OUT, name))
