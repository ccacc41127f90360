#!/usr/bin/env python3
"""The accuracy-versus-time study: tables, recommendations and the Pareto plot.

Reads what scripts/study.sh left in DIR (`osd-cull verify` JSON per option and tessellation
level, bench-cull's interleaved frame table frames.md) and writes the Markdown page OUT.md
and DIR/pareto.png (matplotlib; Debian's python3-matplotlib), then appends DIR/notes.md
(the hand-written reading of the figures):

    /usr/bin/python3 scripts/plots/accuracy_vs_time.py docs/results/accuracy-vs-time \
        docs/results/accuracy-vs-time.md

A point is one method with one option: its cull rate, the oracle's invisible rate on the
same views, false culls, culls outside the double reference, the kernel's ns/patch (verify's
median over its views) and the frame-time ratio culled / unculled (bench-cull, where the
method draws through the cull pass alone). The Pareto front per tessellation level is the
set of zero-false-cull points, surface-exact excluded (not conservative by construction),
that no other such point beats in both cull rate and ns/patch.
"""
import glob
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OPTIONS = {  # file stem (without -tessN) -> (option label, drawn-triangle handling)
    "bound": "drawn-triangle bound (default)",
    "surface": "surface-exact (papers)",
    "listed": "listed triangles (tightened)",
    "hiz-half-paper": "Hi-Z half res., paper lookup (default)",
    "hiz-full-paper": "Hi-Z full res., paper lookup",
    "hiz-half-tight": "Hi-Z half res., tight lookup",
    "hiz-full-tight": "Hi-Z full res., tight lookup",
    "displaced": "displaced bound (2% amplitude)",
}
FRAME_SUFFIX = {"bound": "", "surface": "/surface", "listed": "/listed"}


def load_points(folder):
    points = []
    for path in sorted(glob.glob(os.path.join(folder, "*-tess*.json"))):
        stem = os.path.basename(path)[:-5]
        m = re.fullmatch(r"(.*)-tess(\d+)", stem)
        option, tess = m.group(1), int(m.group(2))
        with open(path) as f:
            run = json.load(f)
        for method in run["methods"]:
            if method["name"] == "frustum" and option != "bound":
                continue  # the frustum stage runs in every verify run; keep one
            if option == "displaced" and method["name"] == "hiz":
                continue  # the undisplaced kernel against the displaced draw: not a choice
            points.append({
                "option": option, "tess": tess, "method": method["name"],
                "stage": method["stage"], "views": run["views"],
                "width": run["width"], "height": run["height"],
                "patches": run["patches"], "device": run["device"], "mesh": run["mesh"],
                "rate": 100.0 * method["cull_rate"],
                "rate_bezier": 100.0 * method["cull_rate_bezier"],
                "oracle": 100.0 * method["oracle_invisible_rate"],
                "false": method["false_culls"],
                "outside_ref": method["culled_not_in_reference"],
                "ns": method["ns_per_patch"],
            })
    return points


def table_rows(folder, ncells):
    """The rows of frames.md's Markdown tables with `ncells` cells and a number first."""
    path = os.path.join(folder, "frames.md")
    if not os.path.exists(path):
        return
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == ncells and cells[0].isdigit():
                yield cells


def load_kernel_ns(folder):
    """bench-cull part 1 rows (level, tess, patches, method, ...): (tess, method) -> ns/patch,
    every kernel timed interleaved per view in one run."""
    return {(int(c[1]), c[3]): float(c[5]) for c in table_rows(folder, 8)}


def attach_bench_ns(points, ns):
    """Use bench-cull's interleaved ns/patch where it timed the point's kernel."""
    suffix = {"bound": "", "surface": "/surface", "listed": "/listed"}
    for p in points:
        key = (p["tess"], p["method"] + suffix.get(p["option"], "?"))
        if p["option"] in suffix and key in ns:
            p["ns"] = ns[key]
            p["ns_source"] = "bench"


