"""The live map for dense traffic (design §5.8), in headless Chromium on a real kewd: the
demo's recording (an hour of ADS-B around Black Rock City, 88NV) cut at 10:12:49Z, when
four losses of separation are active among six aircraft close together, and replayed
into kewd, whose long track timeout keeps the moment on the map. Checked from the DOM: no
two visible labels (aircraft, alert figures, aerodromes, range rings) overlap; every
alerting aircraft's label is visible; aerodrome idents and the scale bar are drawn; the
audible cue's toggle is off by default and remembered; selecting each alert zooms to its
pair. A screenshot is saved as build/map-dense.png.

Needs Debian's chromium, chromium-driver and python3-selenium, as test_web_map.py; ctest
runs it with Debian's python3. By hand, from tests/e2e:
  B=../../build KEWD=$B/daemon/kewd KEW_BUILD_DIR=$B /usr/bin/python3 -m unittest test_web_map_dense -v
KEW_WEB_ROOT=DIR serves another web/ (another version of the page), and
KEW_DENSE_SCREENSHOT=FILE copies the screenshot there (docs/img/map-dense-*.png); the
picture is taken before the checks, so a page that fails them is pictured too.
"""

import gzip
import json
import os
import unittest

from kewd_harness import Kewd, wait_until
from web_map_harness import SOURCE_DIR, BrowserCase

WEB_ROOT = os.environ.get("KEW_WEB_ROOT", os.path.join(SOURCE_DIR, "web"))
RECORDING = os.path.join(SOURCE_DIR, "tests", "data", "text", "readsb_1hr.json.gz")
MOMENT = 1693303969  # 2023-08-29 10:12:49Z: the demo's picture (deploy/demo.sh)
WINDOW = (1280, 800)  # the demo's picture's size

# The recording ends at MOMENT; the tracks stay (a long timeout) and the data clock then
# stands still, so the alerts of that moment stay as they are.
CONFIG = """
[service]
alert_listen = "127.0.0.1:0"

[tracks]
timeout_s = 900.0

[http]
listen = "127.0.0.1:0"
web_root = "{web_root}"
"""

# Every label the page shows: aircraft, the alerts' figures, aerodromes and range rings;
# visible ones only (a dropped label is hidden but keeps its size), as page rectangles.
VISIBLE_LABELS = """
const map = document.getElementById('map').getBoundingClientRect();
const out = [];
for (const el of document.querySelectorAll('.ac-label, .leaflet-tooltip.alert-label, .ref-label .map-label')) {
  const r = el.getBoundingClientRect();
  const style = getComputedStyle(el);
  if (r.width === 0 || r.height === 0 || style.visibility === 'hidden' || style.display === 'none') continue;
  if (r.right <= map.left || r.left >= map.right || r.bottom <= map.top || r.top >= map.bottom) continue;
  const marker = el.closest('[data-track-id]');
  out.push({what: marker ? 'aircraft ' + marker.dataset.trackId : el.className + ' ' + el.textContent,
            x0: r.left, y0: r.top, x1: r.right, y1: r.bottom});
}
return out;
"""


def overlapping(labels, tolerance=0.5):
    """The pairs of labels whose rectangles share more than `tolerance` px each way."""
    pairs = []
    for i, a in enumerate(labels):
        for b in labels[i + 1:]:
            w = min(a["x1"], b["x1"]) - max(a["x0"], b["x0"])
            h = min(a["y1"], b["y1"]) - max(a["y0"], b["y0"])
            if w > tolerance and h > tolerance:
                pairs.append((a["what"], b["what"]))
    return pairs


