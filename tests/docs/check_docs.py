#!/usr/bin/env python3
"""The documents are a guide for the people who use and maintain kew:

- README.md has at most 500 lines;
- every relative link of every Markdown file the repository tracks resolves: the file
  exists and, with an anchor, the target file has a heading of that anchor (GitHub's
  rule: lower case, punctuation dropped, spaces as hyphens, repeated headings numbered);
- no document or source speaks of the project's issue numbers, work rounds or sessions;
- the documents speak of the product as it is, not of how it came to be. A document is
  every Markdown file the repository tracks but the provenance notes of the test data
  (tests/data/*/SOURCE.md) and anything under a vendor/ or third_party/ folder;
- in a document, anywhere (code included, and wrapped across a line break), these
  phrases are refused, whole words, in any case: "used to" (so "used to be" too),
  "no longer", "mended" ("was mended"), "as before", "as kew had before", "once did",
  "before the rules of this page changed", "previously", "formerly", "originally",
  "until recently", "we fixed", "was changed", "were changed", "has become",
  "have become", "a later version";
- in a document, a commit hash in prose is refused. A hash is a run of 7 to 40
  lower-case hexadecimal characters with at least one digit and at least one of a-f,
  standing alone: no letter, digit or '_' on either side, no '.', '-', '/' or '@' before
  it, no '-', '/' or '@' after it, nor a '.' that joins it to a following letter or digit
  (so no file name, version, path or address); a longer run (a SHA-256 sum) is none.
  It is allowed only
    1. inside a fenced code block or an inline code span;
    2. on a measurement line: a line that also holds the word "commit" (or "commits")
       and a date written YYYY-MM-DD, as in "measured 2026-12-03 at commit 5b2c3d3";
    3. in a table whose header row (its first line) holds the word "commit": a table of
       measurements with a commit column, such as the fuzzing table of docs/testing.md.

Every finding is printed as FILE:LINE: "what was found": what to do.

  check_docs.py [ROOT]        check the tree at ROOT (default: this repository)
  check_docs.py --self-test   first prove that each rule fires, on a scratch tree
"""

import json
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
# Wording that tells the story of a change instead of describing the product (documents only).
HISTORY_PHRASES = ("used to", "no longer", "mended", "as before", "as kew had before", "once did",
                   "before the rules of this page changed", "previously", "formerly", "originally",
                   "until recently", "we fixed", "was changed", "were changed", "has become", "have become",
                   "a later version")
HISTORY_PHRASE = re.compile(r"\b(?:" + "|".join(re.escape(p).replace(r"\ ", r"\s+") for p in
                                                  sorted(HISTORY_PHRASES, key=len, reverse=True)) + r")\b", re.I)
# A standalone hexadecimal word of 7-40 characters with a digit and a letter: a commit hash.
COMMIT_HASH = re.compile(r"(?<![\w./@-])(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}(?![\w/@-])(?!\.\w)")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
DATE = re.compile(r"\b\d{4}-\d{2}-\d{2}\b")
COMMIT_WORD = re.compile(r"\bcommits?\b", re.I)
TABLE_ROW = re.compile(r"^\s*\|")
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


def is_document(name):
    """A Markdown file whose words are kew's own: not a test excerpt's provenance note, not vendored."""
    parts = name.split("/")
    if not name.endswith(".md") or "vendor" in parts[:-1] or "third_party" in parts[:-1]:
        return False
    return not (len(parts) == 4 and parts[:2] == ["tests", "data"] and parts[3] == "SOURCE.md")