def load_frame_rows(folder):
    """bench-cull part 2 rows: (tess, mode) -> (patches drawn, frame ms, ratio to none)."""
    return {(int(c[0]), c[1]): (float(c[2]), float(c[4]), float(c[5]))
            for c in table_rows(folder, 6)}


def load_frames(folder):
    """(tess, mode) -> frame-time ratio to none."""
    return {k: v[2] for k, v in load_frame_rows(folder).items()}


def break_even(points, rows, png):
    """Nießner & Loop §6.3 / Fig. 9 left: the cull rate at which culling pays, against the
    tessellation level. Model: x = (RT0 + CT) / (RT - RT0), RT the unculled frame time per
    patch at that level, CT the kernel's ns/patch (verify, tess 4), RT0 = 0 (culled patches
    are dropped from the indirect draws, not drawn with factor 0). Measured: from the
    culled frame, r = CT'/RT + (1 - x) with x the share not drawn, so the break-even rate is
    x + r - 1 (CT' the whole in-frame cost of culling: dispatch, kernel, draw compaction)."""
    if not rows:
        return []
    n = next(p["patches"] for p in points)
    tess_levels = sorted({t for t, _ in rows})
    table = []
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    for method, color in (("tcone", "tab:blue"), ("tangent-plane", "tab:orange")):
        ct = [p["ns"] for p in points if p["method"] == method and p["option"] == "bound"
              and p["tess"] == 4]
        if not ct:
            continue
        measured, predicted = [], []
        for t in tess_levels:
            if (t, "none") not in rows or (t, method) not in rows:
                continue
            rt = rows[(t, "none")][1] * 1e6 / n  # ns per patch
            drawn, _, r = rows[(t, method)]
            x = 1.0 - drawn / n
            measured.append((t, 100.0 * (x + r - 1.0)))
            predicted.append((t, 100.0 * ct[0] / rt))
            table.append((method, t, rt, ct[0], 100.0 * x, r, 100.0 * (x + r - 1.0),
                          100.0 * ct[0] / rt))
        ax.plot(*zip(*measured), "o-", color=color, label=f"{method}: measured x + r - 1")
        ax.plot(*zip(*predicted), "s--", color=color, label=f"{method}: model CT / RT")
    ax.axhline(35.8, color="gray", lw=0.8, ls=":", label="paper: 35.8% at tess 4 (GPU)")
    ax.set_xscale("log", base=2)
    ax.set_xticks(tess_levels)
    ax.set_xticklabels([str(t) for t in tess_levels])
    ax.set_xlabel("uniform tessellation level")
    ax.set_ylabel("break-even cull rate (%)")
    ax.set_title("culling pays above the curve (drawn-triangle bound)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    return table


def frame_ratio(point, ratios):
    if point["option"] not in FRAME_SUFFIX or point["stage"] != "back-patch":
        return None
    return ratios.get((point["tess"], point["method"] + FRAME_SUFFIX[point["option"]]))


def pareto(points):
    # Options conservative by construction only: surface-exact is plotted for reference.
    ok = [p for p in points if p["false"] == 0 and p["outside_ref"] == 0
          and p["option"] != "surface"]
    return [p for p in ok
            if not any(q is not p and q["rate"] >= p["rate"] and q["ns"] <= p["ns"]
                       and (q["rate"] > p["rate"] or q["ns"] < p["ns"]) for q in ok)]


def label(p):
    return f"{p['method']} / {OPTIONS.get(p['option'], p['option'])}"


def plot(points, tess_levels, path):
    fig, axes = plt.subplots(1, len(tess_levels), figsize=(6.5 * len(tess_levels), 5.2),
                             squeeze=False)
    markers = {"bound": "o", "surface": "s", "listed": "D", "displaced": "^"}
    for ax, tess in zip(axes[0], tess_levels):
        pts = [p for p in points if p["tess"] == tess]
        front = pareto(pts)
        for p in pts:
            marker = markers.get(p["option"], "v")
            color = "tab:red" if p["false"] > 0 else ("tab:green" if p in front else "tab:blue")
            ax.scatter(p["ns"], p["rate"], marker=marker, color=color, s=36, zorder=3)
            ax.annotate(f"{p['method']}\n{p['option']}", (p["ns"], p["rate"]), fontsize=6,
                        xytext=(3, 2), textcoords="offset points")
        front.sort(key=lambda p: p["ns"])
        ax.step([p["ns"] for p in front], [p["rate"] for p in front], where="post",
                color="tab:green", lw=1, zorder=2)
        ax.set_xscale("log")
        ax.set_xlabel("kernel ns / patch (median over views, log)")
        ax.set_ylabel("patches culled (%)")
        ax.set_title(f"tess {tess}: green = Pareto front (conservative options), red = false culls",
                     fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    folder, out = sys.argv[1], sys.argv[2]
    points = load_points(folder)
    attach_bench_ns(points, load_kernel_ns(folder))
    ratios = load_frames(folder)
    breakeven_png = os.path.join(folder, "breakeven.png")
    breakeven = break_even(points, load_frame_rows(folder), breakeven_png)
    if not points:
        sys.exit(f"accuracy_vs_time.py: no *-tessN.json in {folder}")
    tess_levels = sorted({p["tess"] for p in points})
    png = os.path.join(folder, "pareto.png")
    plot(points, tess_levels, png)
    first = points[0]
    lines = [
        "# Accuracy against time: every cull method and option, one mesh, the same views",
        "",
        "<!-- written by scripts/plots/accuracy_vs_time.py from scripts/study.sh; edit those -->",
        "",
        f"Mesh {os.path.basename(first.get('mesh', 'bigguy.obj'))} ({first['patches']} patches), "
        f"sphere views (seed 1), {first['width']}x{first['height']}, "
        f"device {first['device']}. Reproduce: `scripts/study.sh` (environment variables in "
        "its header), then this page is written by `scripts/plots/accuracy_vs_time.py`.",
        "",
        f"![Pareto plot](accuracy-vs-time/{os.path.basename(png)})",
        "",
        "Columns: `cull` the share of patch-views culled (all patches; `bezier` Bézier only), "
        "`oracle` the share the item-buffer oracle sees no pixel of on the same views (the "
        "ceiling of any conservative test), `false` culled patch-views with a pixel in the "
        "oracle, `!ref` GPU culls the double reference does not make, `ns/patch` the "
        "kernel's median cost (bench-cull part 1, every kernel interleaved per view in one "
        "run, where it timed the point; else verify's, marked *), `frame` the frame time culled / unculled (bench-cull, "
        "back faces culled by the rasterizer on both sides, interleaved per view; back-patch "
        "stages only), `front` on the Pareto front of its tessellation level.",
        "",
    ]
    front_ids = set()
    for tess in tess_levels:
        front_ids |= {id(p) for p in pareto([p for p in points if p["tess"] == tess])}
    for tess in tess_levels:
        nviews = sorted({p["views"] for p in points if p["tess"] == tess})
        lines += [f"## Tessellation {tess}", "",
                  f"Views per verify run: {', '.join(map(str, nviews))} (the first views of one "
                  "seeded sequence; which run had how many: `oracle` differs with the count, "
                  "and the commands at the end say).",
                  "",
                  "| stage | method | option | cull | bezier | oracle | false | !ref | ns/patch "
                  "| frame | front |",
                  "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
        for p in sorted((p for p in points if p["tess"] == tess),
                        key=lambda p: (p["stage"], p["method"], p["option"])):
            r = frame_ratio(p, ratios)
            lines.append(
                f"| {p['stage']} | {p['method']} | {OPTIONS.get(p['option'], p['option'])} | "
                f"{p['rate']:.1f}% | {p['rate_bezier']:.1f}% | {p['oracle']:.1f}% | "
                f"{p['false']} | {p['outside_ref']} | {p['ns']:.0f}{'' if p.get('ns_source') else '*'} | "
                f"{'' if r is None else f'{r:.2f}'} | {'yes' if id(p) in front_ids else ''} |")
        lines.append("")
    # The price of exactness: listed and bound against surface-exact, per method.
    lines += ["## The price of exactness", "",
              "Share of the surface-exact (papers') cull rate each conservative option keeps "
              "(Bézier patches, same views):", "",
              "| tess | method | bound | listed | surface-exact rate |",
              "|---:|---|---:|---:|---:|"]
    for tess in tess_levels:
        for method in ("tcone", "ncone", "tangent-plane", "tangent-plane-16", "tcone-fp64",
                       "ncone-fp64"):
            get = {p["option"]: p for p in points
                   if p["tess"] == tess and p["method"] == method}
            if not {"bound", "listed", "surface"} <= get.keys():
                continue
            s = get["surface"]["rate_bezier"]
            if s <= 0:
                continue
            lines.append(f"| {tess} | {method} | {100 * get['bound']['rate_bezier'] / s:.0f}% | "
                         f"{100 * get['listed']['rate_bezier'] / s:.0f}% | {s:.1f}% |")
    lines.append("")
    if breakeven:
        lines += ["## Break-even cull rate against tessellation", "",
                  f"![break-even](accuracy-vs-time/{os.path.basename(breakeven_png)})", "",
                  "Nießner & Loop §6.3: culling pays when the share culled x exceeds "
                  "(RT0 + CT) / (RT − RT0) (their Fig. 9 left: 35.8% at tess 4). RT: the "
                  "unculled frame per patch; CT: the kernel's ns/patch (bench-cull, tess 4); "
                  "RT0 = 0 here (culled patches leave the indirect draws). Measured: x + r − 1 "
                  "from the culled frame's ratio r and its share not drawn x, i.e. the whole "
                  "in-frame cost of culling over RT.", "",
                  "| method | tess | RT ns/patch | CT ns/patch | x | ratio r | measured | model |",
                  "|---|---:|---:|---:|---:|---:|---:|---:|"]
        for method, t, rt, ct, x, r, meas, pred in breakeven:
            lines.append(f"| {method} | {t} | {rt:.0f} | {ct:.0f} | {x:.1f}% | {r:.2f} | "
                         f"{meas:.1f}% | {pred:.1f}% |")
        lines.append("")
    # Recommendations: per tessellation level and stage, the zero-false-cull point with the
    # best frame ratio where measured, else the front's highest rate per ns.
    lines += ["## Recommended per case (read by the planner)", "",
              "Among the options that are conservative by construction (not surface-exact): "
              "the lowest measured frame ratio where bench-cull drew the option, else the "
              "highest cull rate.", ""]
    for tess in tess_levels:
        for stage in ("back-patch", "occlusion"):
            # Only options that are conservative by construction: surface-exact culls can
            # take silhouette pixels even where this sample measured none.
            pts = [p for p in points if p["tess"] == tess and p["stage"] == stage
                   and p["false"] == 0 and p["outside_ref"] == 0
                   and p["option"] not in ("displaced", "surface")]
            if not pts:
                continue
            framed = [p for p in pts if frame_ratio(p, ratios) is not None]
            if framed:
                best = min(framed, key=lambda p: frame_ratio(p, ratios))
                why = f"lowest measured frame ratio {frame_ratio(best, ratios):.2f}"
            else:
                best = max(pts, key=lambda p: (p["rate"], -p["ns"]))
                why = f"highest cull rate {best['rate']:.1f}% at {best['ns']:.0f} ns/patch"
            lines.append(f"- tess {tess}, {stage}: **{label(best)}** ({why}).")
        disp = [p for p in points if p["tess"] == tess and p["option"] == "displaced"
                and p["false"] == 0]
        if disp:
            best = max(disp, key=lambda p: (p["rate"], -p["ns"]))
            lines.append(f"- tess {tess}, displaced mesh: **{best['method']}** "
                         f"({best['rate']:.1f}% culled, {best['ns']:.0f} ns/patch).")
    lines.append("")
    notes = os.path.join(folder, "notes.md")  # the hand-written reading of the figures
    if os.path.exists(notes):
        with open(notes) as f:
            lines += [f.read()]
    with open(out, "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
