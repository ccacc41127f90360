#!/usr/bin/env python3
"""The function-length check of issue 22 ("No function over ~120 lines without a written
reason"; ../shared/STYLE.md: "functions under ~100").

Scans the C++ sources of osd_cull/, samples/, benchmarks/ and adapters/ with a brace
matcher (comments, strings and preprocessor lines blanked first), finds every function
body at namespace or class scope (a lambda inside a function counts as part of it) and
fails on one longer than LIMIT lines, counted from the first line of its signature to its
closing brace, unless the comment right above it (its \\brief) carries a written reason:

    // long-function: <why this one reads better whole>

Functions listed in scripts/function_length_allow.txt ("path: name" a line) are let
through for now; an entry that no longer names a long function fails the check, so the
list only shrinks.

  check_function_length.py [--root DIR]        exit 1 and list the long functions
  check_function_length.py --plant FILE[:r]    as if FILE ended with a long function (with
                                               ':r', one carrying a reason marker): the
                                               tests that the check can fail and can excuse
  check_function_length.py --list N            every function of N lines or more, longest
                                               first (for finding what to split next)
  check_function_length.py --self-test         the scanner on small known cases
"""
import argparse
import os
import re
import sys

LIMIT = 120
SOURCE_DIRS = ["osd_cull", "samples", "benchmarks", "adapters"]
EXTENSIONS = (".cpp", ".cc", ".h", ".hpp")
ALLOW_LIST = "scripts/function_length_allow.txt"
# The reason must say something: at least a few words after the marker.
MARKER = re.compile(r"long-function:\s*(\S.{9,})")
CONTAINER = re.compile(r"\b(class|struct|union|enum)\b")
IDENT = re.compile(r"(?:[A-Za-z_]\w*\s*::\s*)*(?:operator\s*[^\s\w(]+|operator\s+\w+|~?[A-Za-z_]\w*)\s*$")


def blank(text):
    """The text with comments, string and character literals and preprocessor lines
    replaced by spaces (newlines kept), so braces and parentheses in them do not count."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#" or (line_start and c in " \t" and text[i:].lstrip(" \t").startswith("#")):
            # A preprocessor line (with its continuations).
            j = i
            while j < n:
                if text[j] == "\n" and text[j - 1] != "\\":
                    break
                j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
            continue
        line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                close = ")" + m.group(1) + '"'
                j = text.find(close, i + m.end())
                j = n if j < 0 else j + len(close)
                out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:j]))
                i = j
            else:
                out.append(c)
                i += 1
        elif c in "\"'":
            if c == "'" and i > 0 and (text[i - 1].isalnum()):  # a digit separator: 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else c)
            i = j
        else:
            out.append(c)
            if c == "\n":
                line_start = True
            i += 1
    return "".join(out)


def strip_groups(s):
    """The header with the insides of (), [] and <...> template brackets removed, so what
    is left is its top level."""
    out, depth = [], 0
    for c in s:
        if c in "([":
            if depth == 0:
                out.append(c)
            depth += 1
        elif c in ")]":
            depth = max(depth - 1, 0)
            if depth == 0:
                out.append(c)
        elif depth == 0:
            out.append(c)
    return "".join(out)


def match_brace(code, i):
    """The index of the brace closing the one at code[i]."""
    depth = 0
    for j in range(i, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code) - 1


def in_init_list(top):
    """True when the top-level header `top` stops inside a constructor's member
    initializer list right after a member name (`A::A() : b_{1}`): that brace is the
    member's initializer, not the body."""
    m = re.search(r"\)\s*(?:noexcept\s*)?:(?!:)", top)
    if not m:
        return False
    rest = top[m.end():]
    return bool(re.search(r"[\w>]\s*$", rest))


