#!/usr/bin/env python3
"""Plots Table 1 of Niessner & Loop next to our displaced-BigGuy cull rates.

usage: displacement_table1.py OUT.svg LEVEL0.json LEVEL1.json
The JSON files are `osd-cull verify --displaced-bound all --json` outputs.
"""
import json
import sys

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KERNELS = ["full-oobb", "acon-oobb", "con-oobb", "full-caf", "acon-caf", "con-caf"]
PAPER = {  # Table 1, percent
    "Frog": [10.5, 12.1, 14.0, 14.4, 17.0, 18.4],
    "Frog2": [17.1, 25.1, 26.4, 22.8, 29.4, 30.9],
    "Cow": [10.1, 14.1, 15.6, 14.5, 17.6, 18.7],
    "Cow2": [17.8, 27.9, 29.1, 24.0, 31.2, 32.7],
}


def rates(path):
    try:
        doc = json.load(open(path))
        by = {m["name"]: 100.0 * m["cull_rate"] for m in doc["methods"]}
    except (json.JSONDecodeError, KeyError, TypeError) as e:
        sys.exit(f"displacement_table1.py: {path}: not `osd-cull verify --json` output ({e})")
    missing = [k for k in KERNELS if k not in by]
    if missing:
        sys.exit(f"displacement_table1.py: {path}: no method {', '.join(missing)} "
                 "(run verify with --displaced-bound all)")
    return [by[k] for k in KERNELS]


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("out", help="image to write (.svg or .png)")
    parser.add_argument("level0", help="osd-cull verify --displaced-bound all --json, level 0")
    parser.add_argument("level1", help="the same at level 1")
    args = parser.parse_args()
    out, level0, level1 = args.out, args.level0, args.level1
    rows = dict(PAPER)
    rows["BigGuy (ours, level 0)"] = rates(level0)
    rows["BigGuy (ours, level 1)"] = rates(level1)
    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.8 / len(rows)
    for i, (name, values) in enumerate(rows.items()):
        xs = [k + (i - len(rows) / 2 + 0.5) * width for k in range(len(KERNELS))]
        ours = name.startswith("BigGuy")
        ax.bar(xs, values, width, label=name, hatch=None if ours else "//", alpha=1.0 if ours else 0.55)
    ax.set_xticks(range(len(KERNELS)))
    ax.set_xticklabels(KERNELS)
    ax.set_ylabel("cull rate (%)")
    ax.set_title("Displaced patches: cull rate per kernel (whole-object views)")
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(out)


if __name__ == "__main__":
    main()
