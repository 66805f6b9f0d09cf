"""The live map's volumes of the area proximity warning (design §4.11, §5.8), in headless
Chromium on a real kewd: two [[volume]] tables, a restricted polygon EDR-1 and a circle
that follows the helicopter CHX12, and a feed written record by record at the wall
clock's pace in which DLH4AB flies into EDR-1 while CHX12 flies past it. Checked from the
DOM: both volumes are drawn and labelled with their names (the followed circle around
CHX12's symbol as it moves; no label overprints another), GET /api/volumes says what the
page drew, the area alert
is listed as "DLH4AB → EDR-1 (restricted) …" with its line and the volume outlined in
its severity colour, a click on it brings the aircraft and the volume into view, and the
page logs no JavaScript error. A screenshot is saved as build/map-volumes.png.

Needs Debian's chromium, chromium-driver and python3-selenium, as test_web_map.py; ctest
runs it with Debian's python3. By hand, from tests/e2e:
  B=../../build KEWD=$B/daemon/kewd KEW_BUILD_DIR=$B /usr/bin/python3 -m unittest test_web_map_volumes -v
KEW_WEB_ROOT=DIR serves another web/ (the page of an earlier commit fails: it draws no
volume and drops area alerts), and KEW_SCREENSHOT_TO_DOCS=1 copies the screenshot to
docs/img/map-volumes.png.
"""

import json
import math
import os
import socket
import threading
import time
import unittest

from kewd_harness import Kewd, wait_until
from web_map_harness import SOURCE_DIR, BrowserCase
from test_web_map_dense import VISIBLE_LABELS, overlapping

WEB_ROOT = os.environ.get("KEW_WEB_ROOT", os.path.join(SOURCE_DIR, "web"))
WINDOW = (1280, 800)

CONFIG = """
[service]
alert_listen = "127.0.0.1:0"

[tracks]
timeout_s = 900.0

[[input]]
name = "feed"
format = "ndjson"
transport = "tcp-server"
address = "127.0.0.1:0"

[http]
listen = "127.0.0.1:0"
web_root = "{web_root}"

[[volume]]
name = "EDR-1"
kind = "restricted"
polygon = [[50.0, 8.0], [50.1, 8.0], [50.1, 8.2], [50.0, 8.2]]
floor_ft = 0
ceiling_ft = 5000

[[volume]]
name = "CHX escort"
follow = "CHX*"
radius_nm = 1
floor_ft = -1000
ceiling_ft = 1000
"""

KT = 1852.0 / 3600.0  # m/s per knot
M_PER_DEG = 111195.0


class Flight:
    """A straight, level flight from (lat, lon) on `trk_deg` at `gs_kt`, started at t0."""

    def __init__(self, ident, callsign, lat, lon, alt_ft, trk_deg, gs_kt, t0):
        self.ident, self.callsign = ident, callsign
        self.lat, self.lon, self.alt_ft, self.trk_deg, self.gs_kt, self.t0 = lat, lon, alt_ft, trk_deg, gs_kt, t0

    def at(self, t):
        d = (t - self.t0) * self.gs_kt * KT
        north = d * math.cos(math.radians(self.trk_deg))
        east = d * math.sin(math.radians(self.trk_deg))
        lat = self.lat + north / M_PER_DEG
        lon = self.lon + east / (M_PER_DEG * math.cos(math.radians(self.lat)))
        return {"t": round(t, 3), "id": self.ident, "cs": self.callsign, "lat": round(lat, 6), "lon": round(lon, 6),
                "alt_ft": self.alt_ft, "gs_kt": self.gs_kt, "trk_deg": self.trk_deg, "vr_fpm": 0, "src": "feed"}


class Feed(threading.Thread):
    """Writes one record per flight each second, stamped with the wall clock, to kewd's
    NDJSON input until stopped."""

    def __init__(self, port, flights):
        super().__init__(daemon=True)
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=10)
        self.flights = flights
        self.stopping = threading.Event()
        self.sent = 0

    def run(self):
        while not self.stopping.is_set():
            now = time.time()
            lines = "".join(json.dumps(f.at(now)) + "\n" for f in self.flights)
            try:
                self.sock.sendall(lines.encode())
            except OSError:
                return
            self.sent += len(self.flights)
            self.stopping.wait(1.0)

    def stop(self):
        self.stopping.set()
        self.join(timeout=5)
        self.sock.close()