def classify(header):
    """What a brace opens, judged by the text before it: 'namespace', 'class' (a class,
    struct, union or enum body), 'function' (with its name) or 'other' (an initializer)."""
    h = re.sub(r"^\s*(?:(?:public|private|protected)\s*:\s*)+", "", header)
    top = strip_groups(h)
    if re.search(r"\bnamespace\b", top) or re.match(r'\s*extern\s*""\s*$', top):
        return "namespace", None
    if CONTAINER.search(top) and "(" not in top.replace("operator(", ""):
        return "class", None
    if "(" not in top:
        return "other", None
    lambda_at_scope = re.search(r"=\s*\[\s*\]\s*\(", top)
    if "=" in re.sub(r"operator\s*[=!<>+\-*/%&|^]*=|[=!<>]=|->", "", top) and not lambda_at_scope:
        return "other", None
    if lambda_at_scope:
        name = re.search(r"([A-Za-z_]\w*)\s*=\s*\[", top)
        return "function", name.group(1) if name else "lambda"
    # The name: the identifier before the first top-level parameter list.
    depth, before = 0, h
    for idx, c in enumerate(h):
        if c == "(" and depth == 0:
            before = h[:idx]
            break
        depth += c in "([" and 1 or (-1 if c in ")]" else 0)
    m = IDENT.search(before)
    name = re.sub(r"\s+", "", m.group(0)) if m else "?"
    return "function", name


def functions(text):
    """(name, first line, last line) of every function body at namespace or class scope;
    lines count from 1."""
    code = blank(text)
    found = []
    line_of = lambda pos: code.count("\n", 0, pos) + 1

    def walk(start, stop):
        header_start = start
        i = start
        while i < stop:
            c = code[i]
            if c in ";}":
                header_start = i + 1
            elif c == "{":
                header = code[header_start:i]
                kind, name = classify(header)
                close = match_brace(code, i)
                if kind == "function" and in_init_list(strip_groups(header)):
                    i = close + 1  # a member initializer: the header goes on
                    continue
                if kind in ("namespace", "class"):
                    walk(i + 1, close)
                elif kind == "function":
                    first = header_start + (len(header) - len(header.lstrip()))
                    found.append((name, line_of(first), line_of(close)))
                i = close
                header_start = close + 1
            i += 1

    walk(0, len(code))
    return found


def reason_of(lines, first):
    """The written reason in the comment block right above line `first` (1-based), or
    None."""
    k = first - 2
    while k >= 0 and lines[k].strip().startswith(("//", "/*", "*", "template")):
        m = MARKER.search(lines[k])
        if m:
            return m.group(1).strip()
        k -= 1
    return None


PLANT = "\n// \\brief A planted function of {n} lines (the check's own test).\n{marker}" \
        "int plantedLongFunction() {{\n  int sum = 0;\n{body}  return sum;\n}}\n"


def planted_text(n, with_reason):
    marker = "// long-function: one planted table the test reads whole, kept as written\n" \
        if with_reason else ""
    body = "".join(f"  sum += {k};\n" for k in range(n - 4))
    return PLANT.format(n=n, marker=marker, body=body)


def scan(root, planted=()):
    """(path, name, lines, reason) of every function longer than LIMIT, and the count of
    functions and files seen."""
    long_ones, nfunctions, nfiles = [], 0, 0
    plants = dict(planted)
    for top in SOURCE_DIRS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = sorted(d for d in dirnames if d not in ("build", "Testing", "third_party"))
            for fn in sorted(filenames):
                if not fn.endswith(EXTENSIONS):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, fn), root)
                with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
                    text = f.read()
                if rel in plants:
                    text += planted_text(LIMIT + 5, plants.pop(rel))
                nfiles += 1
                lines = text.split("\n")
                for name, first, last in functions(text):
                    nfunctions += 1
                    length = last - first + 1
                    long_ones.append((rel, name, length, reason_of(lines, first)))
    for rel in plants:
        raise SystemExit(f"check_function_length: --plant names no source file: {rel}")
    return long_ones, nfunctions, nfiles


