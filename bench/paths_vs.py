#!/usr/bin/env python3
"""Two builds' bench_paths side by side: runs them alternately (A B A B ...), so that both see the
same machine, and prints for every path the median collision rate of each and the median, least and
largest of the paired ratios B/A (a change that keeps the speed shows ratios around 1).

usage: bench/paths_vs.py A/bench_paths B/bench_paths [--rounds R] [--column rate|cpu] [bench_paths args ...]
e.g.   bench/paths_vs.py old/bin/bench_paths build/bin/bench_paths --rounds 5 --no-pairs 1000000
"""
import statistics
import subprocess
import sys


def run(exe, args):
    out = subprocess.run([exe] + args, check=True, capture_output=True, text=True).stdout
    rates = {}
    for line in out.splitlines():
        parts = line.split()
        # path name (several words), then collisions/s, coll/part., seconds, ratio, CPU coll/s
        if len(parts) >= 6:
            try:
                numbers = [float(x) for x in parts[-5:]]
            except ValueError:
                continue
            rates[" ".join(parts[:-5])] = numbers
    return rates


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    a, b, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    rounds, column = 5, 0
    args = []
    i = 0
    while i < len(rest):
        if rest[i] == "--rounds":
            rounds = int(rest[i + 1]); i += 2
        elif rest[i] == "--column":
            column = 0 if rest[i + 1] == "rate" else 4; i += 2
        else:
            args.append(rest[i]); i += 1
    ra, rb = {}, {}
    for r in range(rounds):
        for exe, store in ((a, ra), (b, rb)):
            for path, numbers in run(exe, args).items():
                store.setdefault(path, []).append(numbers[column])
        print(f"round {r + 1}/{rounds} done", file=sys.stderr)
    print(f"{'path':42s} {'A median':>11s} {'B median':>11s}  {'B/A median':>10s} {'min':>6s} {'max':>6s}")
    for path in ra:
        if path not in rb:
            continue
        ratios = [y / x for x, y in zip(ra[path], rb[path]) if x > 0]
        print(f"{path:42s} {statistics.median(ra[path]):11.4g} {statistics.median(rb[path]):11.4g}  "
              f"{statistics.median(ratios):10.3f} {min(ratios):6.3f} {max(ratios):6.3f}")


if __name__ == "__main__":
    main()
