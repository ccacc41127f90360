#!/usr/bin/python3
"""Cost per patch against the patch count, from bench-scale output (Markdown tables). Writes
an SVG with matplotlib: cull ns/patch, peak RSS bytes/patch and set-up CPU us/patch, each
relative to its value at the smallest size, on a log patch axis.

  /usr/bin/python3 scripts/plots/scale.py docs/results/scale/bench_scale.md \
      docs/results/scale/scale.svg   # python3-matplotlib (Debian)

Every table row of the input whose first cell is a number is a measurement; rows of the same
patch count (several runs) are reduced to their median.
"""
import statistics

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    header, out = None, []
    for line in open(path, encoding="utf-8"):
        cells = [c.strip().strip("*") for c in line.strip().strip("|").split("|")]
        if len(cells) < 4:
            continue
        if cells[0] == "grid":
            header = cells
        elif header and cells[0].isdigit() and len(cells) == len(header):
            out.append(dict(zip(header, cells)))
    return out


def main(src, dst):
    by_count = {}
    for r in rows(src):
        by_count.setdefault(int(r["patches"]), []).append(r)
    counts = sorted(by_count)
    if not counts:
        raise SystemExit(f"{src}: no bench-scale table (a header row starting 'grid')")
    series = {
        "cull ns/patch": "cull ns/patch",
        "peak RSS bytes/patch": "bytes/patch",
        "set-up CPU us/patch": "set-up CPU ms",
    }
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for label, key in series.items():
        values = []
        for n in counts:
            v = statistics.median(float(r[key]) for r in by_count[n])
            values.append(v * 1000.0 / n if key == "set-up CPU ms" else v)
        axes[0].plot(counts, values, marker="o", label=label)
        axes[1].plot(counts, [v / values[0] for v in values], marker="o", label=label)
    axes[0].set_yscale("log")
    axes[0].set_title("cost per patch")
    axes[1].axhline(1.5, color="grey", linestyle="--", linewidth=1)
    axes[1].set_title("relative to the smallest mesh (dashed: 1.5x)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("patches (torus, level 1)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(dst)


if __name__ == "__main__":
    parser = plot_cli.parser(__doc__)
    parser.add_argument("src", help="bench-scale's Markdown output")
    parser.add_argument("dst", help="image to write (.svg or .png)")
    args = parser.parse_args()
    main(args.src, args.dst)
