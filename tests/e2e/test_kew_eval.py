"""End-to-end test of kew-eval (design §2.6) on a generated recording whose
losses of separation are planted with known geometry.

Every planted aircraft flies straight legs in a local east/north frame at one latitude,
so that its latitude and longitude are linear in time and the truth's interpolation is
exact; each pair flies on its own meridian, a degree of longitude from the next. This
file computes the truth's loss starts itself, by the rules of replay/README.md
("kew-eval"), and the pipeline's alert openings from the record schedule, then requires
kew-eval --json --list to agree.

Run by ctest (tests/CMakeLists.txt) with KEW_EVAL and KEW_REPLAY set; by hand:
  KEW_EVAL=build/replay/kew-eval KEW_REPLAY=build/replay/kew-replay \
  python3 -m unittest tests/e2e/test_kew_eval.py -v
"""

import json
import math
import os
import re
import subprocess
import tempfile
import unittest

KEW_EVAL = os.environ.get("KEW_EVAL", "kew-eval")
KEW_REPLAY = os.environ.get("KEW_REPLAY", "kew-replay")

T0 = 1714400000            # whole UTC second
LAT0 = 50.0
PERIOD = 4.0               # every aircraft is seen every 4 s
DURATION = 400.0
NM = 1852.0
S_H = 5 * NM
KT = NM / 3600.0           # m/s per knot
LOOKAHEAD = 120.0          # the default configuration's T

A_WGS84 = 6378137.0
F_WGS84 = 1 / 298.257223563
E2 = F_WGS84 * (2 - F_WGS84)


def radii(lat_deg):
    """(meridional, prime vertical) radii of curvature of WGS84 at lat_deg, metres."""
    s = math.sin(math.radians(lat_deg))
    w = math.sqrt(1 - E2 * s * s)
    return A_WGS84 * (1 - E2) / w ** 3, A_WGS84 / w


M0, N0 = radii(LAT0)


def local_distance(p, q):
    """The truth's horizontal distance (kew::replay::local_distance_m), metres."""
    m, n = radii(0.5 * (p[0] + q[0]))
    east = n * math.cos(math.radians(0.5 * (p[0] + q[0]))) * math.radians(q[1] - p[1])
    north = m * math.radians(q[0] - p[0])
    return math.hypot(east, north)


class Aircraft:
    """Straight legs: each (t_from, north_m, east_m, v_north, v_east) holds from t_from on."""

    def __init__(self, ident, lon0, alt_ft, phase, legs, t_start=T0, t_end=T0 + DURATION, src="eval", squawk=None):
        self.ident, self.src, self.lon0, self.alt_ft, self.squawk = ident, src, lon0, alt_ft, squawk
        self.legs, self.t_start, self.t_end = legs, t_start, t_end
        self.times = []
        t = T0 + phase
        while t < self.t_end:
            if t >= self.t_start:
                self.times.append(round(t, 3))
            t += PERIOD

    def leg(self, t):
        return [leg for leg in self.legs if leg[0] <= t + 1e-9][-1]

    def position(self, t):
        t_from, north, east, vn, ve = self.leg(t)
        north += vn * (t - t_from)
        east += ve * (t - t_from)
        return LAT0 + math.degrees(north / M0), self.lon0 + math.degrees(east / (N0 * math.cos(math.radians(LAT0))))

    def records(self):
        for t in self.times:
            lat, lon = self.position(t)
            _, _, _, vn, ve = self.leg(t)
            record = {"t": t, "id": self.ident, "src": self.src, "lat": lat, "lon": lon, "alt_ft": self.alt_ft,
                      "gs_kt": round(math.hypot(vn, ve) / KT, 3),
                      "trk_deg": round(math.degrees(math.atan2(ve, vn)) % 360, 3),
                      "vr_fpm": 0, "cs": "C" + self.ident}
            if self.squawk:
                record["sq"] = self.squawk
            yield record

    def sample(self, s):
        """The truth's sample at whole second s: linear between records ≤ 20 s apart."""
        for a, b in zip(self.times, self.times[1:]):
            if a <= s <= b:
                pa, pb = self.position(a), self.position(b)
                f = (s - a) / (b - a)
                return pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1])
        return None