class WebMapVolumes(BrowserCase):
    def tearDown(self):
        if getattr(self, "feed", None):
            self.feed.stop()
        super().tearDown()

    def label(self, name):
        """The text of the volume's name label when it is shown, else None."""
        return self.js(
            "const el = document.querySelector('.ref-label.volume[data-volume=\"' + CSS.escape(arguments[0]) + '\"] .map-label');"
            " if (!el) return null; const r = el.getBoundingClientRect(), s = getComputedStyle(el);"
            " return r.width > 0 && s.visibility !== 'hidden' && s.display !== 'none' ? el.textContent : null;", name)

    def circle_off_centre_px(self, ident):
        """How far (px) the followed circle's centre is from the symbol of `ident`, and where
        the symbol is; None while either is missing."""
        return self.js(
            "const path = document.querySelector('path.volume[data-volume=\"CHX escort\"]');"
            " const marker = document.querySelector('.leaflet-marker-pane [data-track-id=\"' + arguments[0] + '\"]');"
            " if (!path || !marker) return null;"
            " const c = path.getBoundingClientRect(), m = marker.getBoundingClientRect();"
            " return [Math.hypot((c.left + c.right) / 2 - m.left, (c.top + c.bottom) / 2 - m.top), m.left, m.top];",
            ident)

    def save_screenshot(self):
        docs = os.environ.get("KEW_SCREENSHOT_TO_DOCS") == "1"
        self.screenshot("map-volumes.png", os.path.join(SOURCE_DIR, "docs", "img", "map-volumes.png") if docs else None)

    def test_volumes_are_drawn_and_an_area_alert_is_listed_and_shown(self):
        self.kewd = Kewd(CONFIG.format(web_root=WEB_ROOT), self.workdir)
        volumes = self.get("/api/volumes")
        self.assertEqual([f["properties"]["name"] for f in volumes["features"]], ["EDR-1", "CHX escort"])
        self.assertEqual(volumes["features"][0]["geometry"]["type"], "Polygon")
        self.assertIsNone(volumes["features"][1]["geometry"])
        self.assertEqual(volumes["features"][1]["properties"]["follow"], "CHX*")

        self.open_map(WINDOW)
        wait_until(lambda: self.js("return document.getElementById('connection-state').dataset.state") == "live",
                   20, "the page's WebSocket (#connection-state live)")
        wait_until(lambda: self.js("return document.getElementById('map').dataset.basemap") == "loaded", 20,
                   "the offline base map")

        # The fixed volume is drawn before any traffic, with its kind; the followed one
        # only once its aircraft is seen.
        wait_until(lambda: self.js("return document.querySelectorAll('path.volume[data-volume=\"EDR-1\"]').length") == 1, 20,
                   "EDR-1 drawn (path[data-volume])")
        self.assertEqual(self.js("const p = document.querySelector('path.volume[data-volume=\"EDR-1\"]');"
                                 " return [p.getAttribute('data-volume-kind'), p.getAttribute('data-active')];"),
                         ["restricted", "true"])
        self.assertEqual(self.js("return document.getElementById('map').dataset.volumes"), "2")
        self.assertEqual(self.js("return document.querySelectorAll('path.volume[data-volume=\"CHX escort\"]').length"), 0)
        legend = self.js("return Array.from(document.querySelectorAll('#volume-legend li'), li => li.dataset.kind);")
        self.assertEqual(legend[:4], ["prohibited", "restricted", "danger", "watch"])

        # DLH4AB eastbound at 3,000 ft, 27 s from EDR-1's western edge; CHX12 westbound at
        # 1,500 ft along 50.125°N, its circle just north of EDR-1 (and of DLH4AB's band).
        t0 = time.time()
        dlh = Flight("3C4B26", "DLH4AB", 50.05, 7.93, 3000, 90.0, 360.0, t0)
        chx = Flight("3C6E81", "CHX12", 50.125, 8.17, 1500, 270.0, 90.0, t0)
        self.feed = Feed(self.kewd.input_port("feed"), [dlh, chx])
        self.feed.start()

        wait_until(lambda: self.js("return document.querySelectorAll('path.volume[data-volume=\"CHX escort\"]').length") == 1,
                   20, "the followed circle drawn around CHX12")
        self.assertEqual(self.js("return document.querySelector('path.volume[data-volume=\"CHX escort\"]')"
                                 ".getAttribute('data-follows');"), chx.ident)

        # The area alert: kewd has it, the list shows it with the volume's name, its line
        # is drawn and the volume is outlined in its colour.
        def area_alert():
            alerts = [a for a in self.get("/api/alerts")["alerts"] if a.get("kind") == "apw"]
            return alerts[0] if alerts else None
        alert = wait_until(area_alert, 60, "an area alert (kind apw) in /api/alerts")
        self.assertEqual(alert["volume"], "EDR-1")
        self.assertEqual(alert["a"]["cs"], "DLH4AB")
        self.assertNotIn("b", alert)
        row = f'#alert-list li[data-alert-id="{alert["id"]}"]'
        text = wait_until(lambda: self.js("const li = document.querySelector(arguments[0]);"
                                          " return li && li.querySelector('.pair').textContent;", row),
                          20, "the area alert listed")
        self.assertRegex(text, r"^DLH4AB → EDR-1 \(restricted\) (in \d+ s|inside)(  #\d+)?$")
        wait_until(lambda: self.js("return document.querySelectorAll("
                                   "'path.alert-line[data-alert-id=\"' + arguments[0] + '\"][data-alert-volume=\"EDR-1\"]').length;",
                                   alert["id"]) == 1, 10, "the area alert's line")
        wait_until(lambda: (self.js("return document.querySelector('path.volume[data-volume=\"EDR-1\"]')"
                                    ".getAttribute('data-alert');") or "").startswith("sev-"),
                   10, "EDR-1 outlined in the alert's severity colour")
        wait_until(lambda: (self.js("return document.querySelector('.leaflet-marker-pane [data-track-id=\"'"
                                    " + arguments[0] + '\"]').dataset.alert;", dlh.ident) or "").startswith("sev-"),
                   10, "DLH4AB ringed as an alerting aircraft")
        self.assertEqual(self.js("return document.getElementById('alert-count').dataset.count"),
                         str(len(self.get("/api/alerts")["alerts"])))

        # A click on the row: DLH4AB and the whole of EDR-1 in view.
        self.driver.find_element("css selector", row).click()
        self.settle()
        in_view = self.js(
            "const b = Kew.map.getBounds(); const t = Array.from(Kew.state.tracks.values()).find(t => t.id === arguments[0]);"
            " return b.contains([t.lat, t.lon]) && b.contains([50.0, 8.0]) && b.contains([50.1, 8.2]);", dlh.ident)
        self.assertTrue(in_view, "DLH4AB and EDR-1 in view after the click")

        # Both names shown; the followed circle stays centred on CHX12's symbol as it moves.
        wait_until(lambda: self.label("EDR-1") == "EDR-1", 10, "EDR-1's name shown")
        wait_until(lambda: self.label("CHX escort") == "CHX escort", 10, "the followed circle's name shown")
        first = wait_until(lambda: (lambda r: r if r and r[0] < 3 else None)(self.circle_off_centre_px(chx.ident)), 10,
                           "the followed circle centred on CHX12")

        def moved_and_centred():
            r = self.circle_off_centre_px(chx.ident)
            return r if r and r[0] < 3 and math.hypot(r[1] - first[1], r[2] - first[2]) >= 4 else None
        wait_until(moved_and_centred, 20, "CHX12 to move with its circle centred on it")
        self.settle()
        self.save_screenshot()
        # The names take their places with the other labels: none overprints another.
        self.assertEqual(overlapping(self.js(VISIBLE_LABELS)), [], "labels overprinted")

        errors = [e for e in self.driver.get_log("browser") if e["level"] == "SEVERE"]
        self.assertEqual(errors, [], "the browser's console")


if __name__ == "__main__":
    unittest.main()
