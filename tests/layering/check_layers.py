#!/usr/bin/env python3
"""Libraries depend one way (docs/design.md §3.2): core <- protocol <- config <- replay <- daemon,
and inside core each folder is a library linked one way (CORE below, no cycle).

Fails (exit 1, one line per finding) when
- a library's source includes a header of a library above it, or its CMakeLists.txt links a
  target of a library above it;
- a folder of core includes a header of, or links, a folder of core it does not depend on
  (CORE holds what each folder may use; the order must have no cycle);
- a header path kew/<x>/ belongs to no library, or a folder of core/src or core/include/kew
  is not in CORE (a new folder must be placed in the order here);
- core/ or protocol/ include socket headers (core knows nothing of I/O, protocol nothing of
  sockets);
- a CMakeLists.txt collects sources with file(GLOB), or a .cpp file of a library or of
  tests/ is named in no CMakeLists.txt (or .cmake file) of its folder or above it: sources
  are listed one by one, so a file nobody listed would be neither built nor tested.

  check_layers.py [ROOT]          check the tree at ROOT (default: this repository)
  check_layers.py --self-test     check that every rule fires, on a scratch tree
"""

import os
import re
import sys
import tempfile

# Each folder of core/src and core/include/kew is the library kew_<folder>; the folders of
# core it uses directly (what its headers and sources include, what core/CMakeLists.txt
# links). What a folder may use is this relation's transitive closure.
CORE = {
    "util": set(),
    "geometry": set(),
    "triangulation": {"geometry", "util"},
    "kinetic": {"geometry", "triangulation", "util"},
    "geo": {"geometry"},
    "probe": {"geometry", "kinetic", "util"},
    "track": {"geo", "kinetic", "probe", "util"},
    "alert": {"util"},
    "eligibility": {"geo", "probe", "track", "util"},
    "region": {"geo", "geometry"},
    "zone": {"geo", "geometry", "kinetic", "probe", "region", "util"},
    "volume": {"geometry", "util"},
    "pipeline": {"alert", "eligibility", "geo", "geometry", "kinetic", "probe", "region", "track", "util",
                 "volume", "zone"},
}

# Library folder -> (level, the kew/<x> header folders it owns, its CMake targets).
LIBRARIES = {
    "core": (0, set(CORE), {"kew_core"} | {f"kew_{folder}" for folder in CORE}),
    "protocol": (1, {"protocol"}, {"kew_protocol"}),
    "config": (2, {"config"}, {"kew_config"}),
    "replay": (3, {"replay"}, {"kew_replay"}),
    "daemon": (4, {"daemon"}, {"kew_daemon_config", "kew_modbus", "kew_nats", "kew_connections", "kew_http", "kew_service"}),
}
SOCKET_HEADERS = re.compile(r"#\s*include\s*<(boost/asio|boost/beast|sys/socket\.h|netinet/|arpa/inet\.h|netdb\.h)")
KEW_INCLUDE = re.compile(r'#\s*include\s*"kew/([^/"]+)/')
TARGET = re.compile(r"\bkew_[a-z_]+\b")
LINK_CALL = re.compile(r"target_link_libraries\s*\(\s*(kew_[a-z_]+)([^)]*)\)", re.S)
GLOB = re.compile(r"\bfile\s*\(\s*GLOB", re.I)
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
# Where .cpp files must be listed: the libraries and the tests (data and corpora hold none).
LISTED_TREES = tuple(LIBRARIES) + ("tests",)


def closure(order):
    """{folder: every folder it may use}, or raises ValueError naming a cycle."""
    done = {}

    def visit(folder, path):
        if folder in path:
            cycle = path[path.index(folder):] + [folder]
            raise ValueError(" -> ".join(cycle))
        if folder not in done:
            reach = set()
            for used in order.get(folder, ()):
                reach |= {used} | visit(used, path + [folder])
            done[folder] = reach
        return done[folder]

    for folder in order:
        visit(folder, [])
    return done


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


def strip_cmake_comments(text):
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


def core_folder_of(relative):
    """The folder of core a path below core/ belongs to, or None."""
    parts = relative.split(os.sep)
    if parts[:2] == ["core", "src"] and len(parts) > 3:
        return parts[2]
    if parts[:3] == ["core", "include", "kew"] and len(parts) > 4:
        return parts[3]
    return None


