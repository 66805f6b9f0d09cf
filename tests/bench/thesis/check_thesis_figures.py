#!/usr/bin/env python3
"""Checks that the thesis' figures in docs/ are current on today's code.

    python3 tests/bench/thesis/check_thesis_figures.py BENCH docs/data/thesis-effects.json

Runs kew_thesis_bench --counts-only at the documented setting (its parameters are read
from the JSON) and compares the ratios that are counts, not times — the queue with and
without H, the events computed, the discarded share with and without §8.3, the share of
velocity-only updates — with the documented ones. The engine is deterministic, so they
agree to rounding (a change of compiler may move a root by an ulp): the tolerance is
0.2 % of the documented value. A difference means the engine's behaviour changed and the figures,
plots and text of docs/performance-kinetic.md must be measured again
(`kew_thesis_bench --sweeps all --json docs/data/thesis-effects.json`, then
plot_thesis.py). The timed ratios cannot be checked by a test: they are the JSON's.
"""

import json
import subprocess
import sys
import tempfile

COUNT_RATIOS = ("queue_failures", "queue_entries", "events_computed", "discarded", "velocity_share")
RELATIVE_TOLERANCE = 0.002


def main():
    bench, documented_path = sys.argv[1], sys.argv[2]
    with open(documented_path, encoding="utf-8") as f:
        documented = json.load(f)["setting"]
    p = documented["parameters"]
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([bench, "--counts-only", "--aircraft", str(p["aircraft"]), "--period", str(p["period_s"]),
                        "--duration", str(p["duration_s"]), "--noise", str(p["noise_sigma_m"]),
                        "--tolerance", str(p["tolerance_m"]), "--seed", str(p["seed"]), "--json", out.name],
                       check=True, stdout=subprocess.DEVNULL)
        with open(out.name, encoding="utf-8") as f:
            measured = json.load(f)["setting"]["ratios"]
    failures = []
    for key in COUNT_RATIOS:
        want, got = documented["ratios"][key], measured[key]
        status = "ok" if abs(want - got) <= RELATIVE_TOLERANCE * abs(want) else "DIFFERS"
        print(f"{key}: documented {want:.4f}, measured {got:.4f}: {status}")
        if status != "ok":
            failures.append(key)
    if failures:
        print(f"check_thesis_figures: {', '.join(failures)} changed: measure and plot again "
              "(docs/performance-kinetic.md says how)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
