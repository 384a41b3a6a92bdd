#!/usr/bin/env python3
"""docs/api.md's example programs against the files that are built and run (CTest docs_api).

Usage: check_api_examples.py ROOT NAME=PROGRAM...
       check_api_examples.py --update ROOT     (rewrites api.md's code blocks from the files)

The example programs are docs/examples/NAME.cpp, built by tests/CMakeLists.txt against the
build tree's libraries (a build that fails to compile one fails CI). docs/api.md shows each one
after a marker line, and its output after another:

    <!-- example: docs/examples/NAME.cpp -->
    ```cpp
    (the file, exactly)
    ```
    <!-- output: docs/examples/NAME.cpp -->
    ```text
    (what the program prints, exactly)
    ```

Fails (exit 1, one line per problem) when a file under docs/examples/ has no example marker in
docs/api.md or no program given here, when a code block differs from its file, or when a program
exits non-zero or prints other than its output block. The outputs are derived by hand in each
file's opening comment; `--update` refreshes only the code blocks, never an output.
"""
import difflib
import os
import re
import subprocess
import sys

MARKER = re.compile(r"^<!-- (example|output): (docs/examples/[\w.-]+\.cpp) -->$")


def blocks(lines):
    """{(kind, path): (first, last)}: the line range of the fenced block after each marker."""
    found = {}
    for i, line in enumerate(lines):
        m = MARKER.match(line.rstrip("\n"))
        if not m:
            continue
        key = (m.group(1), m.group(2))
        if key in found:
            raise SystemExit(f"check_api_examples: docs/api.md:{i + 1}: a second {key[0]} marker for {key[1]}")
        if i + 1 >= len(lines) or not lines[i + 1].startswith("```"):
            raise SystemExit(f"check_api_examples: docs/api.md:{i + 1}: no fenced block right after the marker")
        end = next((j for j in range(i + 2, len(lines)) if lines[j].rstrip("\n") == "```"), None)
        if end is None:
            raise SystemExit(f"check_api_examples: docs/api.md:{i + 2}: the fenced block is not closed")
        found[key] = (i + 2, end)
    return found


def differ(label, want, got):
    diff = difflib.unified_diff(want.splitlines(), got.splitlines(), "docs/api.md", label, lineterm="", n=1)
    return "\n".join(diff)


def update(root):
    api = os.path.join(root, "docs", "api.md")
    lines = open(api, encoding="utf-8").readlines()
    ranges = sorted(((r, p) for (kind, p), r in blocks(lines).items() if kind == "example"), reverse=True)
    for (first, last), path in ranges:
        text = open(os.path.join(root, path), encoding="utf-8").read()
        lines[first:last] = [text if text.endswith("\n") else text + "\n"]
    open(api, "w", encoding="utf-8").writelines(lines)
    print(f"check_api_examples: {len(ranges)} code blocks written into docs/api.md")
    return 0


def check(root, programs):
    lines = open(os.path.join(root, "docs", "api.md"), encoding="utf-8").readlines()
    found = blocks(lines)
    text = lambda key: "".join(lines[found[key][0]:found[key][1]])
    files = sorted(f"docs/examples/{f}" for f in os.listdir(os.path.join(root, "docs", "examples")) if f.endswith(".cpp"))
    problems = []
    for path in files:
        name = os.path.basename(path)[:-4]
        if ("example", path) not in found:
            problems.append(f"{path} is not shown in docs/api.md (no line \"<!-- example: {path} -->\")")
        elif text(("example", path)) != open(os.path.join(root, path), encoding="utf-8").read():
            problems.append(f"docs/api.md's block for {path} differs from the file (check_api_examples.py --update ROOT):\n"
                            + differ(path, text(("example", path)), open(os.path.join(root, path), encoding="utf-8").read()))
        if name not in programs:
            problems.append(f"{path}: no program given (add it to the docs_api test in tests/CMakeLists.txt)")
            continue
        if ("output", path) not in found:
            problems.append(f"{path}: docs/api.md shows no output (no line \"<!-- output: {path} -->\")")
            continue
        r = subprocess.run([programs[name]], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=120)
        if r.returncode != 0:
            problems.append(f"{path}: the program exited {r.returncode}: {r.stderr.strip()}")
        elif r.stdout != text(("output", path)):
            problems.append(f"{path}: the program's output differs from docs/api.md's:\n"
                            + differ(f"{name} (run)", text(("output", path)), r.stdout))
    for kind, path in found:
        if path not in files:
            problems.append(f"docs/api.md has an {kind} marker for {path}, which does not exist")
    for p in problems:
        print(p)
    if problems:
        print(f"check_api_examples: {len(problems)} problem(s)")
        return 1
    print(f"check_api_examples: {len(files)} examples shown as they are, built, run and printing what docs/api.md shows")
    return 0


def main():
    args = sys.argv[1:]
    if len(args) == 2 and args[0] == "--update":
        return update(args[1])
    if len(args) < 2 or any("=" not in a for a in args[1:]):
        sys.exit(__doc__)
    return check(args[0], dict(a.split("=", 1) for a in args[1:]))


if __name__ == "__main__":
    sys.exit(main())