def head_on(name, lon0, speed, loss_after, alt_a=30000, alt_b=30000, phase_a=0.3, phase_b=2.3):
    """Two aircraft closing head-on along a meridian at `speed` m/s each, reaching S_h
    `loss_after` seconds after T0 (a non-integer, so the loss second is unambiguous)."""
    d0 = S_H + 2 * speed * loss_after
    a = Aircraft(name + "A", lon0, alt_a, phase_a, [(T0, -d0 / 2, 0.0, speed, 0.0)])
    b = Aircraft(name + "B", lon0, alt_b, phase_b, [(T0, d0 / 2, 0.0, -speed, 0.0)])
    return a, b


def loss_seconds(a, b):
    """Whole seconds at which the pair is within S_h (both at one level, airborne)."""
    out = []
    for s in range(T0, int(T0 + DURATION) + 1):
        pa, pb = a.sample(s), b.sample(s)
        if pa and pb and local_distance(pa, pb) < S_H:
            out.append(s)
    return out


def planted():
    """(aircraft, expectations by pair name)."""
    aircraft, expect = [], {}
    # Four head-on conflicts at one level, losses starting at T0 + 150.5 + 20k. The radar
    # phases differ, so do the openings; none is within 0.5 s of loss − T, where the
    # first conflicting evaluation is.
    phases = [(0.3, 2.3), (1.0, 3.0), (1.7, 3.7), (3.1, 1.6)]
    for k in range(4):
        a, b = head_on(f"H{k}", 8.0 + k, 200.0 + 20 * k, 150.5 + 20 * k, phase_a=phases[k][0], phase_b=phases[k][1])
        aircraft += [a, b]
        expect[f"H{k}"] = ("hit", "detected", a, b)
    # Passing 975 ft apart (adjacent levels within the altimetry tolerance): kew alerts
    # today (S_v = 1,000 ft); the truth sees no loss and no close call.
    a, b = head_on("N", 12.0, 220.0, 160.5, alt_b=30975)
    aircraft += [a, b]
    expect["N"] = ("nuisance", None, a, b)
    # Head-on below 1,500 ft: not airborne by the truth's rules.
    a, b = head_on("L", 13.0, 80.0, 160.5, alt_a=1000, alt_b=1000)
    aircraft += [a, b]
    expect["L"] = ("ineligible", None, a, b)
    # Converging to a predicted 4.5 NM miss, B turns away east at 5.5 NM: a close call.
    east = 4.5 * NM
    along = math.sqrt((5.5 * NM) ** 2 - east ** 2)  # along-track separation at the turn
    v = 230.0
    t_turn = T0 + 2.3 + 4 * 50  # a record time of B, so the turn is exact in the records
    d0 = along + 2 * v * (t_turn - T0)
    b_north_at_turn = d0 / 2 - v * (t_turn - T0)
    a = Aircraft("CA", 14.0, 31000, 0.3, [(T0, -d0 / 2, 0.0, v, 0.0)])
    b = Aircraft("CB", 14.0, 31000, 2.3, [(T0, d0 / 2, east, -v, 0.0), (t_turn, b_north_at_turn, east, 0.0, v)])
    aircraft += [a, b]
    expect["C"] = ("close_call", None, a, b)
    # Parallel 5.2 NM apart, then B turns straight at A: the loss begins 1.5 s after the
    # turn and no alert can be confirmed before A's next update 3.5 s after it: missed.
    t_turn = T0 + 0.8 + 4 * 60
    a = Aircraft("MA", 15.0, 32000, 0.3, [(T0, 0.0, 0.0, 250.0, 0.0)])
    b = Aircraft("MB", 15.0, 32000, 0.8, [(T0, 0.0, 5.2 * NM, 250.0, 0.0),
                                          (t_turn, 250.0 * (t_turn - T0), 5.2 * NM, 0.0, -250.0)])
    aircraft += [a, b]
    expect["M"] = (None, "missed", a, b)
    # B is first seen 4.5 NM from A, head-on: no track can be warned of on its first
    # sample: unwarnable.
    v = 240.0
    t_first = T0 + 2.3 + 4 * 40
    d_first = 4.5 * NM
    d0 = d_first + 2 * v * (t_first - T0)
    a = Aircraft("UA", 16.0, 33000, 0.3, [(T0, -d0 / 2, 0.0, v, 0.0)])
    b = Aircraft("UB", 16.0, 33000, 2.3, [(T0, d0 / 2, 0.0, -v, 0.0)], t_start=t_first)
    aircraft += [a, b]
    expect["U"] = (None, "unwarnable", a, b)
    # One aircraft seen as two tracks (another source) with one code, 0.2 NM and 100 ft
    # apart: kew opens no alert, and any would be scored ineligible.
    a = Aircraft("SAME", 17.0, 34000, 0.3, [(T0, 0.0, 0.0, 240.0, 0.0)], squawk="4711")
    b = Aircraft("SAME", 17.0, 34100, 1.1, [(T0, 0.0, 0.2 * NM, 240.0, 0.0)], src="eval2", squawk="4711")
    aircraft += [a, b]
    expect["S"] = ("ineligible", None, a, b)
    return aircraft, expect


