#!/usr/bin/env python3
"""Frame time ratio (culled / unculled) against tessellation level, next to free culling.

Reads the CSV that `bench-frame-cost --csv FILE` writes and draws, with matplotlib, one
column of panels per camera path: on top the uniform levels, below the screen-space
adaptive ones (rows "aN", N pixels per segment) where the CSV has them. Per cull
configuration the measured median ratio culled / unculled (solid, dots) and the free-culling
frame's free / unculled (dashed, same color: the same patches drawn with no cull work, the
limit of culling on the device; 1 - x, x the share of patches not drawn, for CSVs from
before the free-culling frame); the break-even line at 1.

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
          "frustum + ncone": "#9467bd", "frustum + occlusion": "#ff7f0e", "all": "#d62728"}


def level(row, adaptive):
    """The row's level: uniform N, or adaptive pixels N of "aN"; None for the other kind."""
    t = row["tess"]
    if adaptive:
        return int(t[1:]) if t.startswith("a") and t[1:].isdigit() else None
    return int(t) if t.isdigit() else None


def limit(row):
    """free / unculled; the ideal 1 - x for CSVs written before the free-culling frame."""
    if row.get("free_ms") and row.get("unculled_ms"):
        return float(row["free_ms"]) / float(row["unculled_ms"])
    return 1.0 - float(row["not_drawn"])


def panel(ax, rows, path, adaptive):
    for stage, color in COLORS.items():
        pts = sorted((level(r, adaptive), float(r["ratio"]), limit(r))
                     for r in rows if r["path"] == path and r["stages"] == stage
                     and level(r, adaptive) is not None)
        if not pts:
            continue
        x = [p[0] for p in pts]
        ax.plot(x, [p[1] for p in pts], "o-", color=color, label=stage)
        ax.plot(x, [p[2] for p in pts], "--", color=color, alpha=0.6)
    ax.axhline(1.0, color="black", linewidth=0.8)
    ax.set_xscale("log", base=2)
    ticks = sorted({level(r, adaptive) for r in rows if r["path"] == path} - {None})
    ax.set_xticks(ticks)
    ax.set_xticklabels([str(t) for t in ticks])
    ax.set_title(path + (" (adaptive)" if adaptive else ""), fontsize=10)
    ax.set_xlabel("pixels per segment" if adaptive else "uniform tessellation level")
    ax.grid(alpha=0.3)


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
    kinds = [False] + ([True] if any(level(r, True) is not None for r in rows) else [])
    fig, axes = plt.subplots(len(kinds), len(paths), figsize=(4.6 * len(paths), 4.0 * len(kinds)),
                             sharey=True, squeeze=False)
    for k, adaptive in enumerate(kinds):
        for ax, path in zip(axes[k], paths):
            panel(ax, rows, path, adaptive)
        axes[k][0].set_ylabel("frame ms / unculled (dashed: free culling)")
    axes[0][-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out)


if __name__ == "__main__":
    main()
