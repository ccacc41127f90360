#!/usr/bin/python3
"""Cull-kernel cost per patch, the 516-term table kernel against the factored one, from
bench-cull outputs (Markdown tables) run alternately. Writes an SVG with matplotlib.

  scripts/plots/backpatch_kernel_cost.py docs/results/backpatch/kernel_cost.txt \
      docs/results/backpatch/kernel_cost.svg

The input holds runs separated by lines "== table N" and "== factored N"; the plot shows,
per method, the median over runs of each run's median ns/patch (log scale).
"""
import re
import statistics

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHODS = ["tcone/surface", "tcone", "tangent-plane/surface", "tangent-plane",
           "tangent-plane-16/surface", "tangent-plane-16"]


def load(path):
    runs = {}  # kernel -> method -> [ns]
    kernel = None
    for line in open(path):
        m = re.match(r"== (table|factored) \d+", line)
        if m:
            kernel = m.group(1)
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if kernel and len(cells) >= 5 and cells[2] in METHODS and cells[4].isdigit():
            runs.setdefault(kernel, {}).setdefault(cells[2], []).append(int(cells[4]))
    return runs


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("runs", help="bench-cull tables, runs separated by '== table N' / '== factored N'")
    parser.add_argument("out", help="image to write (.svg or .png)")
    args = parser.parse_args()
    runs = load(args.runs)
    if not runs:
        parser.error(f"{args.runs}: no '== table N' or '== factored N' run with a method row")
    fig, ax = plt.subplots(figsize=(8, 4))
    width = 0.38
    for k, (kernel, color) in enumerate([("table", "#7f7f7f"), ("factored", "#d62728")]):
        values = [statistics.median(runs.get(kernel, {}).get(m, [float("nan")])) for m in METHODS]
        xs = [i + (k - 0.5) * width for i in range(len(METHODS))]
        ax.bar(xs, values, width, label=f"{kernel} build", color=color)
    ax.set_yscale("log")
    ax.set_xticks(range(len(METHODS)))
    ax.set_xticklabels(METHODS, rotation=20, ha="right")
    ax.set_ylabel("ns per patch (median)")
    ax.set_title("Cull kernel cost, BigGuy level 2 (5554 patches), lavapipe, 2 shared cores")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out)


if __name__ == "__main__":
    main()
