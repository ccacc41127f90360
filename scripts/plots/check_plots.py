#!/usr/bin/env python3
"""Runs one plot script of scripts/plots (or all) the way a user would, and checks it.

    scripts/plots/check_plots.py --root . --only plan

For each script: `--help` exits 0, prints "usage:" and writes no file; the script draws its
picture from the inputs committed under docs/results into a temporary folder (an image
with the PNG signature or an <svg> element and at least 1 KB, or the CSV / Markdown page it
writes); an empty input ends with a one-line error naming the problem, not a traceback.
Prints "plot NAME: ok" per script, or the failures, and exits 1 on any failure.
"""
import os
import shutil
import subprocess
import sys
import tempfile

import plot_cli

R = "docs/results"
# name -> (arguments, files it must write, index of the argument replaced by an empty file)
# "{T}" is the temporary folder, "{R}" the results folder of the source tree.
CASES = {
    "accuracy_vs_time": (["{T}/avt", "{T}/avt.md"], ["avt.md", "avt/pareto.png"], None),
    "animation_speed": (["{T}/out.png", "{R}/animation/animation_speed.csv"], ["out.png"], 1),
    "backpatch_kernel_cost": (["{R}/backpatch/kernel_cost.txt", "{T}/out.svg"], ["out.svg"], 0),
    "backpatch_tess": (["{R}/backpatch", "{T}/out.svg"], ["out.svg"], None),
    "displacement_table1": (["{T}/out.svg", "{R}/displacement/bigguy_level0.json",
                             "{R}/displacement/bigguy_level1.json"], ["out.svg"], 1),
    "frame_cost": (["{R}/frame-cost/frame_cost.csv", "{T}/out.png"], ["out.png"], 0),
    "frame_cost_tables": (["{T}/out.csv", "{R}/frame-cost/bench_frame_cost.md"], ["out.csv"], 1),
    "large_coordinates": (["{R}/scene/large_coordinates.csv", "{T}/out.svg"], ["out.svg"], 0),
    "occlusion_rotation": (["{T}/out.svg", "{R}/occlusion/rotation.csv"], ["out.svg"], 1),
    "plan": (["{R}/plan/plan.csv", "{T}/out.png"], ["out.png"], 0),
    "scale": (["{R}/scale/bench_scale.md", "{T}/out.svg"], ["out.svg"], 0),
}


def looks_written(path):
    """A picture with its format's signature and some content, or a non-empty text file."""
    if not os.path.isfile(path):
        return f"{path} was not written"
    data = open(path, "rb").read()
    if path.endswith(".png"):
        ok = data.startswith(b"\x89PNG\r\n\x1a\n") and len(data) > 1024
    elif path.endswith(".svg"):
        ok = b"<svg" in data[:2000] and len(data) > 1024
    else:
        ok = len(data.strip().splitlines()) >= 2
    return None if ok else f"{path}: not a drawn {os.path.splitext(path)[1]} ({len(data)} bytes)"


def run(script, args, cwd):
    return subprocess.run([sys.executable, script] + args, cwd=cwd, capture_output=True, text=True,
                          timeout=300)


def check(root, name):
    script = os.path.join(root, "scripts", "plots", name + ".py")
    args, outputs, empty_at = CASES[name]
    failures = []
    with tempfile.TemporaryDirectory() as t:
        help_dir = os.path.join(t, "help")
        os.mkdir(help_dir)
        p = run(script, ["--help"], help_dir)
        if p.returncode != 0 or "usage:" not in p.stdout:
            failures.append(f"--help: exit {p.returncode}, output {p.stdout[:200]!r}{p.stderr[:300]!r}")
        if os.listdir(help_dir):
            failures.append(f"--help wrote {os.listdir(help_dir)}")
        if name == "accuracy_vs_time":  # it writes its plots into the folder it reads
            shutil.copytree(os.path.join(root, R, "accuracy-vs-time"), os.path.join(t, "avt"))
        full = [a.replace("{T}", t).replace("{R}", os.path.join(root, R)) for a in args]
        p = run(script, full, t)
        if p.returncode != 0:
            failures.append(f"on {R}: exit {p.returncode}: {p.stderr[-600:]}")
        failures += [f for f in (looks_written(os.path.join(t, o)) for o in outputs) if f]
        if empty_at is not None:
            empty = os.path.join(t, "empty" + os.path.splitext(full[empty_at])[1])
            open(empty, "w").close()
            bad = list(full)
            bad[empty_at] = empty
            p = run(script, bad, t)
            if p.returncode == 0 or "Traceback" in p.stderr or not p.stderr.strip():
                failures.append(f"an empty {os.path.basename(empty)}: exit {p.returncode}, "
                                f"stderr {p.stderr[-400:]!r}")
    return failures


def main():
    parser = plot_cli.parser(__doc__)
    parser.add_argument("--root", default=".", help="the source tree (default: .)")
    parser.add_argument("--only", choices=sorted(CASES), help="one script (default: all)")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    failed = 0
    for name in [args.only] if args.only else sorted(CASES):
        failures = check(root, name)
        print(f"plot {name}: " + ("ok" if not failures else "FAILED"))
        for f in failures:
            print("  " + f)
        failed += bool(failures)
    listed = {f[:-3] for f in os.listdir(os.path.join(root, "scripts", "plots"))
              if f.endswith(".py") and f not in ("plot_env.py", "plot_cli.py", "check_plots.py")}
    if not args.only and listed != set(CASES):
        print(f"plot scripts without a case here: {sorted(listed - set(CASES))}")
        failed += 1
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
