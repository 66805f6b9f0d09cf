#!/usr/bin/env python3
"""The documents are a guide for the people who use and maintain kew:

- README.md has at most 500 lines;
- every relative link of every Markdown file the repository tracks resolves: the file
  exists and, with an anchor, the target file has a heading of that anchor (GitHub's
  rule: lower case, punctuation dropped, spaces as hyphens, repeated headings numbered);
- no document or source speaks of the project's issue numbers, work rounds or sessions.

  check_docs.py [ROOT]        check the tree at ROOT (default: this repository)
  check_docs.py --self-test   first prove that each rule fires, on a scratch tree
"""

import os
import re
import subprocess
import sys
import tempfile

README_MAX_LINES = 500
LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
CODE_FENCE = re.compile(r"^\s*```")
# Wording about how the project was made rather than about the product.
HISTORY = re.compile(r"\bissues? #?\d+\b|\b(?:first|second|third|fourth|fifth|sixth|seventh|eighth|"
                     r"later|earlier|previous|next|this|last) round\b|\bround \d+\b|"
                     r"\b(?:this|previous|next|last|earlier|later) (?:working )?session\b(?!'s)", re.I)
SOURCE_SUFFIXES = (".md", ".cpp", ".hpp", ".h", ".py", ".sh", ".toml", ".scd", ".js", ".html", ".css", ".in",
                   ".txt")


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "--cached", "--others", "--exclude-standard"],
                             capture_output=True, text=True, check=True).stdout
        return sorted(f for f in out.splitlines() if os.path.exists(os.path.join(root, f)))
    except (OSError, subprocess.CalledProcessError):
        found = []
        for directory, dirs, files in os.walk(root):
            dirs[:] = [d for d in dirs if not d.startswith(".") and d != "build"]
            found += [os.path.relpath(os.path.join(directory, f), root) for f in files]
        return sorted(found)


def slug(heading):
    text = re.sub(r"`|\*|_(?=\w)|(?<=\w)_", lambda m: "" if m.group(0) in "`*" else m.group(0), heading.strip())
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = text.lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path):
    seen = {}
    out = set()
    in_code = False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if CODE_FENCE.match(line):
                in_code = not in_code
                continue
            if in_code:
                continue
            m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
            if not m:
                continue
            base = slug(m.group(1))
            n = seen.get(base, 0)
            out.add(base if n == 0 else f"{base}-{n}")
            seen[base] = n + 1
    return out


def links(path):
    in_code = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if CODE_FENCE.match(line):
                in_code = not in_code
                continue
            if in_code:
                continue
            line = re.sub(r"`[^`]*`", "", line)  # code spans are not links
            for m in LINK.finditer(line):
                yield number, m.group(1) or m.group(2)


def check(root):
    findings = []
    readme = os.path.join(root, "README.md")
    if os.path.exists(readme):
        with open(readme, encoding="utf-8") as f:
            count = sum(1 for _ in f)
        if count > README_MAX_LINES:
            findings.append(f"README.md: {count} lines, more than {README_MAX_LINES}")
    files = tracked_files(root)
    anchor_cache = {}
    for name in files:
        if not name.endswith(".md"):
            continue
        path = os.path.join(root, name)
        for number, target in links(path):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            file_part, _, anchor = target.partition("#")
            destination = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if not os.path.exists(destination):
                findings.append(f"{name}:{number}: link to {target}: no such file")
                continue
            if anchor and destination.endswith(".md"):
                if destination not in anchor_cache:
                    anchor_cache[destination] = anchors(destination)
                if anchor not in anchor_cache[destination]:
                    findings.append(f"{name}:{number}: link to {target}: no heading #{anchor} in "
                                    f"{os.path.relpath(destination, root)}")
    for name in files:
        if not name.endswith(SOURCE_SUFFIXES) and os.path.basename(name) != "CMakeLists.txt":
            continue
        if name.startswith("tests/docs/"):
            continue  # the rules' own words
        try:
            with open(os.path.join(root, name), encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    m = HISTORY.search(line)
                    if m:
                        findings.append(f"{name}:{number}: \"{m.group(0)}\": say what the product does, "
                                        "not how its making went")
        except UnicodeDecodeError:
            continue
    return findings


def self_test():
    with tempfile.TemporaryDirectory() as root:
        def write(name, text):
            path = os.path.join(root, name)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        write("README.md", "# kew\n\n## Run it as a service\n\n[ok](docs/a.md#the-stream-tcp-4747)\n"
                           "[ok too](#run-it-as-a-service)\n```\n[not a link](nowhere.md)\n```\n")
        write("docs/a.md", "# A\n\n## The stream (TCP, 4747)\n\n## The stream (TCP, 4747)\n[self](#the-stream-tcp-4747-1)\n")
        write("src/x.cpp", "// Hilbert order (design §8.3)\n")
        assert check(root) == [], check(root)
        cases = {
            "README.md": ("# kew\n" + "line\n" * 600, "more than 500"),
            "docs/b.md": ("[x](missing.md)\n", "no such file"),
            "docs/c.md": ("[x](a.md#no-such-heading)\n", "no heading #no-such-heading"),
            "src/y.cpp": ("// as issue 22 says\n", "issue 22"),
            "src/w.cpp": ("// the fifth round of figures\n", "fifth round"),
            "src/z.py": ("# as the previous session found\n", "previous session"),
        }
        for name, (text, expected) in cases.items():
            original = None
            if os.path.exists(os.path.join(root, name)):
                with open(os.path.join(root, name), encoding="utf-8") as f:
                    original = f.read()
            write(name, text)
            found = check(root)
            assert any(expected in f for f in found), (name, expected, found)
            if original is None:
                os.remove(os.path.join(root, name))
            else:
                write(name, original)
        assert check(root) == []
    print("self-test: every rule fires")


def main():
    args = sys.argv[1:]
    if args and args[0] == "--self-test":
        self_test()
        args = args[1:]
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    findings = check(os.path.abspath(root))
    for finding in findings:
        print(finding)
    if findings:
        print(f"{len(findings)} findings")
        return 1
    print("documents: README within 500 lines, every link resolves, no history wording")
    return 0


if __name__ == "__main__":
    sys.exit(main())
