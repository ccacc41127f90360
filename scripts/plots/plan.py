#!/usr/bin/env python3
"""The planned frame against no culling and all culling, and the planner's prediction.

Reads the CSV that `bench-plan --csv FILE` writes (one or more runs concatenated, one
header each) and draws one panel per case with matplotlib: the measured median frame time
of no culling, all culling and the planned frame against the tessellation level (log-log),
and the planner's predicted frame time (dashed, same color as planned).

    scripts/plots/plan.py docs/results/plan/plan.csv docs/results/plan/plan.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SERIES = [("none_ms", "no culling", "#7f7f7f", "o-"), ("all_ms", "all culling", "#d62728", "s-"),
          ("planned_ms", "planned", "#2ca02c", "^-"),
          ("predicted_ms", "planned, predicted", "#2ca02c", "--")]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["case"] != "case"]
    cases = list(dict.fromkeys(r["case"] for r in rows))
    columns = len(cases) if len(cases) <= 3 else (len(cases) + 1) // 2
    lines = (len(cases) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(4.4 * columns, 4.0 * lines), squeeze=False)
    for ax in axes.flat[len(cases):]:
        ax.set_visible(False)
    for ax, case in zip(axes.flat, cases):
        pts = sorted((int(r["tess"]), r) for r in rows if r["case"] == case)
        tess = [p[0] for p in pts]
        for key, label, color, style in SERIES:
            ax.plot(tess, [float(p[1][key]) for p in pts], style, color=color, label=label,
                    alpha=0.7 if style == "--" else 1.0)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xticks(tess)
        ax.set_xticklabels([str(t) for t in tess])
        ax.set_title(case)
        ax.set_xlabel("tessellation level")
        ax.grid(True, which="both", alpha=0.3)
    for row in axes:
        row[0].set_ylabel("frame ms (median, lavapipe)")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
