#!/usr/bin/env python3
"""Back-patch cull rates of a cube authored far from the origin, recentred (object space,
view x model in double) against baked (the offset kept in the fp32 control points).

Reads the CSV of scripts/large_coordinates.sh and writes an SVG with matplotlib:

    /usr/bin/python3 scripts/plots/large_coordinates.py docs/results/scene/large_coordinates.csv \
        docs/results/scene/large_coordinates.svg
"""
import csv
import sys

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("csv", help="scripts/large_coordinates.sh's CSV")
    parser.add_argument("out", help="image to write (.svg or .png)")
    args = parser.parse_args()
    rows = list(csv.DictReader(open(args.csv)))
    if not rows:
        sys.exit(f"large_coordinates.py: {args.csv}: no row")
    offsets = sorted({int(r["offset"]) for r in rows})
    methods = ["tcone", "ncone", "tangent-plane"]
    colors = {"tcone": "#1f77b4", "ncone": "#2ca02c", "tangent-plane": "#d62728"}
    fig, ax = plt.subplots(figsize=(7.2, 4.0))
    x = list(range(len(offsets)))
    for m in methods:
        for mode, style in (("recentred", "-"), ("baked", "--")):
            y = [100 * float(r["cull_rate"]) for o in offsets for r in rows
                 if int(r["offset"]) == o and r["method"] == m and r["mode"] == mode]
            ax.plot(x, y, style, marker="o", color=colors[m], label=f"{m}, {mode}")
    ax.set_xticks(x)
    ax.set_xticklabels(["0" if o == 0 else f"1e{len(str(o)) - 1}" for o in offsets])
    ax.set_xlabel("distance of the cage from the origin")
    ax.set_ylabel("cull rate (%)")
    ax.set_title("Cube (level 3) over 101 views: recentred (solid) vs baked fp32 (dashed)")
    ax.legend(fontsize=8, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out)


if __name__ == "__main__":
    main()
