#!/usr/bin/env python3
"""The accuracy-versus-time study: tables, the plan comparison and the plots.

Reads what scripts/study.sh left in DIR and writes the Markdown page OUT.md, DIR/pareto.png
(one panel per tessellation level) and DIR/breakeven.png (matplotlib; Debian's
python3-matplotlib), then appends DIR/notes.md (the hand-written reading of the figures):

    /usr/bin/python3 scripts/plots/accuracy_vs_time.py docs/results/accuracy-vs-time \
        docs/results/accuracy-vs-time.md

Inputs: `osd-cull verify` JSON per option and tessellation level (NAME-tessN.json: cull
rate, oracle rate, false culls, culls outside the double reference), bench-cull's tables
kernels.md (every kernel's ns/patch, interleaved per view, at every level), frames.md (the
frame-time ratio culled / unculled of every point, interleaved) and breakeven.md (the
measured break-even cull rate), the device calibration calibration.txt (the model's
prediction, Niessner & Loop §6.3) and `osd-cull plan` of each case (plan-CASE-tessN.md),
and run.txt (the command and the load).

The Pareto front per tessellation level and mesh (undisplaced, displaced) is the set of
points with zero false culls and no cull outside the reference, surface-exact excluded (not
conservative for the drawn triangles by construction), that no other such point beats in
both cull rate and kernel ns/patch.
"""
import glob
import json
import os
import re
import sys

import plot_cli
import plot_env  # noqa: F401  (first: finds matplotlib, selects Agg)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OPTIONS = {  # file stem (without -tessN) -> option label
    "bound": "drawn-triangle bound (default)",
    "surface": "surface-exact (papers)",
    "listed": "listed triangles (tightened)",
    "hiz-half-paper": "Hi-Z half res., paper lookup (default)",
    "hiz-full-paper": "Hi-Z full res., paper lookup",
    "hiz-half-tight": "Hi-Z half res., tight lookup",
    "hiz-full-tight": "Hi-Z full res., tight lookup",
    "displaced": "displaced mesh (procedural map)",
}
# A point's name in bench-cull (kernels.md, frames.md): method + suffix of its option.
BENCH_SUFFIX = {"bound": "", "surface": "/surface", "listed": "/listed", "displaced": ""}
HIZ_NAME = {"hiz-half-paper": "hiz", "hiz-full-paper": "hiz/full",
            "hiz-half-tight": "hiz/tight", "hiz-full-tight": "hiz/full-tight"}


def bounds_ms(cal, method):
    """Calibration::boundsMs: the bounds pass per patch of a back-patch method (its own,
    else the pass it shares: tangent-plane-16 that of tangent-plane, the fp64 variants that
    of their fp32 method, else TCONE's)."""
    own = cal["bounds-method"]
    shared = {"tangent-plane-16": "tangent-plane", "tcone-fp64": "tcone", "ncone-fp64": "ncone"}
    for m in (method, shared.get(method)):
        if m in own:
            return own[m]
    return float(cal["bounds"][0])


def bench_name(p):
    if p["option"] in HIZ_NAME:
        return HIZ_NAME[p["option"]]
    return p["method"] + BENCH_SUFFIX.get(p["option"], "?")


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
                "level": run["level"],
                "rate": 100.0 * method["cull_rate"],
                "rate_bezier": 100.0 * method["cull_rate_bezier"],
                "oracle": 100.0 * method["oracle_invisible_rate"],
                "false": method["false_culls"],
                "outside_ref": method["culled_not_in_reference"],
                "ns": method["ns_per_patch"], "ns_source": "verify",
                "displaced": option == "displaced",
            })
    return points


def table_rows(path, ncells):
    """The rows of a Markdown file's tables with `ncells` cells and a number first."""
    if not os.path.exists(path):
        return
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == ncells and cells[0].isdigit():
                yield cells


def load_kernel_ns(folder):
    """kernels.md (bench-cull part 1: level, tess, patches, method, ...): (tess, method) ->
    ns/patch, every kernel timed interleaved per view in one run."""
    return {(int(c[1]), c[3]): float(c[5])
            for c in table_rows(os.path.join(folder, "kernels.md"), 8)}


def attach_bench(points, ns, frames):
    for p in points:
        key = (p["tess"], bench_name(p))
        if key in ns:
            p["ns"] = ns[key]
            p["ns_source"] = "bench"
        p["frame"] = frames.get(key)