def history_findings(name, text):
    """The history phrases and the commit hashes in prose of one document, as findings."""
    findings = []
    # A phrase may wrap from one line to the next: it is sought in the whole text and
    # reported at the line where it starts.
    for m in HISTORY_PHRASE.finditer(text):
        number = text.count("\n", 0, m.start()) + 1
        phrase = " ".join(m.group(0).split())
        findings.append(f"{name}:{number}: \"{phrase}\": history wording; say what kew does and why")
    in_code = False
    commit_table = False
    previous_was_row = False
    for number, line in enumerate(text.splitlines(), 1):
        if CODE_FENCE.match(line):
            in_code = not in_code
            previous_was_row = False
            continue
        if in_code:
            continue
        is_row = bool(TABLE_ROW.match(line))
        if is_row and not previous_was_row:
            commit_table = bool(COMMIT_WORD.search(line))  # the header row of a new table
        previous_was_row = is_row
        if is_row and commit_table:
            continue
        if DATE.search(line) and COMMIT_WORD.search(line):
            continue  # a measurement line names the commit it was measured at
        for m in COMMIT_HASH.finditer(CODE_SPAN.sub(lambda c: " " * len(c.group(0)), line)):
            findings.append(f"{name}:{number}: \"{m.group(0)}\": a commit hash in prose; name a commit only on a "
                            "measurement line (the word commit and a YYYY-MM-DD date), in code, or in a table "
                            "whose header names the commit")
    return sorted(findings, key=lambda f: int(f[len(name) + 1:].split(":", 1)[0]))


THESIS_FIGURES = "docs/data/thesis-effects.json"
THESIS_MARK = re.compile(r"<!-- thesis:([a-z_]+) -->")


