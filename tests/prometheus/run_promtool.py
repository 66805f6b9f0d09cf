#!/usr/bin/env python3
"""The shipped alerting rules through promtool (ctest prometheus-rules).

  run_promtool.py DEPLOY_DIR    promtool check rules DEPLOY_DIR/prometheus/kew-rules.yml, then
                                promtool test rules DEPLOY_DIR/prometheus/kew-rules.test.yml

Exits 0 when both pass, 77 when promtool is absent (ctest's SKIP_RETURN_CODE: reported
as skipped, never as passed), 1 otherwise.
"""

import os
import shutil
import subprocess
import sys

SKIPPED = 77


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 64
    promtool = shutil.which("promtool")
    if not promtool:
        print("SKIPPED LOUDLY: promtool absent (Debian package prometheus, deploy/bootstrap.sh): "
              "the alerting rules are NOT checked", file=sys.stderr)
        return SKIPPED
    directory = os.path.join(sys.argv[1], "prometheus")
    failed = False
    for command in (["check", "rules", "kew-rules.yml"], ["test", "rules", "kew-rules.test.yml"]):
        print("$ promtool " + " ".join(command), flush=True)
        failed |= subprocess.run([promtool, *command], cwd=directory).returncode != 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