def load_frames(folder):
    """frames.md (bench-cull part 2): (tess, mode) -> dict(drawn, tes, ms, ratio)."""
    return {(int(c[0]), c[1]): {"drawn": float(c[2]), "tes": float(c[3]), "ms": float(c[4]),
                                "ratio": float(c[5])}
            for c in table_rows(os.path.join(folder, "frames.md"), 6)}


def load_break_even(folder):
    """breakeven.md: the sweep rows (tess, method, zoom, share, ratio, none ms) and the
    summary rows (tess, method, RT ns/patch, a, b, x*)."""
    sweep, summary = [], []
    for c in table_rows(os.path.join(folder, "breakeven.md"), 6):
        if c[5].endswith("%"):
            summary.append({"tess": int(c[0]), "method": c[1], "rt_ns": float(c[2]),
                            "a": float(c[3]), "b": float(c[4]), "x": float(c[5][:-1])})
        else:
            sweep.append({"tess": int(c[0]), "method": c[1], "zoom": float(c[2]),
                          "share": float(c[3]), "ratio": float(c[4]), "none_ms": float(c[5])})
    return sweep, summary


def load_calibration(folder):
    """calibration.txt (plan/calibration.h toText): name -> list of words."""
    path = os.path.join(folder, "calibration.txt")
    cal = {"draw": {}, "cull": {}, "bounds-method": {}}
    if not os.path.exists(path):
        return None
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "draw":
                cal["draw"][int(w[1])] = float(w[2])
            elif w[0] in ("cull", "bounds-method"):
                cal[w[0]][w[1]] = float(w[2])
            else:
                cal[w[0]] = w[1:]
    return cal


def model_x(cal, tess, method, patches, rt0):
    """Niessner & Loop §6.3: x = (RT0 + CT) / (RT - RT0), RT(tf) and CT per patch from the
    calibration (CT: the frustum kernel plus the method's stage, as the plan counts it, and
    the fixed dispatch spread over the mesh's patches)."""
    rt = draw_ms(cal, tess)
    ct = cal["cull"]["frustum"] + (cal["cull"][method] if method != "frustum" else 0.0)
    ct += float(cal["cull-dispatch"][0]) / patches
    return 100.0 * (rt0 + ct) / (rt - rt0) if rt > rt0 else None  # None: never pays


def draw_ms(cal, tess):
    """Calibration::drawMs: linear in (tf + 1)^2 between the measured levels."""
    levels = sorted(cal["draw"])
    if tess in cal["draw"]:
        return cal["draw"][tess]
    lo = max([t for t in levels if t < tess] or levels[:1])
    hi = min([t for t in levels if t > tess] or levels[-1:])
    if lo == hi:
        lo, hi = levels[-2], levels[-1]
    f = ((tess + 1) ** 2 - (lo + 1) ** 2) / ((hi + 1) ** 2 - (lo + 1) ** 2)
    return cal["draw"][lo] + f * (cal["draw"][hi] - cal["draw"][lo])


def break_even_plot(summary, cal, patches, png):
    rows = []
    fig, ax = plt.subplots(figsize=(7.0, 4.8))
    colors = {"frustum": "tab:gray", "tcone": "tab:blue", "tangent-plane": "tab:orange"}
    methods = [m for m in colors if any(s["method"] == m for s in summary)]
    tess_levels = sorted({s["tess"] for s in summary})
    for m in methods:
        meas = sorted((s["tess"], s["x"]) for s in summary if s["method"] == m)
        ax.plot(*zip(*meas), "o-", color=colors[m], label=f"{m}: measured")
        if cal:
            pred = [(t, model_x(cal, t, m, patches, 0.0)) for t in tess_levels]
            ax.plot(*zip(*pred), "s--", color=colors[m], label=f"{m}: model, RT0 = 0")
            pred0 = [(t, model_x(cal, t, m, patches, float(cal["draw-zero"][0])))
                     for t in tess_levels]
            pred0 = [(t, x) for t, x in pred0 if x is not None]
            if pred0:
                ax.plot(*zip(*pred0), ":", color=colors[m], lw=1,
                        label=f"{m}: model, RT0 calibrated (factor-0 draws)")
        for t, x in meas:
            rows.append((m, t, x,
                         model_x(cal, t, m, patches, 0.0) if cal else None,
                         model_x(cal, t, m, patches, float(cal["draw-zero"][0])) if cal else None))
    sweep = [s for s in summary if s["method"] == "frustum sweep"]
    if sweep:
        ax.plot([s["tess"] for s in sweep], [s["x"] for s in sweep], "x-", color="black", lw=0.8,
                label="frustum sweep fit (its own crossing)")
    ax.axhline(35.8, color="tab:red", lw=0.8, ls=":", label="Niessner & Loop: 35.8% at tess 4 (GPU)")
    ax.axhline(0.0, color="black", lw=0.5)
    ax.set_xscale("log", base=2)
    ax.set_xticks(tess_levels)
    ax.set_xticklabels([str(t) for t in tess_levels])
    ax.set_xlabel("uniform tessellation level")
    ax.set_ylabel("break-even cull rate x (%)")
    ax.set_title("culling pays above the curve: measured on this device and predicted", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=6.5, ncol=2)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    return rows