def thesis_figure_findings(root, files):
    """A line marked <!-- thesis:KEY --> prints, in bold, the setting's ratio KEY of
    docs/data/thesis-effects.json (kew_thesis_bench's output) to its printed digits."""
    path = os.path.join(root, THESIS_FIGURES)
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8") as f:
        ratios = json.load(f)["setting"]["ratios"]
    findings = []
    for name in files:
        if not name.endswith(".md"):
            continue
        with open(os.path.join(root, name), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                for key in THESIS_MARK.findall(line):
                    printed = re.search(r"\*\*(\d+\.\d+)\*\*", line)
                    if key not in ratios:
                        findings.append(f"{name}:{number}: thesis ratio {key}: not in {THESIS_FIGURES}")
                    elif not printed:
                        findings.append(f"{name}:{number}: thesis ratio {key}: no bold figure on the line")
                    else:
                        digits = len(printed.group(1).split(".")[1])
                        if abs(float(printed.group(1)) - ratios[key]) > 0.5 * 10 ** -digits + 1e-12:
                            findings.append(f"{name}:{number}: thesis ratio {key}: the text says {printed.group(1)}, "
                                            f"{THESIS_FIGURES} {ratios[key]:.{digits}f}")
    return findings


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
    findings += thesis_figure_findings(root, files)
    for name in files:
        if not is_document(name):
            continue
        try:
            with open(os.path.join(root, name), encoding="utf-8") as f:
                findings += history_findings(name, f.read())
        except UnicodeDecodeError:
            continue
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


# A document that breaks no rule, with what the rules must let pass: "use" in the present,
# hexadecimal that is no commit in prose, and commits where they are allowed.
CLEAN_DOCUMENT = """# Sample

The projection used by every zone is conformal, and `use_to` is an identifier.
An alert id in code: `7d286c07be84648f`; the revision `2660c60a1b2c`; ICAO 4CA123, A1B2C3D4E.
Measured 2026-12-03 at commit 5b2c3d3 with `python3 tests/eval/alert_quality.py`.
A sum: fc81d34e3842caa62b5f47dfa99d4c69c8b25648a5a1cbf2a5502e2f201a53f4; deadbeefcafe; 1234567.
A path build/abc1234/x, a file abc1234.json, a version 1.2.3-abc1234, an address me@abc1234.

```
14:13:24Z NEW warning [919e6b37a16e077d] at 5b2c3d3
```

| target | date, commit | runs |
|---|---|---|
| fuzz_sbs | 2026-12-03, 872452a | 4,855,546 |

| pair | commit | records/s |
|---:|---|---|
| 1 | dc72ac4 | 97,591 |
"""


def self_test_history():
    """Every history phrase and every kind of commit hash in prose is caught, with its line."""
    assert history_findings("docs/clean.md", CLEAN_DOCUMENT) == [], history_findings("docs/clean.md", CLEAN_DOCUMENT)
    found = history_findings("docs/c.md", "A span `used to` here.\n```\nno longer\n```\n")  # code is no refuge
    assert [f.split('"')[1] for f in found] == ["used to", "no longer"], found
    assert found[0].startswith("docs/c.md:1: ") and found[1].startswith("docs/c.md:3: "), found
    for phrase in HISTORY_PHRASES:
        for text in (f"Intro.\nThe harness {phrase} the rule.\n", f"Intro.\nThe harness {phrase.upper()} it.\n"):
            found = history_findings("docs/s.md", text)
            assert any(f.startswith("docs/s.md:2: ") and phrase in f.lower() for f in found), (phrase, found)
        words = phrase.split(" ")
        if len(words) > 1:  # wrapped across two lines, indented as in a list
            text = "Intro.\n- The rule " + " ".join(words[:-1]) + "\n  " + words[-1] + " counts.\n"
            found = history_findings("docs/s.md", text)
            assert any(f.startswith("docs/s.md:2: ") and f'"{phrase}"' in f for f in found), (phrase, found)
    for text in ("amended, recommended, a used tool, longer no more\n", "Previous figures; formula; origin\n"):
        assert history_findings("docs/s.md", text) == [], text
    hashes = {
        "measured at 5b2c3d3 on the VM\n": "5b2c3d3",                         # no date, no word commit
        "commit 5b2c3d3, which the bench ran\n": "5b2c3d3",                   # no date
        "on 2026-12-03 the build 5b2c3d3\n": "5b2c3d3",                       # no word commit
        "before the rules (88221a0) and now.\n": "88221a0",
        "dc72ac4: 0.93 of the time\n": "dc72ac4",
        "a full one, 2660c60a1b2c3d4e5f60718293a4b5c6d7e8f901.\n": "2660c60a1b2c3d4e5f60718293a4b5c6d7e8f901",
        "| build | records/s |\n|---|---|\n| dc72ac4 | 97,591 |\n": "dc72ac4",  # a table without a commit column
        "```\ncode\n```\nthen 3fd64e7 in prose\n": "3fd64e7",
    }
    for text, expected in hashes.items():
        found = history_findings("docs/h.md", text)
        assert any(f'"{expected}": a commit hash in prose' in f for f in found), (text, found)
    found = history_findings("docs/h.md", "one\n\nthree 5b2c3d3\n")
    assert found and found[0].startswith('docs/h.md:3: "5b2c3d3"'), found


def self_test():
    self_test_history()
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
        write(THESIS_FIGURES, '{"setting": {"ratios": {"queue_failures": 0.0817}}}')
        write("docs/t.md", "| queue | **0.082** <!-- thesis:queue_failures --> |\n")
        assert check(root) == [], check(root)
        cases = {
            "docs/t.md": ("| queue | **0.081** <!-- thesis:queue_failures --> |\n", "the text says 0.081"),
            "docs/u.md": ("| queue | **0.082** <!-- thesis:no_such_ratio --> |\n", "not in docs/data"),
            "README.md": ("# kew\n" + "line\n" * 600, "more than 500"),
            "docs/b.md": ("[x](missing.md)\n", "no such file"),
            "docs/c.md": ("[x](a.md#no-such-heading)\n", "no heading #no-such-heading"),
            "src/y.cpp": ("// as issue 22 says\n", "issue 22"),
            "src/w.cpp": ("// the fifth round of figures\n", "fifth round"),
            "src/z.py": ("# as the previous session found\n", "previous session"),
            "docs/d.md": ("# D\n\nThe harness was mended.\n", 'docs/d.md:3: "mended"'),
            "docs/e.md": ("# E\n\nkew no\nlonger does that.\n", 'docs/e.md:3: "no longer"'),
            "docs/f.md": ("# F\n\nNow (5b2c3d3):\n", 'docs/f.md:3: "5b2c3d3": a commit hash in prose'),
            "replay/README.md": ("# R\n\nThe rule used to be off.\n", 'replay/README.md:3: "used to"'),
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
        # A test excerpt's provenance note and a vendored file are not kew's documents.
        write("tests/data/asterix/SOURCE.md", "# Source\n\nThe file used to be 2 MB, commit abc1234.\n")
        write("web/vendor/README.md", "# Vendor\n\nIt was previously 3 MB (1a2b3c4).\n")
        write("docs/clean.md", CLEAN_DOCUMENT)
        assert check(root) == [], check(root)
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
    print("documents: README within 500 lines, every link resolves, no history wording, no commit hash in prose, the thesis figures as their JSON")
    return 0


if __name__ == "__main__":
    sys.exit(main())
