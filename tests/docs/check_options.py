#!/usr/bin/env python3
"""The manual pages and --help of every tool name the same options.

For each tool, the options (-x and --x forms) and positionals its CLI11 --help lists are
compared with the terms of the OPTIONS and OPERANDS sections of docs/man/TOOL.SECTION.scd;
options the SYNOPSIS names must exist too. Fails (exit 1, one line per difference) when
they differ. Positionals are paired with operands in order, by count only: CLI11 names
them for the code ("files") and the page for the reader (_recording_).

  check_options.py [TOOL=PATH ...]              check the built tools
  check_options.py --self-test [TOOL=PATH ...]  first check that a difference is found
  --man-dir DIR                                 the pages (default: docs/man of this tree)

Binaries come from the arguments, else from the environment (set by ctest): KEWD,
KEW_WATCH, KEW_REPLAY, KEW_GEN, KEW_DECODE, KEW_EVAL; else the tool's name on PATH.
"""

import glob
import os
import re
import shutil
import subprocess
import sys

TOOLS = {
    "kewd": "KEWD",
    "kew-watch": "KEW_WATCH",
    "kew-replay": "KEW_REPLAY",
    "kew-gen": "KEW_GEN",
    "kew-decode": "KEW_DECODE",
    "kew-eval": "KEW_EVAL",
}
OPTION_NAME = re.compile(r"^(-[A-Za-z0-9]|--[A-Za-z0-9][A-Za-z0-9-]*)$")
HELP_HEADING = re.compile(r"^\S.*:$")
HELP_ENTRY = re.compile(r"^  (\S+)")
HELP_CONTINUATION = re.compile(r"^ {3,}\S")
BOLD = re.compile(r"\*([^*\n]+)\*")
HELP_TIMEOUT_S = 30


class ParseError(Exception):
    pass


def parse_help(text):
    """(options, positionals) of a CLI11 help text.

    A section is a heading line ending in ':' and the lines up to the next blank one. Only
    "Positionals:" and sections whose every entry starts with '-' count: a footer may
    have a heading and indented lines too (kewd's "Watching a recording:"), and its
    example command lines must not be read as options.
    """
    options, positionals = set(), []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        heading = lines[i]
        i += 1
        if not HELP_HEADING.match(heading) or heading.startswith("Usage:"):
            continue
        section = []
        while i < len(lines) and lines[i].strip():
            section.append(lines[i])
            i += 1
        entries = [HELP_ENTRY.match(line).group(1) for line in section if HELP_ENTRY.match(line)]
        layout_ok = entries and all(HELP_ENTRY.match(line) or HELP_CONTINUATION.match(line) for line in section)
        if not layout_ok:
            continue
        if heading == "Positionals:":
            positionals.extend(entries)
        elif all(entry.startswith("-") for entry in entries):
            for entry in entries:
                for name in entry.split(","):
                    if not OPTION_NAME.match(name):
                        raise ParseError(f"--help: cannot read the option name {name!r} of {entry!r}")
                    options.add(name)
    if not options:
        raise ParseError("--help: no option found (not CLI11's layout?)")
    return options, positionals


def scd_sections(text):
    """{heading: [lines]} of an scdoc page, comments dropped."""
    sections, current = {}, None
    for line in text.splitlines():
        if line.startswith(";"):
            continue
        if line.startswith("# "):
            current = line[2:].strip()
            sections[current] = []
        elif current is not None:
            sections[current].append(line)
    return sections


def parse_man(text):
    """(options, operands, synopsis_options, problems) of an scdoc page.

    A term is a line that is not indented and is followed by a tab-indented line; other
    unindented lines of OPTIONS are prose. A term starts with its bold option names
    (*-c, --config* _file_) or is an operand (_recording_); anything else is reported,
    so that a page written another way cannot pass by having nothing read from it.
    """
    sections = scd_sections(text)
    if "OPTIONS" not in sections:
        raise ParseError("no OPTIONS section")
    options, operands, problems = set(), [], []
    for heading in ("OPTIONS", "OPERANDS"):
        lines = sections.get(heading, [])
        for line, following in zip(lines, lines[1:]):
            if not line.strip() or line.startswith("\t") or not following.startswith("\t"):
                continue
            if line.startswith("_"):
                match = re.match(r"_([^_]+)_", line)
                operands.append(match.group(1) if match else line)
                continue
            match = BOLD.match(line)
            names = [name.strip() for name in match.group(1).split(",")] if match else []
            if not names or not all(OPTION_NAME.match(name) for name in names):
                problems.append(f"{heading}: cannot read the term {line!r}")
                continue
            options.update(names)
    synopsis = set()
    for line in sections.get("SYNOPSIS", []):
        synopsis.update(span for span in BOLD.findall(line) if OPTION_NAME.match(span))
    return options, operands, synopsis, problems


def compare(help_text, man_text, page_name):
    """The differences between a help text and a manual page, one sentence each."""
    help_options, positionals = parse_help(help_text)
    man_options, operands, synopsis, differences = parse_man(man_text)
    differences = [f"{page_name}: {problem}" for problem in differences]
    for name in sorted(help_options - man_options):
        differences.append(f"{name}: in --help, not in {page_name}")
    for name in sorted(man_options - help_options):
        differences.append(f"{name}: in {page_name}, not in --help")
    for name in sorted(synopsis - help_options):
        differences.append(f"{name}: in the SYNOPSIS of {page_name}, not in --help")
    for name in positionals[len(operands):]:
        differences.append(f"positional {name}: in --help, no operand for it in {page_name}")
    for name in operands[len(positionals):]:
        differences.append(f"operand _{name}_: in {page_name}, no positional for it in --help")
    return differences, len(help_options), len(positionals)