def percent(x, cal):
    if not cal:
        return ""
    return "never (RT ≤ RT0)" if x is None else f"{x:.1f}%"


def conservative(p):
    return p["false"] == 0 and p["outside_ref"] == 0 and p["option"] != "surface"


def pareto(points):
    ok = [p for p in points if conservative(p)]
    return [p for p in ok
            if not any(q is not p and q["rate"] >= p["rate"] and q["ns"] <= p["ns"]
                       and (q["rate"] > p["rate"] or q["ns"] < p["ns"]) for q in ok)]


def fronts(points, tess):
    """The Pareto fronts of one level: the undisplaced mesh's and the displaced mesh's."""
    pts = [p for p in points if p["tess"] == tess]
    return (pareto([p for p in pts if not p["displaced"]]),
            pareto([p for p in pts if p["displaced"]]))


def label(p):
    return f"{p['method']} / {OPTIONS.get(p['option'], p['option'])}"


def plot(points, tess_levels, path):
    fig, axes = plt.subplots(1, len(tess_levels), figsize=(6.8 * len(tess_levels), 5.6),
                             squeeze=False)
    markers = {"bound": "o", "surface": "s", "listed": "D", "displaced": "^"}
    for ax, tess in zip(axes[0], tess_levels):
        pts = [p for p in points if p["tess"] == tess]
        front, dfront = fronts(points, tess)
        for p in pts:
            marker = markers.get(p["option"], "v")
            color = ("tab:red" if not conservative(p) and p["option"] != "surface"
                     else "tab:green" if p in front or p in dfront
                     else "tab:gray" if p["option"] == "surface" else "tab:blue")
            ax.scatter(p["ns"], p["rate"], marker=marker, color=color, s=34, zorder=3)
            ax.annotate(f"{p['method']} {p['option']}", (p["ns"], p["rate"]), fontsize=5.5,
                        xytext=(3, 2), textcoords="offset points")
        for f, style in ((front, "-"), (dfront, "--")):
            f = sorted(f, key=lambda p: p["ns"])
            ax.step([p["ns"] for p in f], [p["rate"] for p in f], where="post",
                    color="tab:green", lw=1, ls=style, zorder=2)
        ax.set_xscale("log")
        ax.set_xlabel("kernel ns / patch (bench-cull, interleaved, median; log)")
        ax.set_ylabel("patch-views culled (%)")
        ax.set_title(f"tess {tess}: green = Pareto front (solid: BigGuy, dashed: displaced); "
                     "gray = surface-exact; red = false culls", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def load_plan(folder, case, tess):
    """plan-CASE-tessN.md: effect -> (on, choice, predicted ms, reason)."""
    path = os.path.join(folder, f"plan-{case}-tess{tess}.md")
    rows = {}
    if not os.path.exists(path):
        return rows
    with open(path) as f:
        for line in f:
            c = [x.strip() for x in line.strip().strip("|").split("|")]
            if len(c) == 9 and c[1] != "view" and not c[0].startswith("---"):
                rows[c[4].strip("*")] = {"on": c[5], "choice": c[6], "ms": c[7], "reason": c[8]}
    return rows


def recommend(points, tess, case, cal, frames, front_only=True):
    """The study's recommendation for a case: among the points of the case's Pareto front
    (conservative options only), the lowest measured frame ratio; no culling when none is
    below 1. Deforming: the back-patch methods also pay their bounds pass (calibrated)."""
    front, dfront = fronts(points, tess)
    cands = dfront if case == "displaced" else front
    if not front_only:
        cands = [p for p in points if p["tess"] == tess and conservative(p)
                 and p["displaced"] == (case == "displaced")]
    base = frames.get((tess, "displaced:none" if case == "displaced" else "none"))
    scored = []
    for p in cands:
        if p.get("frame") is None:
            continue
        r = p["frame"]["ratio"]
        extra = ""
        if case == "deforming" and p["stage"] == "back-patch" and cal and base:
            bounds = bounds_ms(cal, p["method"]) * p["patches"]
            r += bounds / base["ms"]
            extra = f" (with its bounds pass, {bounds:.1f} ms calibrated)"
        scored.append((r, p, extra))
    if not scored:
        return None, None, ""
    r, p, extra = min(scored, key=lambda s: s[0])
    if r >= 1.0:
        return None, r, extra
    return p, r, extra


def plan_choice(plan):
    """What the plan runs, as "back-patch ncone", "occlusion hiz", "none"."""
    on = [f"{k} {v['choice']}" for k, v in plan.items()
          if k in ("frustum", "back-patch", "occlusion") and v["on"] == "on"]
    return " + ".join(on) if on else "none"


def agreement(best, plan):
    """Whether the plan runs the recommended point: its stage and method, and for Hi-Z its
    resolution and lookup (the plan chooses the resolution; it has no tight lookup)."""
    if not plan:
        return "no plan output"
    runs = {k: v["choice"] for k, v in plan.items()
            if k in ("back-patch", "occlusion") and v["on"] == "on"}
    if best is None:
        return "agree" if not runs else "differ: the plan culls"
    if best["stage"] == "back-patch":
        if runs.get("back-patch") != best["method"]:
            return "differ"
        if best["option"] == "listed":
            return ("agree on the method; the scene form keeps the drawn-triangle bound (one "
                    "cull frame per view); the mesh form chooses it by cost")
        extra = f", the plan adds {runs['occlusion']}" if "occlusion" in runs else ""
        return "agree" + extra
    if best["displaced"]:
        return "agree" if runs.get("occlusion") == best["method"] else "differ"
    if "occlusion" not in runs:
        return "differ"
    notes = []
    full = best["option"].startswith("hiz-full")
    tight = best["option"].endswith("tight")
    choice = plan.get("hi-z", {}).get("choice", "")  # "half/paper", "full/tight", ...
    if full != choice.startswith("full"):
        notes.append("Hi-Z resolution")
    if tight != choice.endswith("tight"):
        notes.append("lookup (the scene form keeps one half-resolution pyramid with the "
                     "paper's lookup per view; the mesh form chooses both by cost)")
    extra = f", the plan adds back-patch {runs['back-patch']}" if "back-patch" in runs else ""
    return ("agree on Hi-Z" + extra) if not notes else ("agree on Hi-Z, differ in " +
                                                        ", ".join(notes) + extra)


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("folder", help="what scripts/study.sh left (docs/results/accuracy-vs-time)")
    parser.add_argument("out", help="the Markdown page to write")
    args = parser.parse_args()
    folder, out = args.folder, args.out
    if not os.path.isdir(folder):
        parser.error(f"{folder}: not a folder")
    points = load_points(folder)
    if not points:
        sys.exit(f"accuracy_vs_time.py: no *-tessN.json in {folder}")
    frames = load_frames(folder)
    attach_bench(points, load_kernel_ns(folder), frames)
    cal = load_calibration(folder)
    sweep, summary = load_break_even(folder)
    tess_levels = sorted({p["tess"] for p in points})
    png = os.path.join(folder, "pareto.png")
    plot(points, tess_levels, png)
    first = points[0]
    patches = first["patches"]
    run = open(os.path.join(folder, "run.txt")).read().splitlines() if os.path.exists(
        os.path.join(folder, "run.txt")) else []
    rel = os.path.basename(folder)
    lines = [
        "# Accuracy against time: every cull method and option, one mesh, the same views",
        "",
        "<!-- written by scripts/plots/accuracy_vs_time.py from scripts/study.sh; edit those -->",
        "",
        f"Mesh {os.path.basename(first['mesh'])} ({patches} patches, level {first['level']}), "
        "sphere views "
        f"(seed 1), {first['width']}x{first['height']}, device {first['device']}. The "
        "displaced points are the same mesh displaced by the procedural map "
        "(`--displacement procedural`, scale in the command).",
        "",
        "Reproduce (one command; the environment variables are in the header of "
        "`scripts/study.sh`, `--quick` makes a small run):",
        "",
        "```",
        *(run[:1] or ["scripts/study.sh"]),
        "```",
        "",
        *[f"- {r}" for r in run[1:]],
        "",
        f"![Pareto plots](accuracy-vs-time/{os.path.basename(png)})",
        "",
        "Columns: `cull` the share of patch-views culled (all patches; `bezier` Bézier only), "
        "`oracle` the share the item-buffer oracle sees no pixel of on the same views (the "
        "ceiling of any conservative test), `false` culled patch-views with a pixel in the "
        "oracle, `!ref` GPU culls the double reference does not make, `ns/patch` the "
        "kernel's median cost (bench-cull, kernels.md: every kernel timed interleaved per "
        "view in one run, at every level; `*` where it did not time the point: verify's "
        "median), `frame` the frame time culled / unculled (bench-cull, frames.md: back "
        "faces culled by the rasterizer on both sides, displaced mesh against its unculled "
        "displaced frame, interleaved per view; Hi-Z: the two-pass frame with frustum and "
        "Hi-Z, a still camera's second frame), `front` on the Pareto front of its level "
        "(BigGuy and displaced BigGuy separately). Back-patch and Hi-Z kernels are timed "
        "alone, as verify runs them; the frame runs the frustum stage too where noted.",
        "",
    ]
    front_ids = set()
    for tess in tess_levels:
        f, d = fronts(points, tess)
        front_ids |= {id(p) for p in f + d}
    for tess in tess_levels:
        nviews = sorted({p["views"] for p in points if p["tess"] == tess})
        lines += [f"## Tessellation {tess}", "",
                  f"Views per verify run: {', '.join(map(str, nviews))}.", "",
                  "| stage | method | option | cull | bezier | oracle | false | !ref | ns/patch "
                  "| frame | front |",
                  "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
        for p in sorted((p for p in points if p["tess"] == tess),
                        key=lambda p: (p["displaced"], p["stage"], p["method"], p["option"])):
            fr = p.get("frame")
            lines.append(
                f"| {p['stage']} | {p['method']} | {OPTIONS.get(p['option'], p['option'])} | "
                f"{p['rate']:.1f}% | {p['rate_bezier']:.1f}% | {p['oracle']:.1f}% | "
                f"{p['false']} | {p['outside_ref']} | "
                f"{p['ns']:.0f}{'' if p['ns_source'] == 'bench' else '*'} | "
                f"{'' if fr is None else format(fr['ratio'], '.2f')} | "
                f"{'yes' if id(p) in front_ids else ''} |")
        lines.append("")
    # The price of exactness: listed and bound against surface-exact, per method.
    lines += ["## The price of exactness", "",
              "Share of the surface-exact (papers') cull rate each conservative option keeps "
              "(Bézier patches and all patches, same views):", "",
              "| tess | method | bound (Bézier) | listed (Bézier) | listed (all) | "
              "surface-exact rate (Bézier) |",
              "|---:|---|---:|---:|---:|---:|"]
    for tess in tess_levels:
        for method in ("tcone", "ncone", "tangent-plane", "tangent-plane-16", "tcone-fp64",
                       "ncone-fp64"):
            get = {p["option"]: p for p in points
                   if p["tess"] == tess and p["method"] == method}
            if not {"bound", "listed", "surface"} <= get.keys():
                continue
            s = get["surface"]["rate_bezier"]
            if s <= 0 or get["surface"]["rate"] <= 0:
                continue
            lines.append(f"| {tess} | {method} | {100 * get['bound']['rate_bezier'] / s:.0f}% | "
                         f"{100 * get['listed']['rate_bezier'] / s:.0f}% | "
                         f"{100 * get['listed']['rate'] / get['surface']['rate']:.0f}% | "
                         f"{s:.1f}% |")
    lines.append("")
    if summary:
        breakeven_png = os.path.join(folder, "breakeven.png")
        rows = break_even_plot(summary, cal, patches, breakeven_png)
        lines += [
            "## Break-even cull rate against tessellation", "",
            f"![break-even](accuracy-vs-time/{os.path.basename(breakeven_png)})", "",
            "Niessner & Loop §6.3 (Fig. 9 left): culling pays when the share culled x exceeds "
            "(RT0 + CT) / (RT − RT0); on their GPU above tess 4 at 35.8%. *Measured* here "
            "(breakeven.md): per view, culled frames over the median unculled frame of the "
            "same view, interleaved; the cull pass tests a frustum narrowed by a zoom of the "
            "projection (1 to 1000) while the frame draws with the real camera, so that a "
            "counted share s of the patches is drawn; a least-squares line r = a + b·s through "
            "the medians per zoom gives the unculled crossing r = 1 at x* = (a + b − 1)/b "
            "(`frustum sweep`). Each method (frustum, and frustum + back-patch stage with "
            "the drawn-triangle bound) is then framed with the real frustum: its intercept "
            "a_m is the median over views of r − b·s and its break-even (a_m + b − 1)/b, "
            "i.e. its whole in-frame cost (dispatch, kernel, compaction, indirect draws) over "
            "the cost of drawing all patches. *Model*: the same formula from the device "
            "calibration (calibration.txt: RT(tf) of the calibration sphere, CT = frustum + "
            "stage kernel + the dispatch over the mesh's patches), with RT0 = 0 (our compact "
            "draw lists do not draw culled patches; what the planner uses) and with the "
            "calibrated RT0 (the paper's factor-0 draws).", "",
            "| method | tess | measured x* | model, RT0 = 0 | model, RT0 calibrated |",
            "|---|---:|---:|---:|---:|"]
        for m, t, x, p0, p1 in rows:
            lines.append(f"| {m} | {t} | {x:.1f}% | {percent(p0, cal)} | {percent(p1, cal)} |")
        lines += ["", "The fits (RT: the unculled BigGuy frame per patch, measured; a, b: the "
                  "line r = a + b·s):", "",
                  "| tess | method | RT ns/patch | a | b | x* |", "|---:|---|---:|---:|---:|---:|"]
        for s in summary:
            lines.append(f"| {s['tess']} | {s['method']} | {s['rt_ns']:.0f} | {s['a']:.3f} | "
                         f"{s['b']:.3f} | {s['x']:.1f}% |")
        if cal:
            lines += ["", "Calibration RT(tf) per patch (ms): " + ", ".join(
                f"tess {t}: {v:.4f}" for t, v in sorted(cal["draw"].items())) +
                f"; RT0 {float(cal['draw-zero'][0]):.4f}; CT (ms/patch): " + ", ".join(
                f"{k} {v:.5f}" for k, v in sorted(cal["cull"].items())) +
                f"; dispatch {float(cal['cull-dispatch'][0]):.3f} ms."]
        lines.append("")
    # The plan's recommendation per case, read off this study.
    frame_tess = sorted({t for t, _ in frames})
    lines += [
        "## The plan's recommendation per case, read off this study", "",
        "Per case the study recommends, among the points on its Pareto front (conservative "
        "options), the one with the lowest measured frame ratio, and no culling when none "
        "is below 1.00. Static: BigGuy as it is; deforming: the same frames plus, for the "
        "back-patch methods (whose per-patch cull data is recomputed when the cage moves), "
        "the calibrated bounds pass of the method per frame (the point update is paid with "
        "or without culling); displaced: the displaced points against the unculled displaced frame. "
        "`osd-cull plan` is asked the same case (a scene of the mesh, one view at the "
        "study's size, frame 1; deforming: a twist deformer; displaced: the procedural "
        "map; plan-*.md). The planner has prior cull rates and one view, the study "
        "measures rates over its views.", "",
        "| case | tess | study recommends (front) | frame ratio | best frame ratio of any "
        "conservative point | plan runs | plan predicts | agree | why they differ (plan's "
        "reason) |",
        "|---|---:|---|---:|---|---|---|---|---|"]
    for case in ("static", "deforming", "displaced"):
        for tess in frame_tess:
            best, r, extra = recommend(points, tess, case, cal, frames)
            plan = load_plan(folder, case, tess)
            agree = agreement(best, plan)
            rec = f"**{label(best)}**" if best else "no culling"
            ratio = "" if r is None else f"{r:.2f}{extra}"
            why = ""
            if agree.startswith("differ"):
                reasons = [f"{k}: {v['reason']}" for k, v in plan.items()
                           if k in ("back-patch", "occlusion")]
                why = "; ".join(reasons)
            frame_row = plan.get("frame", {})
            anyp, anyr, _ = recommend(points, tess, case, cal, frames, front_only=False)
            best_any = f"{label(anyp)} {anyr:.2f}" if anyp else ""
            lines.append(f"| {case} | {tess} | {rec} | {ratio} | {best_any} | "
                         f"{plan_choice(plan)} | {frame_row.get('reason', '')} | {agree} | "
                         f"{why} |")
    lines.append("")
    notes = os.path.join(folder, "notes.md")  # the hand-written reading of the figures
    if os.path.exists(notes):
        with open(notes) as f:
            lines += [f.read()]
    with open(out, "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
