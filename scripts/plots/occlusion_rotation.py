#!/usr/bin/env python3
"""Cull rate against rotation speed, ours next to the paper's (Niessner & Loop, Fig. 9 right).

Reads the CSVs that `bench-occlusion --csv FILE` writes for its rotation sweep and writes an
SVG (python3 standard library only):

    scripts/plots/occlusion_rotation.py docs/results/occlusion/rotation.svg \
        docs/results/occlusion/rotation.csv [more.csv ...] [--scenes "BigGuy level 0;..."]

Per scene two lines: the occlusion cull rate (patches the Hi-Z test culls; dashed) and the
share of patches not drawn at all in the frame (solid; culled patches that were visible
last frame are still drawn in pass 1). The paper gives only the end points of its curve in
the text (25.5% at rest, 20.4% at 10 degrees per frame); they are drawn as two black dots
joined by a dotted line.
"""
import csv
import sys

import plot_cli
from xml.sax.saxutils import escape

PAPER = [(0.0, 25.5), (10.0, 20.4)]
COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"]

WIDTH, HEIGHT = 720, 440
LEFT, RIGHT, TOP, BOTTOM = 70, 230, 40, 60


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    scenes = {}
    for r in rows:
        scenes.setdefault(r["scene"], []).append(
            (float(r["degrees_per_frame"]), float(r["occlusion_cull_rate_percent"]),
             float(r["not_drawn_percent"])))
    if not scenes:
        sys.exit(f"occlusion_rotation.py: no bench-occlusion row in {', '.join(paths)}")
    for points in scenes.values():
        points.sort()
    return scenes


def nice_range(values):
    lo, hi = min(values), max(values)
    lo = max(0.0, 5.0 * int(lo / 5.0) - 5.0)
    hi = 5.0 * int(hi / 5.0 + 1.0) + 0.0
    return lo, hi


def svg(scenes):
    ys = [y for pts in scenes.values() for p in pts for y in p[1:]] + [y for _, y in PAPER]
    y0, y1 = nice_range(ys)
    x0, x1 = 0.0, 10.0
    pw, ph = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM

    def sx(x):
        return LEFT + (x - x0) / (x1 - x0) * pw

    def sy(y):
        return TOP + (1.0 - (y - y0) / (y1 - y0)) * ph

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
           f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="12">',
           f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>',
           f'<text x="{LEFT + pw / 2}" y="22" text-anchor="middle" font-size="14">'
           'Cull rate against rotation speed (camera orbit about the up axis)</text>']
    # Grid and axes.
    step = 5.0 if y1 - y0 <= 50 else 10.0
    y = y0
    while y <= y1 + 1e-9:
        out.append(f'<line x1="{LEFT}" y1="{sy(y):.1f}" x2="{LEFT + pw}" y2="{sy(y):.1f}" '
                   'stroke="#ddd"/>')
        out.append(f'<text x="{LEFT - 6}" y="{sy(y) + 4:.1f}" text-anchor="end">{y:.0f}%</text>')
        y += step
    for x in range(0, 11):
        out.append(f'<line x1="{sx(x):.1f}" y1="{TOP + ph}" x2="{sx(x):.1f}" y2="{TOP + ph + 4}" '
                   'stroke="black"/>')
        out.append(f'<text x="{sx(x):.1f}" y="{TOP + ph + 18}" text-anchor="middle">{x}</text>')
    out.append(f'<rect x="{LEFT}" y="{TOP}" width="{pw}" height="{ph}" fill="none" '
               'stroke="black"/>')
    out.append(f'<text x="{LEFT + pw / 2}" y="{HEIGHT - 18}" text-anchor="middle">'
               'rotation speed (degrees per frame)</text>')
    out.append(f'<text transform="translate(18 {TOP + ph / 2}) rotate(-90)" '
               'text-anchor="middle">patches culled / not drawn</text>')

    legend = []
    for i, (name, pts) in enumerate(scenes.items()):
        color = COLORS[i % len(COLORS)]
        for column, dash, label in ((2, "", "not drawn"), (1, ' stroke-dasharray="6 4"', "cull rate")):
            path = " ".join(f"{sx(p[0]):.1f},{sy(p[column]):.1f}" for p in pts)
            out.append(f'<polyline points="{path}" fill="none" stroke="{color}" '
                       f'stroke-width="2"{dash}/>')
            for p in pts:
                out.append(f'<circle cx="{sx(p[0]):.1f}" cy="{sy(p[column]):.1f}" r="2.5" '
                           f'fill="{color}"/>')
            legend.append((color, dash, f"{name}: {label}"))
    path = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in PAPER)
    out.append(f'<polyline points="{path}" fill="none" stroke="black" stroke-width="1.5" '
               'stroke-dasharray="2 3"/>')
    for x, y in PAPER:
        out.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="4" fill="black"/>')
        out.append(f'<text x="{sx(x) + (8 if x == 0 else -8):.1f}" y="{sy(y) - 8:.1f}" '
                   f'text-anchor="{"start" if x == 0 else "end"}">{y}%</text>')
    legend.append(("black", ' stroke-dasharray="2 3"', "paper (end points)"))

    lx, ly = LEFT + pw + 14, TOP + 8
    for j, (color, dash, label) in enumerate(legend):
        yy = ly + 18 * j
        out.append(f'<line x1="{lx}" y1="{yy}" x2="{lx + 26}" y2="{yy}" stroke="{color}" '
                   f'stroke-width="2"{dash}/>')
        out.append(f'<text x="{lx + 32}" y="{yy + 4}">{escape(label)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("svg", help="output file")
    parser.add_argument("csv", nargs="+", help="bench-occlusion --csv files")
    parser.add_argument("--scenes", help="scene names separated by semicolons (default: all in the CSVs)")
    args = parser.parse_args()
    scenes = read_rows(args.csv)
    if args.scenes:
        wanted = [s.strip() for s in args.scenes.split(";")]
        missing = [s for s in wanted if s not in scenes]
        if missing:
            sys.exit(f"scenes not in {', '.join(args.csv)}: {', '.join(missing)}")
        scenes = {s: scenes[s] for s in wanted}
    with open(args.svg, "w") as f:
        f.write(svg(scenes))


if __name__ == "__main__":
    main()
