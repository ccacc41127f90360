#!/usr/bin/env python3
"""Back-patch cull rate against tessellation level, surface-exact tests against the tests that
respect the drawn triangles, from `osd-cull verify --json` files. Writes an SVG (standard
library only).

  scripts/plots/backpatch_tess.py docs/results/backpatch docs/results/backpatch/tess.svg

Reads DIR/surface-level2-tessN.json and DIR/drawn-level2-tessN.json for every N found.
"""
import json
import re
from pathlib import Path

import plot_cli

METHODS = [("tcone", "#1f77b4"), ("ncone", "#2ca02c"), ("tangent-plane", "#d62728")]


def load(directory):
    rates = {}  # (mode, method) -> {tess: rate}
    for path in sorted(Path(directory).glob("*-level2-tess*.json")):
        m = re.match(r"(surface|drawn)-level2-tess(\d+)\.json", path.name)
        if not m:
            continue
        mode, tess = m.group(1), int(m.group(2))
        doc = json.loads(path.read_text())
        for method in doc["methods"]:
            rates.setdefault((mode, method["name"]), {})[tess] = 100.0 * method["cull_rate_bezier"]
    return rates


def svg(rates):
    width, height, left, right, top, bottom = 700, 400, 60, 210, 30, 50
    tess_values = sorted({t for series in rates.values() for t in series})
    if not tess_values:
        raise SystemExit("no *-level2-tess*.json files")
    ymax = 50.0
    xs = {t: left + i * (width - left - right) / max(1, len(tess_values) - 1)
          for i, t in enumerate(tess_values)}

    def y(v):
        return top + (height - top - bottom) * (1.0 - v / ymax)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           'font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{left}" y="18" font-size="14">BigGuy level 2: back-patch cull rate of the Bézier patches '
           '(sphere views, 256x256)</text>']
    for v in range(0, int(ymax) + 1, 10):
        out.append(f'<line x1="{left}" y1="{y(v):.1f}" x2="{width - right}" y2="{y(v):.1f}" '
                   'stroke="#ddd"/>')
        out.append(f'<text x="{left - 8}" y="{y(v) + 4:.1f}" text-anchor="end">{v}%</text>')
    for t, x in xs.items():
        out.append(f'<text x="{x:.1f}" y="{height - bottom + 18}" text-anchor="middle">{t}</text>')
    out.append(f'<text x="{(left + width - right) / 2:.1f}" y="{height - 10}" '
               'text-anchor="middle">uniform tessellation level</text>')
    legend_y = top + 10
    for method, color in METHODS:
        for mode, dash in (("surface", ""), ("drawn", ' stroke-dasharray="6,4"')):
            series = rates.get((mode, method), {})
            points = " ".join(f"{xs[t]:.1f},{y(v):.1f}" for t, v in sorted(series.items()))
            if points:
                out.append(f'<polyline points="{points}" fill="none" stroke="{color}" '
                           f'stroke-width="2"{dash}/>')
            lx = width - right + 12
            out.append(f'<line x1="{lx}" y1="{legend_y}" x2="{lx + 24}" y2="{legend_y}" '
                       f'stroke="{color}" stroke-width="2"{dash}/>')
            label = f"{method}, {'surface-exact' if mode == 'surface' else 'drawn triangles'}"
            out.append(f'<text x="{lx + 30}" y="{legend_y + 4}" font-size="10">{label}</text>')
            legend_y += 18
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("dir", help="folder of {surface,drawn}-level2-tessN.json (osd-cull verify --json)")
    parser.add_argument("out", help="SVG to write")
    args = parser.parse_args()
    if not Path(args.dir).is_dir():
        parser.error(f"{args.dir}: not a folder")
    Path(args.out).write_text(svg(load(args.dir)))


if __name__ == "__main__":
    main()
