#!/usr/bin/env python3
"""The documentation against the tree and the command (CTest docs_links).

Usage: check_docs.py ROOT PGE

Fails (exit 1, one line per problem) when
  - a relative link or image in ROOT/README.md or ROOT/docs/*.md points to a file that does not
    exist, or its #anchor to a heading that the target .md file does not have;
  - a subcommand listed by `PGE --help` has no section in docs/commands.md, or a long option shown
    by `PGE SUB --help` is not named in that section (top-level options: anywhere in docs/);
  - the exit codes of `PGE --help` and the table in docs/commands.md ("Exit codes") differ.
Links inside code (fenced blocks, `spans`) are not links. Headings are turned into anchors as
GitHub does: lower case, punctuation dropped, spaces to hyphens, -1, -2 ... for repeats.
"""
import os
import re
import subprocess
import sys


def strip_code(text):
    """The text with fenced code blocks and code spans blanked (line numbers kept)."""
    out, fenced = [], False
    for line in text.split("\n"):
        if re.match(r"^\s*(```|~~~)", line):
            fenced = not fenced
            out.append("")
            continue
        out.append("" if fenced else re.sub(r"`[^`]*`", "``", line))
    return out


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"<[^>]+>", "", s)                    # inline HTML
    s = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", s)   # links keep their text
    s = re.sub(r"[^\w\- ]", "", s)                   # punctuation (backticks, dots, slashes...)
    return s.replace(" ", "-")


def anchors(path):
    found, seen, fenced = set(), {}, False
    for line in open(path, encoding="utf-8"):
        if re.match(r"^\s*(```|~~~)", line):
            fenced = not fenced
        if fenced:
            continue
        m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if m:
            base = slug(m.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
    return found


LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
SRC = re.compile(r"<(?:img|a)\b[^>]*?\b(?:src|href)=\"([^\"]+)\"", re.I)


def check_links(root, files, problems):
    for path in files:
        rel = os.path.relpath(path, root)
        for number, line in enumerate(strip_code(open(path, encoding="utf-8").read()), 1):
            for target in LINK.findall(line) + SRC.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
                    continue
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                if not os.path.exists(dest):
                    problems.append(f"{rel}:{number}: broken link {target}: {os.path.relpath(dest, root)} does not exist")
                    continue
                if anchor and dest.endswith(".md") and anchor not in anchors(dest):
                    problems.append(f"{rel}:{number}: broken link {target}: no heading #{anchor} in {os.path.relpath(dest, root)}")


def help_text(pge, *args):
    # Help goes to stderr today (stdout is kept for pge's results); read both.
    r = subprocess.run([pge, *args, "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"check_docs: {pge} {' '.join(args)} --help exited {r.returncode}: {r.stdout.strip()}")
    return r.stdout


def section(help_out, header):
    """The lines of one section of a --help text ("Options:", "Subcommands:")."""
    lines, inside = [], False
    for line in help_out.split("\n"):
        if re.match(r"^\S.*:\s*$", line):
            inside = line.startswith(header)
        elif inside:
            lines.append(line)
    return lines


def long_options(help_out):
    """The long options of a --help text's Options: section (--help itself left out)."""
    opts = []
    for line in section(help_out, "Options:"):
        if re.match(r"^\s+-", line):
            names = line.strip().split(" ")[0]  # the first column: "-o,--out", "--until"
            opts += [o for o in re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", names) if o != "--help"]
    return opts


def subcommands(help_out):
    return [m.group(1) for m in (re.match(r"^\s+([a-z][a-z0-9-]*)\s", l) for l in section(help_out, "Subcommands:")) if m]


def named(text, option):
    return re.search(r"(?<![\w-])" + re.escape(option) + r"(?![\w-])", text) is not None


def sections(commands_md):
    """docs/commands.md's level-2 sections by title: {'`pge run`': text, 'Exit codes': text}."""
    out, title, body = {}, None, []
    for line in commands_md.split("\n"):
        m = re.match(r"^## (.*)$", line)
        if m:
            if title is not None:
                out[title] = "\n".join(body)
            title, body = m.group(1).strip(), []
        elif title is not None:
            body.append(line)
    if title is not None:
        out[title] = "\n".join(body)
    return out


def check_commands(root, pge, docs_text, problems):
    commands_path = os.path.join(root, "docs", "commands.md")
    if not os.path.exists(commands_path):
        problems.append("docs/commands.md does not exist")
        return
    sec = sections(open(commands_path, encoding="utf-8").read())
    top = help_text(pge)
    subs = subcommands(top)
    if not subs:
        problems.append(f"{pge} --help lists no subcommands (its format changed?)")
    for opt in long_options(top):
        if not named(docs_text, opt):
            problems.append(f"pge {opt} (pge --help) is not documented in docs/")
    for sub in subs:
        title = f"`pge {sub}`"
        if title not in sec:
            problems.append(f"pge {sub} (pge --help) has no section \"## {title}\" in docs/commands.md")
            continue
        opts = long_options(help_text(pge, sub))
        if not opts:
            problems.append(f"pge {sub} --help shows no long options (its format changed?)")
        for opt in opts:
            if not named(sec[title], opt):
                problems.append(f"pge {sub} {opt} (pge {sub} --help) is not documented in docs/commands.md, section {title}")
    # Exit codes: pge --help's footer against the table.
    m = re.search(r"Exit codes:(.*)", top, re.S)
    help_codes = set(int(c) for c in re.findall(r"(?:^|;)\s*(\d+)\s", m.group(1).replace("\n", " "))) if m else set()
    table = sec.get("Exit codes", "")
    doc_codes = set(int(c) for c in re.findall(r"^\|\s*(\d+)\s*\|", table, re.M))
    if not help_codes:
        problems.append("pge --help shows no exit codes")
    if help_codes != doc_codes:
        problems.append(f"exit codes differ: pge --help has {sorted(help_codes)}, docs/commands.md \"Exit codes\" has {sorted(doc_codes)}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    root, pge = sys.argv[1], sys.argv[2]
    docs = os.path.join(root, "docs")
    files = [os.path.join(root, "README.md")] + sorted(
        os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    problems = []
    check_links(root, files, problems)
    docs_text = "\n".join(open(f, encoding="utf-8").read() for f in files[1:])
    check_commands(root, pge, docs_text, problems)
    for p in problems:
        print(p)
    if problems:
        print(f"check_docs: {len(problems)} problem(s)")
        return 1
    print(f"check_docs: {len(files)} pages, links, subcommands, options and exit codes: all hold")
    return 0


if __name__ == "__main__":
    sys.exit(main())
