#!/usr/bin/env python3
"""The thesis' figures drawn again from kew_thesis_bench's JSON, with the thesis' values marked.

    python3 tests/bench/thesis/plot_thesis.py docs/data/thesis-effects.json docs/img

Writes four PNGs (Debian's python3-matplotlib):
  thesis-queue.png      the priority queue over time with and without H (thesis Fig. 10.4)
  thesis-tolerance.png  the update cost against τ (thesis Fig. 10.3)
  thesis-discarded.png  the discarded share of computed events with and without §8.3
                        (thesis Figs. 8.3 and 8.6)
  thesis-sweeps.png     the three ratios and the update cost along every sweep
The thesis' values are those its text reads from its figures (Vomáčka, §8.3 and §10.4):
the threshold leaves ≈ 1 % of the queue, τ > 0 leaves ≈ 15 % of the update time, and
about half of the computed events are discarded without §8.3, a third with it.
"""

import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

THESIS_QUEUE = 0.01
THESIS_UPDATE = 0.15
THESIS_DISCARDED_OFF = 0.5
THESIS_DISCARDED_ON = 1 / 3
KEW = "#1f5fa8"
KEPT = "#2a9d5c"
THESIS_WAY = "#c2571a"
MARK = "#888888"


def caption(data):
    m = data["machine"]
    return f"kew_thesis_bench, {data['date'][:10]}, {m['cpu']}, {m['build_type']}, median of {data['repeats']}"


def setting_label(p):
    return (f"{p['aircraft']:,} aircraft, P = {p['period_s']:g} s, σ = {p['noise_sigma_m']:g} m, "
            f"τ = {p['tolerance_m']:g} m, H = P")


def queue_figure(data, out):
    s = data["setting"]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for name, label, colour in (("no_threshold", "without threshold (H = ∞)", THESIS_WAY),
                                ("baseline", "with threshold H = P", KEW)):
        trace = s["configurations"][name]["queue_trace"]
        ax.plot(trace["t_s"], trace["failures"], color=colour, label=f"scheduled failures, {label}")
        total = [f + r for f, r in zip(trace["failures"], trace["renewals"])]
        ax.plot(trace["t_s"], total, color=colour, linestyle=":", label=f"failures + renewal entries, {label}")
    no_h = s["configurations"]["no_threshold"]["queue_mean"]
    ax.axhline(THESIS_QUEUE * no_h, color=MARK, linestyle="--",
               label=f"thesis Fig. 10.4: ≈ 1 % of the queue without threshold")
    ax.set_xlabel("data time (s)")
    ax.set_ylabel("queue entries")
    ax.set_title(f"Priority queue length (as thesis Fig. 10.4): ratio {s['ratios']['queue_failures']:.3f}")
    ax.legend(fontsize=7, loc="center right")
    fig.text(0.01, 0.01, setting_label(s["parameters"]) + "; " + caption(data), fontsize=6, color=MARK)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(os.path.join(out, "thesis-queue.png"), dpi=110)
    plt.close(fig)


def tolerance_figure(data, out):
    points = data["sweeps"]["tolerance"]
    tau = [p["value"] for p in points]
    fig, (cost, ratio) = plt.subplots(1, 2, figsize=(10, 4.5))
    series = (("baseline", "velocity-only within τ (thesis' method)", KEW, "update_cost"),
              ("kept_models", "kept models (design §2.3)", KEPT, "update_cost_kept_models"),
              ("remove_insert", "remove + insert beyond τ (thesis' reinsertion)", THESIS_WAY,
               "update_cost_remove_insert"))
    # τ = 0 runs at every point (the denominator of its ratios): its cost moves a little.
    zero = [p["configurations"]["zero_tolerance"]["update_us_per_call"] for p in points]
    for name, label, colour, key in series:
        cost.plot(tau, [p["configurations"][name]["update_us_per_call"] for p in points], "o-", color=colour,
                  label=label)
        ratio.plot(tau, [p["ratios"][key] for p in points], "o-", color=colour, label=label)
    cost.plot(tau, zero, ":", color=MARK, label="τ = 0 (every update reinserts)")
    cost.plot(tau, [THESIS_UPDATE * z for z in zero], "--", color=MARK, label="thesis Fig. 10.3: ≈ 15 % of τ = 0")
    ratio.axhline(THESIS_UPDATE, color=MARK, linestyle="--", label="thesis Fig. 10.3: ≈ 0.15")
    ratio.axhline(0.5, color=MARK, linestyle=":", label="0.5")
    cost.set_xlabel("τ (m)")
    cost.set_ylabel("update() µs per call")
    cost.set_ylim(bottom=0)
    ratio.set_xlabel("τ (m)")
    ratio.set_ylabel("update cost, τ / τ = 0")
    ratio.set_ylim(0, 1.1)
    cost.set_title("Update cost against τ (as thesis Fig. 10.3)")
    ratio.set_title("Ratio to τ = 0")
    cost.legend(fontsize=7)
    ratio.legend(fontsize=7)
    p = points[0]["parameters"]
    fig.text(0.01, 0.01, f"{p['aircraft']:,} aircraft, P = {p['period_s']:g} s, σ = {p['noise_sigma_m']:g} m, H = P; "
             + caption(data), fontsize=6, color=MARK)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(os.path.join(out, "thesis-tolerance.png"), dpi=110)
    plt.close(fig)


