#!/usr/bin/env python3
"""The end-to-end tests as ctest sees them: one ctest test per Python test method.

  cases.py list FILE...    print MODULE.Class.method of every test method in the modules
                           (read with ast, nothing imported), one a line
  cases.py run NAME...     run those tests with unittest (verbosely) and exit 0 when all
                           passed, 77 when none failed but one was skipped (ctest's
                           SKIP_RETURN_CODE: a test whose tool is missing is reported as
                           skipped, never as passed), 1 otherwise
"""

import ast
import os
import sys
import unittest

SKIPPED = 77


def test_methods(tree):
    """{class name: [test methods, inherited ones within the module included]}."""
    classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}

    def methods(name, seen=()):
        node = classes.get(name)
        if node is None or name in seen:
            return []
        found = []
        for base in node.bases:
            if isinstance(base, ast.Name):
                found += [m for m in methods(base.id, seen + (name,)) if m not in found]
        for item in node.body:
            if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)) and item.name.startswith("test") \
                    and item.name not in found:
                found.append(item.name)
        return found

    return {name: methods(name) for name in classes}


def list_cases(paths):
    for path in paths:
        module = os.path.splitext(os.path.basename(path))[0]
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        for name, methods in test_methods(tree).items():
            for method in methods:
                print(f"{module}.{name}.{method}")
    return 0


def run_cases(names):
    suite = unittest.defaultTestLoader.loadTestsFromNames(names)
    result = unittest.TextTestRunner(verbosity=2).run(suite)
    if not result.wasSuccessful() or result.testsRun == 0:
        return 1
    if result.skipped:
        for test, reason in result.skipped:
            print(f"SKIPPED {test.id()}: {reason}", file=sys.stderr)
        return SKIPPED
    return 0


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ("list", "run"):
        print(__doc__, file=sys.stderr)
        return 64
    if sys.argv[1] == "list":
        return list_cases(sys.argv[2:])
    return run_cases(sys.argv[2:])


if __name__ == "__main__":
    sys.exit(main())
