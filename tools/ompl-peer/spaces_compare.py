#!/usr/bin/env python3
"""Cross-checks smug-spaces' Dubins and Reeds-Shepp distances against OMPL's.

Runs the `spaces_check` example (our distances on seeded random pairs) and the
`spaces_check` OMPL peer on the same pairs, and prints the max absolute and relative
differences per model and class of pair (far, near, tangent: see the
example), and how often smug is shorter or longer than OMPL by more than 1e-6 m. Usage (from the repository root, after tools/ompl-peer/build.sh):

    tools/ompl-peer/spaces_compare.py [--radius 1 2.5] [--pairs 10000] [--seed 1]

Standard library only. See SPACES.md.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def compare(radius, pairs, seed, worst):
    ours = subprocess.run(
        ["cargo", "run", "-q", "--release", "-p", "smug-spaces", "--example", "spaces_check",
         "--", str(radius), str(pairs), str(seed)],
        cwd=ROOT, check=True, capture_output=True, text=True).stdout.split("\n")
    rows = [line.split() for line in ours if line.strip()]
    stdin = "".join(" ".join(r[:6]) + "\n" for r in rows)
    peer = subprocess.run([os.path.join(HERE, "spaces_check"), str(radius)], input=stdin,
                          check=True, capture_output=True, text=True).stdout.split("\n")
    theirs = [line.split() for line in peer if line.strip()]
    assert len(theirs) == len(rows), (len(theirs), len(rows))
    for model, col in (("dubins", 0), ("reeds-shepp", 1)):
        for cls in ("far", "near", "tangent"):
            pairs = [(r, o) for r, o in zip(rows, theirs) if r[8] == cls]
            max_abs = max_rel = 0.0
            shorter = longer = 0
            arg = None
            for r, o in pairs:
                a, b = float(r[6 + col]), float(o[col])
                diff = abs(a - b)
                if diff > max_abs:
                    max_abs, arg = diff, (r[:6], a, b)
                max_rel = max(max_rel, diff / max(abs(b), 1e-12))
                shorter += a < b - 1e-6
                longer += a > b + 1e-6
            print(f"| {radius} | {model} | {cls} | {len(pairs)} | {max_abs:.3e} | {max_rel:.3e}"
                  f" | {shorter} | {longer} |")
            if worst and arg:
                print(f"  worst {model} {cls} r={radius}: pair {' '.join(arg[0])}:"
                      f" smug {arg[1]!r} ompl {arg[2]!r}", file=sys.stderr)

def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--radius", type=float, nargs="+", default=[1.0, 2.5])
    parser.add_argument("--pairs", type=int, default=10000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--worst", action="store_true", help="print the worst pair to stderr")
    args = parser.parse_args()
    print("| radius | model | pairs | n | max abs diff (m) | max rel diff"
          " | smug shorter by > 1e-6 | smug longer by > 1e-6 |")
    print("|---|---|---|---|---|---|---|---|")
    for radius in args.radius:
        compare(radius, args.pairs, args.seed, args.worst)


if __name__ == "__main__":
    main()