def check_core(root, order, findings):
    try:
        allowed = closure(order)
    except ValueError as cycle:
        findings.append(f"core: the order of its folders has a cycle: {cycle}")
        return
    for base in (os.path.join(root, "core", "src"), os.path.join(root, "core", "include", "kew")):
        if os.path.isdir(base):
            for folder in sorted(os.listdir(base)):
                if os.path.isdir(os.path.join(base, folder)) and folder not in order:
                    findings.append(f"{os.path.relpath(os.path.join(base, folder), root)}/: a folder of core that is "
                                    f"in no place of the order (add it to CORE in tests/layering/check_layers.py and "
                                    f"a library kew_{folder} to core/CMakeLists.txt)")
    for directory, _, files in os.walk(os.path.join(root, "core")):
        for name in sorted(files):
            path = os.path.join(directory, name)
            relative = os.path.relpath(path, root)
            folder = core_folder_of(relative)
            if folder not in order or not name.endswith(SOURCE_SUFFIXES):
                continue
            with open(path, errors="replace") as f:
                for number, line in enumerate(f, 1):
                    match = KEW_INCLUDE.search(line)
                    if match and match.group(1) in order and match.group(1) != folder \
                            and match.group(1) not in allowed[folder]:
                        findings.append(f"{relative}:{number}: core/{folder} includes a header of core/"
                                        f"{match.group(1)}, which it does not depend on: {line.strip()}")
    cmake = os.path.join(root, "core", "CMakeLists.txt")
    if os.path.isfile(cmake):
        with open(cmake) as f:
            text = strip_cmake_comments(f.read())
        for call in LINK_CALL.finditer(text):
            folder = call.group(1)[len("kew_"):]
            if folder not in order:
                continue
            number = text.count("\n", 0, call.start()) + 1
            for target in TARGET.findall(call.group(2)):
                used = target[len("kew_"):]
                if used in order and used != folder and used not in allowed[folder]:
                    findings.append(f"core/CMakeLists.txt:{number}: kew_{folder} links {target}, which "
                                    f"core/{folder} does not depend on")


def check_listed(root, findings):
    cmake_texts = {}  # directory -> text of its CMakeLists.txt and *.cmake files
    for tree in LISTED_TREES + ("cmake", "docs"):
        for directory, _, files in os.walk(os.path.join(root, tree)):
            for name in sorted(files):
                if name == "CMakeLists.txt" or name.endswith(".cmake"):
                    path = os.path.join(directory, name)
                    with open(path) as f:
                        text = f.read()
                    if GLOB.search(strip_cmake_comments(text)):
                        findings.append(f"{os.path.relpath(path, root)}: file(GLOB) collects sources; "
                                        f"list them one by one")
                    cmake_texts[directory] = cmake_texts.get(directory, "") + strip_cmake_comments(text) + "\n"
    top = os.path.join(root, "CMakeLists.txt")
    if os.path.isfile(top):
        with open(top) as f:
            cmake_texts[root] = cmake_texts.get(root, "") + strip_cmake_comments(f.read())
    everything = "\n".join(cmake_texts.values())

    def named(text, path):
        return re.search(r"(^|[\s/\"(])" + re.escape(path) + r"($|[\s\")])", text, re.M) is not None

    for tree in LISTED_TREES:
        for directory, _, files in os.walk(os.path.join(root, tree)):
            for name in sorted(files):
                if not name.endswith(".cpp"):
                    continue
                path = os.path.join(directory, name)
                from_root = os.path.relpath(path, root).replace(os.sep, "/")
                listed = named(everything, from_root)
                folder = directory
                while not listed and len(folder) >= len(root):
                    if folder in cmake_texts:
                        listed = named(cmake_texts[folder], os.path.relpath(path, folder).replace(os.sep, "/"))
                    if folder == root:
                        break
                    folder = os.path.dirname(folder)
                if not listed:
                    findings.append(f"{from_root}: named in no CMakeLists.txt (sources and tests are listed "
                                    f"one by one: add it to its folder's list)")