def help_text_of(binary):
    try:
        result = subprocess.run([binary, "--help"], capture_output=True, text=True, timeout=HELP_TIMEOUT_S)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise ParseError(f"{binary} --help: {error}")
    if result.returncode != 0:
        raise ParseError(f"{binary} --help exited {result.returncode}: {result.stderr.strip()}")
    return result.stdout


def man_page_of(man_dir, tool):
    paths = sorted(glob.glob(os.path.join(man_dir, f"{glob.escape(tool)}.[1-9]*.scd")))
    if len(paths) != 1:
        raise ParseError(f"expected one {tool}.SECTION.scd in {man_dir}, found {len(paths)}")
    return paths[0]


def check(binaries, man_dir):
    """Prints the differences of every tool; the exit status."""
    failures = checked_options = checked_positionals = 0
    for tool, binary in binaries.items():
        try:
            path = man_page_of(man_dir, tool)
            with open(path, encoding="utf-8") as f:
                man_text = f.read()
            differences, options, positionals = compare(help_text_of(binary), man_text, os.path.basename(path))
        except ParseError as error:
            differences, options, positionals = [str(error)], 0, 0
        checked_options += options
        checked_positionals += positionals
        for difference in differences:
            print(f"{tool}: {difference}")
        failures += len(differences)
    summary = f"checked {checked_options} option names and {checked_positionals} positionals of {len(binaries)} tools"
    if failures:
        print(f"{failures} differences between --help and the manual pages; {summary}")
        return 1
    print(f"--help and the manual pages agree: {summary}")
    return 0


FAKE_HELP = """\
fake: a tool
Usage: fake [OPTIONS] files...

Positionals:
  files TEXT:FILE ... REQUIRED
                              recordings

Options:
  -h,--help                   Print this help message and exit
  --version                   Display program version information and exit
  -c,--config TEXT            configuration
  --speed FLOAT:POSITIVE Excludes: --max-speed
                              multiple of recorded speed
  --max-speed Excludes: --speed
                              as fast as possible

Running:
  fake --speed X files
       [--not-an-option]
"""

FAKE_MAN = """\
fake(1) "@KEW_MAN_SOURCE@" "kew manual"

; *--commented-out*
# NAME

# SYNOPSIS

*fake* [*-c* _file_] [*--speed* _x_ | *--max-speed*] _recording_...

# OPTIONS

*-c, --config* _file_
	Configuration.

*--speed* _x_
	Multiple of recorded speed.

*--max-speed*
	As fast as possible.

*-h, --help*
	Help.

*--version*
	Version.

Prose that names *--not-an-option* is not a term.

# OPERANDS

_recording_
	A file.
"""


def self_test():
    """The comparison must be quiet on a matching pair and name each kind of difference."""
    problems = []

    def expect(what, help_text, man_text, wanted):
        differences, _, _ = compare(help_text, man_text, "fake.1.scd")
        if sorted(differences) != sorted(wanted):
            problems.append(f"self-test: {what}: expected {wanted}, got {differences}")

    expect("a matching page", FAKE_HELP, FAKE_MAN, [])
    expect("an option missing from the page",
           FAKE_HELP.replace("Options:\n", "Options:\n  -q,--quiet                  quiet\n"), FAKE_MAN,
           ["-q: in --help, not in fake.1.scd", "--quiet: in --help, not in fake.1.scd"])
    expect("an option missing from --help", FAKE_HELP,
           FAKE_MAN.replace("*--version*\n", "*--sort*\n\tSort.\n\n*--version*\n"),
           ["--sort: in fake.1.scd, not in --help"])
    expect("a stale synopsis", FAKE_HELP, FAKE_MAN.replace("*--max-speed*]", "*--max-speed*] [*--gone*]"),
           ["--gone: in the SYNOPSIS of fake.1.scd, not in --help"])
    expect("a positional without an operand", FAKE_HELP, FAKE_MAN.replace("_recording_\n\tA file.\n", ""),
           ["positional files: in --help, no operand for it in fake.1.scd"])
    expect("an unreadable term", FAKE_HELP, FAKE_MAN.replace("*--max-speed*\n\t", "--max-speed\n\t"),
           ["fake.1.scd: OPTIONS: cannot read the term '--max-speed'",
            "--max-speed: in --help, not in fake.1.scd"])
    try:
        parse_help("fake: a tool\nUsage: fake\n")
        problems.append("self-test: a help text without options was read")
    except ParseError:
        pass
    return problems


def main():
    args = sys.argv[1:]
    if args and args[0] == "--self-test":
        args = args[1:]
        problems = self_test()
        if problems:
            print("\n".join(problems))
            return 1
        print("self-test: every kind of difference is found")
    man_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "man")
    binaries = {tool: os.environ.get(variable) or tool for tool, variable in TOOLS.items()}
    while args:
        arg = args.pop(0)
        if arg == "--man-dir" and args:
            man_dir = args.pop(0)
        elif "=" in arg and arg.split("=", 1)[0] in TOOLS:
            tool, binary = arg.split("=", 1)
            binaries[tool] = binary
        else:
            print(f"usage: {sys.argv[0]} [--self-test] [--man-dir DIR] [TOOL=PATH ...]; TOOL is one of "
                  f"{', '.join(TOOLS)}", file=sys.stderr)
            return 64
    missing = [f"{tool} ({TOOLS[tool]})" for tool, binary in binaries.items() if not shutil.which(binary)]
    if missing:
        print(f"not found: {', '.join(missing)}; set the variables or pass TOOL=PATH", file=sys.stderr)
        return 1
    return check(binaries, os.path.normpath(man_dir))


if __name__ == "__main__":
    sys.exit(main())
