#!/usr/bin/env python3
"""The layer check of ../shared/DESIGN.md ("An include never runs up this order").

Reads every quoted #include of the C++ sources, maps both ends to a layer and fails when a
file includes a layer its own layer may not use. The table LAYERS below is the order
written in DESIGN.md (lowest first) with, for each layer, the layers below it that it may
use; docs/architecture.md holds the picture generated from it and from the includes
(--write-doc), and the tests check that the picture is current (--check-doc).

  check_layers.py [--root DIR]                  exit 1 and list the upward includes
  check_layers.py --plant FROM:TO               as if FROM also included TO (the test
                                                 that the check can fail)
  check_layers.py --write-doc | --check-doc     docs/architecture.md's layer block
"""
import argparse
import os
import re
import sys
from collections import defaultdict

# (layer, folders it covers, layers it may include besides itself), lowest first.
# patch and bound are the CPU side (no Vulkan); vk and osd the device side; frame uses
# both. Above it: scene descriptions and animation, the plan's model (reads scene
# descriptions), the measurement of a device's calibration (runs frames and scenes to fill
# the plan's model), the sessions that play a planned mesh or scene, then the file loaders
# and the programs. `shaders` holds the struct layouts shared by C++ and GLSL: any layer
# may include them.
LAYERS = [
    ("base", ["osd_cull/error.h", "osd_cull/hash.h", "osd_cull/version.cpp", "osd_cull/version.h"], []),
    ("patch", ["osd_cull/patch/"], ["base"]),
    ("bound", ["osd_cull/bound/"], ["base", "patch"]),
    ("vk", ["osd_cull/vk/"], ["base"]),
    ("osd", ["osd_cull/osd/"], ["base", "patch", "vk"]),
    ("frame", ["osd_cull/frame/"], ["base", "patch", "bound", "vk", "osd"]),
    ("scene", ["osd_cull/scene/"], ["base", "patch", "bound", "vk", "osd", "frame"]),
    ("plan", ["osd_cull/plan/"], ["base", "patch", "bound", "vk", "osd", "frame", "scene"]),
    ("measure", ["osd_cull/measure/"],
     ["base", "patch", "bound", "vk", "osd", "frame", "scene", "plan"]),
    ("session", ["osd_cull/session/"],
     ["base", "patch", "bound", "vk", "osd", "frame", "scene", "plan", "measure"]),
    ("adapters", ["adapters/"],
     ["base", "patch", "bound", "vk", "osd", "frame", "scene", "plan", "measure", "session"]),
    ("programs", ["samples/", "benchmarks/", "tools/"],
     ["base", "patch", "bound", "vk", "osd", "frame", "scene", "plan", "measure", "session",
      "adapters"]),
    ("tests", ["tests/"],
     ["base", "patch", "bound", "vk", "osd", "frame", "scene", "plan", "measure", "session",
      "adapters", "programs"]),
]
ORDER = [name for name, _, _ in LAYERS]
ALLOWED = {name: set(allowed) | {name, "shaders"} for name, _, allowed in LAYERS}
# Headers no CPU-reference layer may include (DESIGN.md: "CPU reference math never depends
# on Vulkan").
NO_VULKAN = {"patch", "bound"}
SOURCE_DIRS = ["osd_cull", "adapters", "samples", "benchmarks", "tools", "tests"]
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]', re.M)
DOC = "docs/architecture.md"
BEGIN, END = "<!-- layers:begin (scripts/check_layers.py --write-doc) -->", "<!-- layers:end -->"


def layer_of(path):
    """The layer of a path relative to the root, or None (outside every layer)."""
    for name, folders, _ in LAYERS:
        for f in folders:
            if path == f or (f.endswith("/") and path.startswith(f)):
                return name
    if path.startswith("shaders/"):
        return "shaders"
    return None


def resolve(root, including, target):
    """The root-relative file a quoted include names: the including file's folder first,
    then the include roots of the build (project root, shaders/, generated headers)."""
    for base in (os.path.dirname(including), "", "shaders"):
        candidate = os.path.normpath(os.path.join(base, target))
        if os.path.isfile(os.path.join(root, candidate)):
            return candidate
    if target.startswith("osd_cull/"):  # generated (version.h) or not yet on disk
        return target
    return None