def check(root, core_order=None):
    order = CORE if core_order is None else core_order
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
    check_core(root, order, findings)
    check_listed(root, findings)
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
            if library != "core":
                write(f"{library}/CMakeLists.txt", f"add_library(kew_{library} x.cpp)\n")
        write("core/CMakeLists.txt", "add_library(kew_kinetic src/kinetic/k.cpp)\n"
                                     "target_link_libraries(kew_kinetic PUBLIC kew_geometry\n  kew_util)\n"
                                     "add_library(kew_probe src/probe/p.cpp)\n"
                                     "target_link_libraries(kew_probe PUBLIC kew_kinetic)\n")
        write("core/src/kinetic/k.cpp", '#include "kew/triangulation/tds.hpp"\n#include "kew/util/indexed_heap.hpp"\n')
        write("core/src/probe/p.cpp", '#include "kew/triangulation/tds.hpp"\n')
        write("daemon/src/a.cpp", '#include "kew/replay/pacer.hpp"\n#include "kew/core_is_not_a_folder/x.hpp"\n')
        write("daemon/CMakeLists.txt", "add_library(kew_daemon_config src/a.cpp)\n")
        write("protocol/src/b.cpp", '#include "kew/pipeline/pipeline.hpp"\n')
        write("protocol/CMakeLists.txt", "add_library(kew_protocol\n  src/b.cpp\n)\n")
        write("tests/unit/t.cpp", "\n")
        write("tests/unit/sources.cmake", "set(KEW_UNIT_TESTS t.cpp)\n")
        write("tests/support/s.cpp", "\n")
        write("tests/fuzz/CMakeLists.txt", "add_executable(f ${PROJECT_SOURCE_DIR}/tests/support/s.cpp)\n")
        expected_clean = [f"daemon{os.sep}src{os.sep}a.cpp:2: kew/core_is_not_a_folder/ belongs to no library "
                          "(place it in tests/layering/check_layers.py)"]
        if check(root) != expected_clean:
            return ["self-test: a clean tree (downward includes only) was not found clean: " + repr(check(root))]
        write("core/src/c.cpp", '#include "kew/protocol/formats.hpp"\n#include <boost/asio/ip/tcp.hpp>\n')
        write("core/src/kinetic/k2.cpp", '#include "kew/track/track_table.hpp"\n')
        write("core/include/kew/geometry/g.hpp", '#include "kew/kinetic/kinetic_delaunay.hpp"\n')
        write("core/src/beyond/b.cpp", "\n")
        write("core/CMakeLists.txt", "add_library(kew_kinetic src/kinetic/k.cpp src/kinetic/k2.cpp src/c.cpp\n"
                                     "  src/beyond/b.cpp)\n"
                                     "target_link_libraries(kew_kinetic PUBLIC kew_geometry PRIVATE kew_zone)\n")
        write("replay/src/d.hpp", '#include "kew/daemon/config.hpp"\n')
        write("config/CMakeLists.txt", "target_link_libraries(kew_config PUBLIC kew_core kew_replay)\n"
                                       "file(GLOB_RECURSE SOURCES src/*.cpp)\n")
        write("tests/property/forgotten.cpp", "\n")
        findings = check(root)
        expected = ["core includes a header of protocol", "core includes a socket header",
                    "replay includes a header of daemon", "config links kew_replay of replay",
                    "core/kinetic includes a header of core/track", "core/geometry includes a header of core/kinetic",
                    "kew_kinetic links kew_zone, which core/kinetic does not depend on",
                    "core/src/beyond/: a folder of core that is in no place of the order",
                    "file(GLOB) collects sources", "tests/property/forgotten.cpp: named in no CMakeLists.txt"]
        missing = [e for e in expected if not any(e in f.replace(os.sep, "/") for f in findings)]
        problems = [f"self-test: the rule '{m}' did not fire" for m in missing]
        cyclic = dict(CORE, geometry={"pipeline"})
        if not any("has a cycle: " in f and "geometry -> pipeline" in f for f in check(root, cyclic)):
            problems.append("self-test: a cycle in the order of core's folders was not found")
        return problems


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
        print(f"{len(findings)} dependency findings; the order is core <- protocol <- config <- replay <- daemon, "
              f"core's folders as CORE in tests/layering/check_layers.py says")
        return 1
    print("layering: core <- protocol <- config <- replay <- daemon holds, core's folders link one way "
          "and every source is listed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
