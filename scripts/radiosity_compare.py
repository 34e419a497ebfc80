#!/usr/bin/env python3
"""Compare two `prt radiosity --csv` outputs of the same scene (same vertices).

Prints the relative RMS difference of vertex radiance, sqrt(sum (a - b)^2 / sum b^2) over
every vertex and channel, with B the reference; vertices whose reference radiance exceeds
`--exclude-above` (default: none), e.g. the lamp's, are left out. Usage:
    scripts/radiosity_compare.py candidate.csv reference.csv [--exclude-above VALUE]
"""
import csv
import math
import sys


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    out = []
    for row in rows[1:]:
        out.append(tuple(float(v) for v in row[4:7]))
    return out


def main():
    args = sys.argv[1:]
    limit = math.inf
    if "--exclude-above" in args:
        i = args.index("--exclude-above")
        limit = float(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    a, b = read(args[0]), read(args[1])
    if len(a) != len(b):
        sys.exit(f"{args[0]}: {len(a)} vertices, {args[1]}: {len(b)}")
    num = den = 0.0
    worst = 0.0
    peak = max(max(v) for v in b if max(v) <= limit)
    for x, y in zip(a, b):
        if max(y) > limit:
            continue
        for c in range(3):
            num += (x[c] - y[c]) ** 2
            den += y[c] ** 2
            worst = max(worst, abs(x[c] - y[c]) / peak)
    print(f"relative RMS {math.sqrt(num / den):.4%}, worst {worst:.2%} of the brightest vertex")


if __name__ == "__main__":
    main()
