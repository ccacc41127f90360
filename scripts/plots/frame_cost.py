#!/usr/bin/env python3
"""Frame time ratio (culled / unculled) against tessellation level, next to the ideal 1 - x.

Reads the CSV that `bench-frame-cost --csv FILE` writes and draws one panel per camera path
with matplotlib: per cull configuration the measured median ratio (solid, dots) and the
ideal ratio 1 - x (dashed, same color), x being the share of patches not drawn; the
break-even line at 1.

    scripts/plots/frame_cost.py docs/results/frame-cost/frame_cost.csv \
        docs/results/frame-cost/ratio.svg
"""
import csv
import sys

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLORS = {"frustum": "#1f77b4", "frustum + back-patch": "#2ca02c",
          "frustum + occlusion": "#ff7f0e", "all": "#d62728"}


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("csv", help="bench-frame-cost --csv output (or frame_cost_tables.py's)")
    parser.add_argument("out", help="image to write (.svg or .png)")
    args = parser.parse_args()
    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"frame_cost.py: {args.csv}: no bench-frame-cost row")
    paths = list(dict.fromkeys(r["path"] for r in rows))
    fig, axes = plt.subplots(1, len(paths), figsize=(4.2 * len(paths), 4.0), sharey=True,
                             squeeze=False)
    for ax, path in zip(axes[0], paths):
        for stage, color in COLORS.items():
            pts = sorted((int(r["tess"]), float(r["ratio"]), 1.0 - float(r["not_drawn"]))
                         for r in rows if r["path"] == path and r["stages"] == stage
                         and r["tess"].isdigit())  # uniform levels; "aN" rows are adaptive
            if not pts:
                continue
            tess = [p[0] for p in pts]
            ax.plot(tess, [p[1] for p in pts], "o-", color=color, label=stage)
            ax.plot(tess, [p[2] for p in pts], "--", color=color, alpha=0.6)
        ax.axhline(1.0, color="black", linewidth=0.8)
        ax.set_xscale("log", base=2)
        ax.set_xticks([1, 4, 8, 16, 32])
        ax.set_xticklabels(["1", "4", "8", "16", "32"])
        ax.set_title(path, fontsize=10)
        ax.set_xlabel("tessellation level")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("frame time culled / unculled (dashed: ideal 1 - x)")
    axes[0][-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out)


if __name__ == "__main__":
    main()