def write_recording(path, aircraft):
    records = [r for x in aircraft for r in x.records()]
    records.sort(key=lambda r: (r["t"], r["src"], r["id"]))
    with open(path, "w") as f:
        for r in records:
            f.write(json.dumps(r) + "\n")


def expected_open(a, b, loss_t):
    """The default pipeline's opening of the pair's alert: it evaluates the pair on every
    update of either track, finds the conflict from the first update at or after
    loss − T, and opens on the second conflicting evaluation (confirm = 2)."""
    updates = sorted(set(a.times) | set(b.times))
    first = next(i for i, u in enumerate(updates) if u >= loss_t - LOOKAHEAD)
    return updates[first + 1]


class KewEval(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._dir = tempfile.TemporaryDirectory(prefix="kew-eval-e2e-")
        cls.recording = os.path.join(cls._dir.name, "planted.ndjson")
        cls.aircraft, cls.expect = planted()
        write_recording(cls.recording, cls.aircraft)

    @classmethod
    def tearDownClass(cls):
        cls._dir.cleanup()

    def run_eval(self, *args):
        result = subprocess.run([KEW_EVAL, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.assertEqual(result.returncode, 0, result.stderr.decode())
        return result.stdout

    def pair_of(self, a_id, b_id):
        for name, (_, _, a, b) in self.expect.items():
            if {a_id, b_id} == {a.ident, b.ident}:
                return name
        return None

    def test_planted_losses_hits_and_warning_times(self):
        out = json.loads(self.run_eval("--json", "--list", self.recording))
        truth, run = out["truth"], out["runs"][0]
        self.assertEqual(run["name"], "default")
        self.assertEqual(run["lookahead_s"], LOOKAHEAD)

        planted_losses = {name: e for name, e in self.expect.items() if e[1]}
        self.assertEqual(truth["loss_events"], len(planted_losses))
        self.assertEqual(run["loss_events"], len(planted_losses))
        losses = {self.pair_of(l["a"]["id"], l["b"]["id"]): l for l in run["loss_list"]}
        self.assertEqual(set(losses), set(planted_losses))
        alerts = {}
        for alert in run["alert_list"]:
            alerts.setdefault(self.pair_of(alert["a"]["id"], alert["b"]["id"]), []).append(alert)

        for name, (alert_class, outcome, a, b) in planted_losses.items():
            loss = losses[name]
            seconds = loss_seconds(a, b)
            self.assertEqual(loss["start_t"], seconds[0], name)
            self.assertEqual(loss["end_t"], seconds[-1], name)
            self.assertEqual(loss["outcome"], outcome, name)
            if outcome != "detected":
                continue
            # The loss of a head-on pair starts at the planted second; the warning is
            # what the record schedule says, and at least 30 s.
            opened = expected_open(a, b, seconds[0] - 0.5)
            self.assertLessEqual(abs(loss["warning_s"] - (seconds[0] - opened)), 1.0, name)
            self.assertGreaterEqual(loss["warning_s"], 30.0, name)
            self.assertEqual([x["class"] for x in alerts[name]], ["hit"], name)
            self.assertEqual(alerts[name][0]["loss_t"], seconds[0])
            self.assertAlmostEqual(alerts[name][0]["t_open"], opened, delta=1.0)

        # The missed loss: the turn leaves no time, and no alert opened before it.
        self.assertIsNone(losses["M"]["alert"])
        self.assertEqual(losses["U"]["eligible_for_s"], 0)

        # Every alert of a pair planted without a loss has its planted class; the one
        # aircraft's tracks are ineligible as one aircraft, the low pair as not airborne.
        for name, (alert_class, outcome, _, _) in self.expect.items():
            if alert_class and not outcome:
                for alert in alerts.get(name, []):
                    self.assertEqual(alert["class"], alert_class, name)
        for alert in alerts.get("S", []):
            self.assertEqual(alert["reason"], "one_aircraft")
        for alert in alerts.get("L", []):
            self.assertEqual(alert["reason"], "not_airborne")
        self.assertNotIn(None, alerts)  # no alert between unrelated aircraft

        # Alerts of the head-on pairs, of the pair whose loss was unwarnable and the late
        # one of the missed loss (opened after it began, within its window) are hits.
        hit_pairs = [n for n in alerts if self.expect[n][0] == "hit" or n in ("U", "M")]
        self.assertEqual(run["hit"], sum(len(alerts[n]) for n in hit_pairs))
        for alert in alerts.get("M", []):
            self.assertGreater(alert["t_open"], losses["M"]["start_t"] + 1)
        self.assertEqual(run["detected"], 4)
        self.assertEqual(run["missed"], 1)
        self.assertEqual(run["unwarnable"], 1)
        self.assertEqual(run["alerts"], sum(len(v) for v in alerts.values()))
        share = (run["nuisance"] + run["ineligible"]) / run["alerts"]
        self.assertAlmostEqual(run["undesirable_share"], share, places=4)
        # 20 tracks; the two tracks of one aircraft are one.
        self.assertEqual(truth["tracks"], 20)
        self.assertEqual(truth["aircraft"], 19)
        self.assertEqual(truth["merged_by_proximity"], 1)

    def test_same_input_same_bytes_and_alert_logs_score_alike(self):
        table = self.run_eval(self.recording)
        self.assertEqual(table, self.run_eval(self.recording))
        self.assertIn(b"undesirable", table)
        as_json = self.run_eval("--json", self.recording)
        self.assertEqual(as_json, self.run_eval("--json", self.recording))

        log = os.path.join(self._dir.name, "alerts.jsonl")
        subprocess.run([KEW_REPLAY, "--alerts", log, self.recording], check=True, stderr=subprocess.DEVNULL)
        both = json.loads(self.run_eval("--json", "--alerts", log, self.recording))
        self.assertEqual([r["name"] for r in both["runs"]], ["alerts.jsonl"])
        run = json.loads(as_json)["runs"][0]
        logged = both["runs"][0]
        for key in ("alerts", "hit", "close_call", "nuisance", "ineligible", "detected", "missed", "unwarnable"):
            self.assertEqual(logged[key], run[key], key)
        self.assertIsNone(logged["records"])

        # Two configurations side by side: a longer look-ahead warns earlier (the first
        # head-on pair as soon as both are seen, 30 s earlier than with 120 s).
        longer = os.path.join(self._dir.name, "longer.toml")
        with open(longer, "w") as f:
            f.write("[probe]\nlookahead_s = 180\n")
        side = json.loads(self.run_eval("--json", "--config", longer, "--alerts", log, self.recording))
        self.assertEqual([r["name"] for r in side["runs"]], ["longer", "alerts.jsonl"])
        self.assertEqual(side["runs"][0]["lookahead_s"], 180.0)
        self.assertGreater(side["runs"][0]["warning_s"]["min"], run["warning_s"]["min"] + 25)
        self.assertGreater(side["runs"][0]["warning_s"]["max"], run["warning_s"]["max"] + 55)

    def test_explain_names_the_stage_of_every_missed_and_unwarnable_loss(self):
        run = json.loads(self.run_eval("--json", "--explain", self.recording))["runs"][0]
        explained = {self.pair_of(e["a"]["id"], e["b"]["id"]): e for e in run["explain"]}
        # The detected losses were warned 30 s ahead and more: only M and U are explained.
        self.assertEqual(set(explained), {"M", "U"})
        # M flew parallel 5.2 NM apart until B's turn: the probe saw no loss ahead.
        m = explained["M"]
        self.assertEqual((m["outcome"], m["stage"]), ("missed", "probe_clear"))
        self.assertIn("no horizontal loss within the look-ahead", m["reason"])
        self.assertRegex(m["reason"], r"5\.[12]\d NM and 0 ft apart")
        # Then, in the loss, the conflict awaits its confirmation; the late alert ends the notes.
        self.assertEqual([s["stage"] for s in m["spans"][-2:]], ["probe_clear", "confirm_pending"])
        self.assertGreaterEqual(m["spans"][-1]["from_t"], m["start_t"] - 2)  # from B's turn on
        # UB's first record came 4.5 NM from UA, already in conflict; without an address it
        # opens no alert before its second (min_records, design §4.5).
        u = explained["U"]
        self.assertEqual((u["outcome"], u["stage"]), ("unwarnable", "excluded"))
        self.assertIn("first_records: eval:UB seen in 1 record(s), fewer than 2", u["reason"])
        self.assertEqual([s["stage"] for s in u["spans"][:2]], ["no_track", "excluded"])
        self.assertEqual(run["census"], {"excluded": {"missed": 0, "late": 0, "unwarnable": 1},
                                         "probe_clear": {"missed": 1, "late": 0, "unwarnable": 0}})
        # The text form says the same, and explaining changes no figure.
        text = self.run_eval("--explain", self.recording).decode()
        self.assertIn("missed: probe_clear:", text)
        self.assertIn("census of 2 missed", text)
        plain = json.loads(self.run_eval("--json", self.recording))["runs"][0]
        for key in ("alerts", "hit", "nuisance", "detected", "missed", "unwarnable", "warning_s"):
            self.assertEqual(run[key], plain[key], key)

    def test_baselines_are_scored_beside_kew_by_the_same_truth(self):
        out = json.loads(self.run_eval("--json", "--baseline", "statebased", "--baseline", "raw", self.recording))
        default, statebased, raw = out["runs"]
        self.assertEqual([r["name"] for r in out["runs"]], ["default", "statebased", "raw"])
        self.assertEqual([r["kind"] for r in out["runs"]], ["config", "baseline", "baseline"])
        self.assertEqual((statebased["lookahead_s"], statebased["confirm"]), (300.0, 1))
        self.assertEqual((raw["lookahead_s"], raw["confirm"]), (default["lookahead_s"], default["confirm"]))
        for run in (statebased, raw):
            self.assertEqual(run["loss_events"], default["loss_events"])
        # The head-on pair at 1,000 ft opens no alert in kew (the lower limit) and one in
        # both baselines, which the truth finds not airborne.
        self.assertEqual(default["ineligible_reasons"]["not_airborne"], 0)
        self.assertGreaterEqual(raw["ineligible_reasons"]["not_airborne"], 1)
        self.assertGreaterEqual(statebased["ineligible_reasons"]["not_airborne"], 1)
        # 300 s of look-ahead warns of the planted head-on losses earlier than kew's 120 s.
        self.assertGreater(statebased["warning_s"]["p50"], default["warning_s"]["p50"] + 40)

    def test_usage_errors_exit_64(self):
        for args in (["--no-such-flag", self.recording], [], ["--h-nm", "0", self.recording],
                     ["--v-ft", "150", self.recording], ["--baseline", "bluesky", self.recording]):
            result = subprocess.run([KEW_EVAL, *args], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            self.assertEqual(result.returncode, 64, args)


if __name__ == "__main__":
    unittest.main()
