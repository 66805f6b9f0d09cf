#!/usr/bin/env python3
"""Libraries depend one way (docs/design.md §3.2): core <- protocol <- config <- replay <- daemon.

Fails (exit 1, one line per finding) when a library's source includes a header of a
library above it, when its CMakeLists.txt links a target of a library above it, when a
header path kew/<x>/ belongs to no library (a new folder must be placed in the order
here), or when core/ or protocol/ include socket headers (core knows nothing of I/O,
protocol nothing of sockets).

  check_layers.py [ROOT]          check the tree at ROOT (default: this repository)
  check_layers.py --self-test     check that every rule fires, on a scratch tree
"""

import os
import re
import sys
import tempfile

# Library folder -> (level, the kew/<x> header folders it owns, its CMake targets).
LIBRARIES = {
    "core": (0, {"geometry", "triangulation", "kinetic", "geo", "track", "probe", "alert", "eligibility", "region", "zone", "pipeline", "util"},
             {"kew_core"}),
    "protocol": (1, {"protocol"}, {"kew_protocol"}),
    "config": (2, {"config"}, {"kew_config"}),
    "replay": (3, {"replay"}, {"kew_replay"}),
    "daemon": (4, {"daemon"}, {"kew_daemon_config", "kew_modbus", "kew_nats", "kew_connections", "kew_http", "kew_service"}),
}
SOCKET_HEADERS = re.compile(r"#\s*include\s*<(boost/asio|boost/beast|sys/socket\.h|netinet/|arpa/inet\.h|netdb\.h)")
KEW_INCLUDE = re.compile(r'#\s*include\s*"kew/([^/"]+)/')
TARGET = re.compile(r"\bkew_[a-z_]+\b")
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")


def owner_of_header_folder(folder):
    for name, (_, folders, _) in LIBRARIES.items():
        if folder in folders:
            return name
    return None


def owner_of_target(target):
    for name, (_, _, targets) in LIBRARIES.items():
        if target in targets:
            return name
    return None


def check(root):
    findings = []
    for library, (level, _, _) in LIBRARIES.items():
        base = os.path.join(root, library)
        if not os.path.isdir(base):
            findings.append(f"{library}/: missing (the dependency order names it)")
            continue
        for directory, _, files in os.walk(base):
            for name in sorted(files):
                path = os.path.join(directory, name)
                relative = os.path.relpath(path, root)
                if name == "CMakeLists.txt":
                    with open(path) as f:
                        for number, line in enumerate(f, 1):
                            for target in TARGET.findall(line.split("#", 1)[0]):
                                other = owner_of_target(target)
                                if other and LIBRARIES[other][0] > level:
                                    findings.append(f"{relative}:{number}: {library} links {target} of {other}, "
                                                    f"a library above it")
                    continue
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                with open(path, errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        match = KEW_INCLUDE.search(line)
                        if match:
                            other = owner_of_header_folder(match.group(1))
                            if other is None:
                                findings.append(f"{relative}:{number}: kew/{match.group(1)}/ belongs to no library "
                                                f"(place it in tests/layering/check_layers.py)")
                            elif LIBRARIES[other][0] > level:
                                findings.append(f"{relative}:{number}: {library} includes a header of {other}, "
                                                f"a library above it: {line.strip()}")
                        if library in ("core", "protocol") and SOCKET_HEADERS.search(line):
                            findings.append(f"{relative}:{number}: {library} includes a socket header: {line.strip()}")
    return findings


def self_test():
    """Every rule must fire on a tree built to break it, and stay quiet on a clean one."""
    with tempfile.TemporaryDirectory() as root:
        def write(relative, text):
            path = os.path.join(root, relative)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as f:
                f.write(text)
        for library in LIBRARIES:
            write(f"{library}/CMakeLists.txt", f"add_library(kew_{library} x.cpp)\n")
        write("daemon/src/a.cpp", '#include "kew/replay/pacer.hpp"\n#include "kew/core_is_not_a_folder/x.hpp"\n')
        write("protocol/src/b.cpp", '#include "kew/pipeline/pipeline.hpp"\n')
        if check(root) != [f"daemon{os.sep}src{os.sep}a.cpp:2: kew/core_is_not_a_folder/ belongs to no library "
                           "(place it in tests/layering/check_layers.py)"]:
            return ["self-test: a clean tree (downward includes only) was not found clean: " + repr(check(root))]
        write("core/src/c.cpp", '#include "kew/protocol/formats.hpp"\n#include <boost/asio/ip/tcp.hpp>\n')
        write("replay/src/d.hpp", '#include "kew/daemon/config.hpp"\n')
        write("config/CMakeLists.txt", "target_link_libraries(kew_config PUBLIC kew_core kew_replay)\n")
        findings = check(root)
        expected = ["core includes a header of protocol", "core includes a socket header",
                    "replay includes a header of daemon", "config links kew_replay of replay"]
        missing = [e for e in expected if not any(e in f for f in findings)]
        return [f"self-test: the rule '{m}' did not fire" for m in missing]


def main():
    args = sys.argv[1:]
    if args and args[0] == "--self-test":
        problems = self_test()
        args = args[1:]
        if problems:
            print("\n".join(problems))
            return 1
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    findings = check(os.path.abspath(root))
    for finding in findings:
        print(finding)
    if findings:
        print(f"{len(findings)} dependency findings; the order is core <- protocol <- config <- replay <- daemon")
        return 1
    print("layering: core <- protocol <- config <- replay <- daemon holds")
    return 0


if __name__ == "__main__":
    sys.exit(main())