class WebMapDense(BrowserCase):
    def start_at_the_moment(self):
        cut = os.path.join(self.workdir, "readsb-to-101249.json")
        with gzip.open(RECORDING, "rt") as src, open(cut, "w") as dst:
            for line in src:
                if json.loads(line).get("now", 0) <= MOMENT:
                    dst.write(line)
        self.kewd = Kewd(CONFIG.format(web_root=WEB_ROOT), self.workdir, extra_args=["--replay", cut, "--max-speed"])
        self.kewd.wait_log("replay of ", 60)

        def the_moment():
            alerts = self.get("/api/alerts")
            return alerts if alerts["t"] == MOMENT and len(alerts["alerts"]) >= 4 else None
        return wait_until(the_moment, 30, "kewd at 10:12:49Z with its four alerts")["alerts"]

    def open_page(self, alerts):
        self.open_map(WINDOW)
        tracks = self.get("/api/tracks")["tracks"]
        wait_until(lambda: self.js("return document.getElementById('map').dataset.basemap") == "loaded", 20,
                   "the offline base map")
        wait_until(lambda: self.js("return document.querySelectorAll('.leaflet-marker-pane [data-track-id]').length")
                   == len(tracks), 20, "every track drawn")
        wait_until(lambda: self.js("return document.querySelectorAll('path.alert-line').length") == len(alerts), 20,
                   "every alert drawn")
        self.settle()

    def save_screenshot(self):
        self.screenshot("map-dense.png", os.environ.get("KEW_DENSE_SCREENSHOT"))

    def visible(self, selector):
        return self.js("const el = document.querySelector(arguments[0]); if (!el) return false;"
                       " const r = el.getBoundingClientRect(), s = getComputedStyle(el);"
                       " return r.width > 0 && s.visibility !== 'hidden' && s.display !== 'none';", selector)

    def marker(self, party):
        return f'.leaflet-marker-pane [data-track-id="{party["id"]}"][data-track-src="{party["src"]}"]'

    def assert_labels_apart(self, alerts, when):
        labels = self.js(VISIBLE_LABELS)
        self.assertGreater(len(labels), 4, when)
        self.assertEqual(overlapping(labels), [], f"labels overprinted {when}")
        for a in alerts:
            for party in (a["a"], a["b"]):
                self.assertTrue(self.visible(self.marker(party) + " .ac-label"),
                                f"the label of {party.get('cs') or party['id']} (alert {a['id']}) {when}")

    def test_labels_never_overlap_and_an_alert_zooms_to_its_pair(self):
        alerts = self.start_at_the_moment()
        self.open_page(alerts)
        self.save_screenshot()

        self.assert_labels_apart(alerts, "at 10:12:49Z")
        # The reference layers: an aerodrome's ident in view and the scale bar.
        aerodromes = self.js(
            "const map = document.getElementById('map').getBoundingClientRect();"
            " return Array.from(document.querySelectorAll('.ref-label.aerodrome .map-label')).filter(el => {"
            "  const r = el.getBoundingClientRect();"
            "  return getComputedStyle(el).visibility !== 'hidden' && r.width > 0 && r.left >= map.left &&"
            "         r.right <= map.right && r.top >= map.top && r.bottom <= map.bottom; }).map(el => el.textContent);")
        self.assertTrue(aerodromes, "an aerodrome named in view")
        self.assertEqual(self.js("return document.getElementById('map').dataset.aerodromes;"),
                         str(len(self.get("/api/aerodromes"))), "the page has kewd's whole table")
        scale = self.js("return Array.from(document.querySelectorAll('.leaflet-control-scale-line'), e => e.textContent);")
        self.assertEqual(len(scale), 2, "a scale bar of two lines")
        self.assertTrue(scale[0].endswith("km") or scale[0].endswith(" m"), scale)
        self.assertTrue(scale[1].endswith("NM"), scale)

        # The audible cue: a toggle, off unless turned on, remembered.
        self.assertEqual(self.js("return document.getElementById('audible').getAttribute('aria-pressed');"), "false")
        self.assertIsNone(self.js("return localStorage.getItem('kew.audible');"))
        self.driver.find_element("css selector", "#audible").click()
        self.assertEqual(self.js("return [document.getElementById('audible').getAttribute('aria-pressed'),"
                                 " localStorage.getItem('kew.audible')];"), ["true", "on"])
        self.driver.find_element("css selector", "#audible").click()
        self.assertEqual(self.js("return localStorage.getItem('kew.audible');"), "off")

        # Selecting an alert zooms to its pair: both symbols inside the map, labels apart.
        for a in alerts:
            zoom_before = self.js("return Kew.map.getZoom();")
            self.driver.find_element("css selector", f'#alert-list li[data-alert-id="{a["id"]}"]').click()
            self.settle()
            inside = self.js(
                "const map = document.getElementById('map').getBoundingClientRect();"
                " return Array.from(arguments, s => document.querySelector(s + ' .ac-symbol').getBoundingClientRect())"
                "  .every(r => r.left >= map.left && r.right <= map.right && r.top >= map.top && r.bottom <= map.bottom);",
                self.marker(a["a"]), self.marker(a["b"]))
            self.assertTrue(inside, f"both aircraft of alert {a['id']} in view")
            self.assertGreaterEqual(self.js("return Kew.map.getZoom();"), min(zoom_before, 12))
            self.assert_labels_apart(alerts, f"after selecting alert {a['id']}")

        errors = [e for e in self.driver.get_log("browser") if e["level"] == "SEVERE"]
        self.assertEqual(errors, [], "the browser's console")


if __name__ == "__main__":
    unittest.main()