def discarded_figure(data, out):
    points = data["sweeps"]["aircraft"]
    n = [p["value"] for p in points]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(n, [p["configurations"]["no_reduction"]["discarded_share"] for p in points], "o-", color=THESIS_WAY,
            label="§8.3 off")
    ax.plot(n, [p["configurations"]["baseline"]["discarded_share"] for p in points], "o-", color=KEW,
            label="§8.3 on")
    ax.axhline(THESIS_DISCARDED_OFF, color=THESIS_WAY, linestyle="--", label="thesis Fig. 8.3: ≈ 1/2 discarded")
    ax.axhline(THESIS_DISCARDED_ON, color=KEW, linestyle="--", label="thesis Fig. 8.6: ≈ 1/3 discarded")
    ax.set_xscale("log")
    ax.set_ylim(0, 1)
    ax.set_xlabel("aircraft")
    ax.set_ylabel("discarded / computed events")
    ax.set_title("Discarded share of computed events (as thesis Figs. 8.3, 8.6)")
    ax.legend(fontsize=7)
    p = points[0]["parameters"]
    fig.text(0.01, 0.01, f"P = {p['period_s']:g} s, σ = {p['noise_sigma_m']:g} m, τ = {p['tolerance_m']:g} m, H = P; "
             "the thesis: 100 points in free motion, no updates; " + caption(data), fontsize=6, color=MARK)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(os.path.join(out, "thesis-discarded.png"), dpi=110)
    plt.close(fig)


def sweeps_figure(data, out):
    sweeps = [(name, data["sweeps"][name]) for name in ("aircraft", "period", "noise", "tolerance", "horizon")
              if name in data["sweeps"]]
    fig, axes = plt.subplots(2, len(sweeps), figsize=(3.2 * len(sweeps), 6.5), squeeze=False)
    units = {"aircraft": "aircraft", "period": "P (s)", "noise": "σ (m)", "tolerance": "τ (m)", "horizon": "H (periods)"}
    for column, (name, points) in enumerate(sweeps):
        # H = ∞ is drawn at twice the largest finite H.
        finite = [p["value"] for p in points if p["value"] is not None]
        x = [p["value"] if p["value"] is not None else 2 * max(finite) for p in points]
        top, bottom = axes[0][column], axes[1][column]
        for key, label, colour in (("queue_failures", "queue, H / ∞", "#222222"), ("update_cost", "update, τ / 0", KEW),
                                   ("update_cost_kept_models", "kept models / τ = 0", KEPT),
                                   ("update_cost_remove_insert", "remove + insert, τ / 0", THESIS_WAY),
                                   ("discarded", "discarded, §8.3 on / off", MARK)):
            top.plot(x, [p["ratios"].get(key) for p in points], "o-", color=colour, label=label, markersize=3)
        for config, label, colour in (("zero_tolerance", "τ = 0", MARK), ("baseline", "velocity-only", KEW),
                                      ("kept_models", "kept models", KEPT),
                                      ("remove_insert_zero_tolerance", "remove + insert, τ = 0", THESIS_WAY)):
            bottom.plot(x, [p["configurations"][config]["update_us_per_call"] for p in points], "o-", color=colour,
                        label=label, markersize=3)
        if name in ("aircraft", "horizon"):
            top.set_xscale("log")
            bottom.set_xscale("log")
        top.set_ylim(0, 1.2)
        top.set_title(f"sweep: {name}", fontsize=9)
        bottom.set_xlabel(units[name] + (" (∞ drawn at the right end)" if name == "horizon" else ""), fontsize=8)
        bottom.set_ylim(bottom=0)
        if column == 0:
            top.set_ylabel("ratio")
            bottom.set_ylabel("update() µs per call")
    axes[0][0].legend(fontsize=6)
    axes[1][0].legend(fontsize=6)
    fig.text(0.01, 0.005, "each sweep varies one parameter from " + setting_label(data["setting"]["parameters"])
             + "; " + caption(data), fontsize=6, color=MARK)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.savefig(os.path.join(out, "thesis-sweeps.png"), dpi=100)
    plt.close(fig)


def main():
    source, out = sys.argv[1], sys.argv[2]
    with open(source, encoding="utf-8") as f:
        data = json.load(f)
    queue_figure(data, out)
    if "tolerance" in data["sweeps"]:
        tolerance_figure(data, out)
    if "aircraft" in data["sweeps"]:
        discarded_figure(data, out)
    if data["sweeps"]:
        sweeps_figure(data, out)


if __name__ == "__main__":
    main()
