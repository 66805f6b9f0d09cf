#!/usr/bin/env python3
"""Where a kinetic update's time goes: a velocity-only update against a reinsertion.

    python3 tests/bench/thesis/profile_thesis.py BUILD/tests/bench/kew_thesis_bench [bench flags]

Runs kew_thesis_bench --only under `perf record --call-graph dwarf` (Debian's
linux-perf; a build with debug information, RelWithDebInfo, unwinds best) three times:
every update velocity-only (the baseline with τ = 10 km, which no report of the
workload exceeds), every update a reinsertion (τ = 0), and every update the thesis'
reinsertion by remove() and insert(). Only the samples inside the loop's call for a
measurement count (update(), or remove() and insert(); the setup's insertions, one per
aircraft, are 1 % of the last run's). Each is given to the first phase its stack names
from the leaf up (certificate polynomials, root isolation, the approach test, queue
work, scheduling, triangulation combinatorics, event execution) and printed as µs per
update: the phase's share of those samples times the update's time as the bench timed it.
Then advance() between updates, with H = P and with H = ∞, split by the queue entry it
serves (failures, renewals, approaches and drifts, the queue itself): what the
threshold's renewals cost against the failures it spares.
"""

import re
import subprocess
import sys
import tempfile

PHASES = [
    ("certificate polynomials", r"incircle_polynomial|orientation_polynomial|dot_polynomial|lifted_determinant|"
                                r"unless_rounding_noise|edge_certificate"),
    ("root isolation (Sturm, bounds)", r"Sturm|sign_changes|first_positive_crossing|locate_first_root|"
                                       r"negated_remainder|normalise|root_bound|certified_sign|certainly_negative|"
                                       r"evaluate|refine|bisect|newton"),
    ("approach test", r"approach_offset"),
    ("queue work", r"EventQueue|schedule_edge|clear_edge|is_live"),
    ("scheduling", r"schedule_dirty_faces|reschedule_star|solve_edge|watch_degenerate|earliest_failure|"
                   r"face_created|face_destroyed|grow_to"),
    ("triangulation (remove, locate, insert)", r"triangulation::(Tds::|DelaunayTriangulation::(?!position|trajectory))|orient2d|"
                                               r"geometry::incircle|attach|detach|locate|reinsert|"
                                               r"attached_neighbour|TwinRegistry"),
    ("event execution", r"KineticDelaunay::advance|KineticDelaunay::execute|flip_degenerate"),
]
ADVANCE_RUNS = [
    ("H = P", ["--only", "baseline"]),
    ("H = ∞", ["--only", "no_threshold"]),
]
OTHER = "other (allocation, copies)"
ENTRY = r"KineticDelaunay::(update|remove|insert)$"
RUNS = [
    ("velocity-only updates", ["--only", "baseline", "--tolerance", "10000"]),
    ("reinsertions (engine)", ["--only", "zero_tolerance"]),
    ("reinsertions (remove + insert)", ["--only", "remove_insert_zero_tolerance"]),
]


def samples(perf_data):
    """Each sample's stack as a list of function names, leaf first."""
    text = subprocess.run(["perf", "script", "-i", perf_data, "-F", "ip,sym"], check=True, capture_output=True,
                          text=True).stdout
    stack = []
    for line in text.splitlines() + [""]:
        line = line.strip()
        if not line:
            if stack:
                yield stack
            stack = []
            continue
        parts = line.split(None, 1)
        if len(parts) == 2:
            stack.append(re.sub(r"\+0x[0-9a-f]+.*$", "", parts[1]))


def event_kind(frames):
    """Which entry of the queue a sample inside advance() serves."""
    if any(f.endswith("execute_failure") for f in frames):
        return "failures (flip, new certificates)"
    if any(f.endswith(("execute_approach", "execute_drift")) for f in frames):
        return "approaches, drifts"
    if any(f.endswith("KineticDelaunay::execute") for f in frames):
        return "renewals (solve again)"
    if any(re.search(r"EventQueue::(pop|compact)|is_live", f) for f in frames):
        return "queue (pop, stale entries, compaction)"
    return "other"


def attribute(bench, flags, entry, classify, per_call):
    """Runs the bench under perf; the samples under the loop's call of `entry` (a pattern
    of the function run_once calls) are classified by classify(frames below run_once),
    and each class gets its share of the time per call the bench printed after `per_call`."""
    with tempfile.TemporaryDirectory() as folder:
        data = folder + "/perf.data"
        out = subprocess.run(["perf", "record", "-q", "-F", "2000", "--call-graph", "dwarf", "-o", data, bench] + flags,
                             check=True, capture_output=True, text=True).stdout
        microseconds = float(re.search(r"([\d.]+) µs per " + per_call, out).group(1))
        counts, total = {}, 0
        for stack in samples(data):
            caller = next((i for i, name in enumerate(stack) if name.endswith("run_once")), None)
            if caller is None or caller == 0 or not re.search(entry, stack[caller - 1]):
                continue
            total += 1
            kind = classify(stack[:caller])
            counts[kind] = counts.get(kind, 0) + 1
    return {kind: microseconds * n / total for kind, n in counts.items()}, microseconds


def phase_of(frames):
    """The first phase the stack names from the leaf up."""
    return next((name for frame in frames for name, pattern in PHASES if re.search(pattern, frame)), OTHER)


def table(title, columns, rows):
    print(f"| {title} | " + " | ".join(name for name, _, _ in columns) + " |")
    print("|---|" + "---|" * len(columns))
    for row in rows:
        print(f"| {row} | " + " | ".join(f"{by_row.get(row, 0.0):.2f}" for _, by_row, _ in columns) + " |")
    print("| **as the bench timed it** | " + " | ".join(f"**{total:.2f}**" for _, _, total in columns) + " |")


def main():
    bench, extra = sys.argv[1], sys.argv[2:]
    # The update's own samples: those under the call the loop makes for a measurement
    # (update(), or remove() and insert() for the thesis' way).
    updates = [(name, *attribute(bench, flags + extra, ENTRY, phase_of, "update")) for name, flags in RUNS]
    table("update(), µs per update", updates, [name for name, _ in PHASES] + [OTHER])
    print()
    # What the threshold costs between updates: advance() with H = P against H = ∞.
    advances = [(name, *attribute(bench, flags + extra, r"KineticDelaunay::advance$", event_kind, "advance"))
                for name, flags in ADVANCE_RUNS]
    table("advance(), µs per measurement", advances,
          ["failures (flip, new certificates)", "renewals (solve again)", "approaches, drifts",
           "queue (pop, stale entries, compaction)", "other"])


if __name__ == "__main__":
    main()
