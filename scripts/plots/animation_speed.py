#!/usr/bin/python3
"""Cull rate and not-drawn share against deformation speed (bench-animation section 1).

The analogue of Niessner & Loop Fig. 9 right for motion of the mesh instead of the camera:
BigGuy with the limb skinning rig, the joints turning by up to the x value per frame.

    scripts/plots/animation_speed.py docs/results/animation/speed.png \
        docs/results/animation/animation_speed.csv
"""
import csv
import sys

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out, path):
    series = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            series.setdefault(r["stages"], []).append(
                (float(r["joint_deg"]), 100 * float(r["cull_rate"]), 100 * float(r["not_drawn"])))
    if not series:
        sys.exit(f"animation_speed.py: {path}: no bench-animation row")
    fig, ax = plt.subplots(figsize=(7, 4.2))
    colors = ["#1f77b4", "#d62728", "#2ca02c"]
    for (name, pts), color in zip(sorted(series.items()), colors):
        pts.sort()
        x = [p[0] for p in pts]
        ax.plot(x, [p[1] for p in pts], "--o", color=color, label=f"{name}: culled")
        ax.plot(x, [p[2] for p in pts], "-s", color=color, label=f"{name}: not drawn")
    ax.set_xlabel("largest joint turn per frame (degrees)")
    ax.set_ylabel("share of patches (%)")
    ax.set_title("BigGuy, limb skinning rig: culling against deformation speed")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    parser = plot_cli.parser(__doc__)
    parser.add_argument("out", help="image to write (.png or .svg)")
    parser.add_argument("csv", help="bench-animation's section-1 CSV (animation_speed.csv)")
    args = parser.parse_args()
    main(args.out, args.csv)