def scan(root, planted=()):
    """Every include edge (from, to, kind) of the sources; kind 'quote' or 'system'."""
    edges = []
    for top in SOURCE_DIRS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = [d for d in dirnames if d not in ("build", "Testing")]
            for fn in sorted(filenames):
                if not fn.endswith((".h", ".hpp", ".cpp", ".cc")):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, fn), root)
                with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
                    text = f.read()
                for kind, target in INCLUDE.findall(text):
                    if kind == "<":
                        edges.append((rel, target, "system"))
                    else:
                        to = resolve(root, rel, target)
                        if to is not None:
                            edges.append((rel, to, "quote"))
    for frm, to in planted:
        edges.append((frm, to, "quote"))
    return edges


def violations(edges):
    out = []
    for frm, to, kind in edges:
        a = layer_of(frm)
        if a is None:
            continue
        if kind == "system":
            if a in NO_VULKAN and to.startswith("vulkan/"):
                out.append(f"{frm}: includes <{to}>: the {a} layer is CPU-only (no Vulkan)")
            continue
        b = layer_of(to)
        if b is None or b in ALLOWED[a]:
            continue
        out.append(f"{frm}: includes {to}: layer '{a}' may not use layer '{b}' "
                   f"(order, lowest first: {' -> '.join(ORDER)})")
    return out


def picture(edges):
    """The generated layer block of docs/architecture.md."""
    uses = defaultdict(lambda: defaultdict(int))
    for frm, to, kind in edges:
        a, b = layer_of(frm), layer_of(to) if kind == "quote" else None
        if a and b and a != b and b != "shaders":
            uses[a][b] += 1
    lines = [BEGIN, "", "Layers, lowest first, each with the lower layers its files include; generated",
             "from the sources by `scripts/check_layers.py --write-doc` and checked by the test",
             "`Layers.DocIsCurrent`:", "", "```"]
    for name, folders, _ in LAYERS:
        used = ", ".join(b for b in ORDER if uses[name].get(b))
        lines.append(f"{name:9} {' '.join(folders)}")
        lines.append(f"{'':9}   uses: {used or '-'}")
    lines += ["```", "", END]
    return "\n".join(lines)


def doc_block(root):
    with open(os.path.join(root, DOC), encoding="utf-8") as f:
        text = f.read()
    if BEGIN not in text or END not in text:
        return text, None
    start = text.index(BEGIN)
    stop = text.index(END) + len(END)
    return text, (start, stop)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--plant", action="append", default=[], metavar="FROM:TO")
    ap.add_argument("--write-doc", action="store_true")
    ap.add_argument("--check-doc", action="store_true")
    args = ap.parse_args()
    planted = []
    for p in args.plant:
        if ":" not in p:
            ap.error(f"--plant wants FROM:TO, got '{p}'")
        planted.append(tuple(p.split(":", 1)))
    edges = scan(args.root, planted)
    if not edges:
        print(f"check_layers: no sources under {args.root}", file=sys.stderr)
        return 2
    if args.write_doc or args.check_doc:
        text, span = doc_block(args.root)
        if span is None:
            print(f"check_layers: {DOC} has no block {BEGIN} ... {END}", file=sys.stderr)
            return 1
        new = text[:span[0]] + picture(edges) + text[span[1]:]
        if args.write_doc:
            with open(os.path.join(args.root, DOC), "w", encoding="utf-8") as f:
                f.write(new)
            print(f"check_layers: wrote the layer picture into {DOC}")
            return 0
        if new != text:
            print(f"check_layers: {DOC}'s layer picture is out of date: run "
                  "scripts/check_layers.py --write-doc", file=sys.stderr)
            return 1
        print(f"check_layers: {DOC}'s layer picture is current")
        return 0
    bad = violations(edges)
    for v in bad:
        print(v)
    files = len({e[0] for e in edges})
    print(f"check_layers: {files} files, {len(edges)} includes, {len(bad)} upward")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
