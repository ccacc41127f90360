#!/usr/bin/env python3
"""The planned frame against no culling and all culling, and the planner's prediction.

Reads the CSV that `bench-plan --csv FILE` writes (one or more runs concatenated, one
header each) and draws one panel per case with matplotlib: the measured median frame time
of no culling, all culling and the planned frame against the tessellation level (log-log),
and the planner's predicted frame time (dashed, same color as planned).

    scripts/plots/plan.py docs/results/plan/plan.csv docs/results/plan/plan.png

With `--splice BENCH.md PAGE.md` it also replaces the part of PAGE.md between the lines
`<!-- bench-plan output: begin -->` and `<!-- bench-plan output: end -->` by BENCH.md
(bench-plan's standard output, progress lines dropped), so that the results page is the
benchmark's own markdown plus the reading around it:

    scripts/plots/plan.py plan.csv docs/results/plan/plan.png \
        --splice bench_plan.md docs/results/plan.md
"""
import csv
import re
import sys

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SERIES = [("none_ms", "no culling", "#7f7f7f", "o-"), ("all_ms", "all culling", "#d62728", "s-"),
          ("planned_ms", "planned", "#2ca02c", "^-"),
          ("predicted_ms", "planned, predicted", "#2ca02c", "--")]


BEGIN = "<!-- bench-plan output: begin -->"
END = "<!-- bench-plan output: end -->"


def splice(bench_md, page_md):
    with open(bench_md) as f:
        # bench::progress lines ("[   1.3 s] ...") go to stderr; drop them if captured too.
        body = "".join(line for line in f if not re.match(r"^\[\s*[0-9.]+ s\]", line)).strip()
    with open(page_md) as f:
        page = f.read()
    if BEGIN not in page or END not in page:
        sys.exit(f"{page_md}: no '{BEGIN}' ... '{END}' lines to splice between")
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    with open(page_md, "w") as f:
        f.write(head + BEGIN + "\n\n" + body + "\n\n" + END + tail)


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("csv", help="bench-plan --csv output (runs concatenated)")
    parser.add_argument("out", help="image to write (.png or .svg)")
    parser.add_argument("--splice", nargs=2, metavar=("BENCH_MD", "PAGE_MD"),
                        help="also put BENCH_MD between the bench-plan markers of PAGE_MD")
    args = parser.parse_args()
    if args.splice:
        splice(*args.splice)
    with open(args.csv, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["case"] != "case"]
    cases = list(dict.fromkeys(r["case"] for r in rows))
    if not cases:
        sys.exit(f"{args.csv}: no bench-plan row")
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
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