def read_allow_list(root):
    """The temporary allow-list: {(path, name): line number}."""
    entries = {}
    path = os.path.join(root, ALLOW_LIST)
    if not os.path.isfile(path):
        return entries
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            if ":" not in line:
                raise SystemExit(f"check_function_length: {ALLOW_LIST}:{number}: expected "
                                 f"'path: function name', got '{line}'")
            rel, name = (x.strip() for x in line.split(":", 1))
            entries[(rel, name)] = number
    return entries


SELF_TESTS = [
    ("int f(int a) {\n  return a;\n}\n", [("f", 1, 3)]),
    ("namespace a::b {\nstruct S {\n  int g() const { return 1; }\n};\n}\n", [("g", 3, 3)]),
    ("A::A(int x) : b_{x}, c_(x) {\n  go();\n}\n", [("A::A", 1, 3)]),
    ("const int kT[] = {1, 2};\nvoid h() {\n  auto l = [] { return '}'; };\n}\n", [("h", 2, 4)]),
    ("// { not a brace\nauto k() -> int {\n  return \"{\"[0];\n}\n", [("k", 2, 4)]),
    ("#define M {\nenum class E : int { A, B };\nbool operator==(E, E) {\n  return true;\n}\n",
     [("operator==", 3, 5)]),
    ("const auto lam = [](int v) {\n  return v;\n};\n", [("lam", 1, 3)]),
    ("int big = 1'000;\nvoid q() { if (big) { big = 2; } }\n", [("q", 2, 2)]),
]


def self_test():
    bad = 0
    for text, want in SELF_TESTS:
        got = functions(text)
        if got != want:
            print(f"self-test: {text!r}\n  want {want}\n  got  {got}")
            bad += 1
    lines = ["// \\brief x", "// long-function: a table of nine cases read whole", "void f() {"]
    if reason_of(lines, 3) is None or reason_of(["// long-function: short", "void f() {"], 2):
        print("self-test: the reason marker is not read as written")
        bad += 1
    total = len(SELF_TESTS) + 1
    print(f"check_function_length: self-test: " +
          (f"all {total} cases pass" if not bad else f"{bad} of {total} cases fail"))
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--plant", action="append", default=[], metavar="FILE[:r]")
    ap.add_argument("--list", type=int, metavar="N")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    planted = []
    for p in args.plant:
        rel, _, flag = p.partition(":")
        if flag not in ("", "r"):
            ap.error(f"--plant wants FILE or FILE:r, got '{p}'")
        planted.append((rel, flag == "r"))
    found, nfunctions, nfiles = scan(args.root, planted)
    if nfiles == 0:
        print(f"check_function_length: no sources under {args.root}", file=sys.stderr)
        return 2
    if args.list is not None:
        for rel, name, length, reason in sorted(found, key=lambda f: -f[2]):
            if length >= args.list:
                print(f"{length:5} {rel}: {name}" + (f"  [{reason}]" if reason else ""))
        return 0
    allowed = read_allow_list(args.root)
    bad, excused, listed = [], 0, set()
    for rel, name, length, reason in found:
        if length <= LIMIT:
            continue
        if reason:
            excused += 1
        elif (rel, name) in allowed:
            listed.add((rel, name))
        else:
            bad.append(f"{rel}: {name} is {length} lines (limit {LIMIT}): split it into named "
                       f"steps, or write '// long-function: <reason>' above it")
    for (rel, name), number in sorted(allowed.items(), key=lambda e: e[1]):
        if (rel, name) not in listed:
            bad.append(f"{ALLOW_LIST}:{number}: '{rel}: {name}' is no longer a long function: "
                       f"remove it from the list")
    for b in bad:
        print(b)
    print(f"check_function_length: {nfiles} files, {nfunctions} functions, {excused} long with "
          f"a reason, {len(listed)} on the allow-list, {len(bad)} failing")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
