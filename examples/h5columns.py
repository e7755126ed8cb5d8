#!/usr/bin/env python3
"""Print observables of a granular-dsmc output file as columns (needs only h5dump, no Python packages).

usage: h5columns.py FILE.h5 OBSERVABLE[:COLUMN] ... [--group /sweep/point_1] [--theory THEORY.json]

Prints the sample time, then value and standard error of every observable named (COLUMN counts
from 0 across the second axis, e.g. temperature:1 is species 2). Example:
  h5columns.py haff-cooling.h5 total_temperature collisions_per_particle
With --theory (the JSON of granular-theory for the same namelist), every observable that has a
trajectory {"time": [...], "value": [...]} of the same name there gets a column "theory" beside it.
"""
import json
import re
import signal
import subprocess
import sys

signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head


def dataset(path, name):
    """The numbers of one dataset and its shape, read with h5dump."""
    out = subprocess.run(["h5dump", "-d", name, "-y", "-w", "0", path], capture_output=True, text=True)
    if out.returncode != 0:
        return None, None
    text = out.stdout
    shape = re.search(r"DATASPACE\s+SIMPLE\s+\{\s*\(\s*([0-9, ]+)\)", text)
    dims = [int(d) for d in shape.group(1).split(",")] if shape else [1]
    body = text.split("DATA {", 1)[1]
    numbers = [float(x) for x in re.findall(r"[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|inf|nan)", body)]
    return numbers, dims


def main(argv):
    group = "/observables"
    if "--group" in argv:
        i = argv.index("--group")
        group = argv[i + 1].rstrip("/") + "/observables"
        del argv[i:i + 2]
    if len(argv) < 3:
        sys.exit(__doc__)
    theory = {}
    if "--theory" in argv:
        i = argv.index("--theory")
        with open(argv[i + 1]) as f:
            theory = json.load(f)
        del argv[i:i + 2]
    path, columns = argv[1], []
    time = None
    for spec in argv[2:]:
        name, _, col = spec.partition(":")
        col = int(col) if col else 0
        value, dims = dataset(path, f"{group}/{name}/value")
        if value is None:
            sys.exit(f"h5columns: no {group}/{name}/value in {path}")
        error, _ = dataset(path, f"{group}/{name}/error")
        width = dims[1] if len(dims) > 1 else 1
        rows = dims[0]
        if time is None:
            time, _ = dataset(path, f"{group}/{name}/time")
        columns.append((spec, [value[r * width + col] for r in range(rows)],
                        [error[r * width + col] for r in range(rows)] if error else None))
        t = theory.get(name)
        if isinstance(t, dict) and "value" in t and len(t["value"]) == rows:
            v = t["value"]
            columns.append(("theory", [v[r][col] if isinstance(v[r], list) else v[r] for r in range(rows)], None))
    header = ["time"] + [h for spec, _, err in columns for h in ([spec, "+-"] if err else [spec])]
    print("  ".join(f"{h:>12}" for h in header))
    for r in range(len(time)):
        cells = [f"{time[r]:12.5g}"]
        for _, val, err in columns:
            cells.append(f"{val[r]:12.6g}")
            if err:
                cells.append(f"{err[r]:12.3g}")
        print("  ".join(cells))


if __name__ == "__main__":
    main(sys.argv)
