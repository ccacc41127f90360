#!/usr/bin/env python3
"""The Markdown tables of bench-frame-cost as the CSV frame_cost.py plots.

    scripts/plots/frame_cost_tables.py OUT.csv bench_frame_cost.md [more.md ...]

Reads every table row under a "### PATH" heading: the 11-column table written before the
free-culling frame (issue 24) and the 16-column one after it.
"""
import sys

import plot_cli

HEADER = ("path,stages,tess,not_drawn,ratio,tes_ratio,fragment_ratio,unculled_ms,free_ms,"
          "culled_ms,overhead,split\n")


def rows(md):
    path = None
    for line in open(md):
        if line.startswith("### "):
            path = line[4:].strip()
            continue
        if not (path and line.startswith("| ") and not line.startswith("| tess")):
            continue
        c = [x.strip() for x in line.strip().strip("|").split("|")]
        if not c[0].isdigit():
            continue
        if len(c) == 11:  # the table before the free-culling frame (issue 24)
            tess, st, x, _fr, _ideal, ms, ratio, _share, tes, frag, split = c
            free = culled = overhead = ""
        elif len(c) == 16:
            (tess, st, x, _fr, ms, free, culled, overhead, _share, ratio, tes, _same, frag, split,
             _excess, _gpuwall) = c
            overhead = "%.5f" % (float(overhead.rstrip("%")) / 100)
        else:
            continue
        yield '"%s","%s",%s,%.5f,%s,%s,%s,%s,%s,%s,%s,"%s"\n' % (
            path, st, tess, float(x.rstrip("%")) / 100, ratio, tes, frag, ms, free, culled,
            overhead, split)


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("out", help="CSV to write")
    parser.add_argument("md", nargs="+", help="bench-frame-cost Markdown output")
    args = parser.parse_args()
    lines = [r for md in args.md for r in rows(md)]
    if not lines:
        sys.exit(f"frame_cost_tables.py: no bench-frame-cost table row in {', '.join(args.md)}")
    with open(args.out, "w") as out:
        out.write(HEADER)
        out.writelines(lines)


if __name__ == "__main__":
    main()
