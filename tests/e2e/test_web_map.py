"""The live map in a real browser (design §5.8): headless Chromium opens the map
served by a real kewd fed a scenario with conflicts, and what it draws is checked against
kewd's own /api/tracks and /api/alerts; acknowledging from the page must put an ACK object
with "by":"web" on the alert stream. A screenshot is saved in the build directory.

Needs Debian's chromium, chromium-driver and python3-selenium (deploy/bootstrap.sh); ctest
runs it with Debian's python3 (tests/CMakeLists.txt). By hand, from tests/e2e:
  B=../../build KEWD=$B/daemon/kewd KEW_REPLAY=$B/replay/kew-replay KEW_GEN=$B/replay/kew-gen \
  KEW_BUILD_DIR=$B /usr/bin/python3 -m unittest test_web_map -v
To refresh the README's screenshot (docs/img/kew-map.png) as well: KEW_SCREENSHOT_TO_DOCS=1.
"""

import os
import unittest

from kewd_harness import Kewd, Subscriber, count_lines, generate, replay_to, wait_until
from web_map_harness import SOURCE_DIR, BrowserCase, start_browser

WEB_ROOT = os.path.join(SOURCE_DIR, "web")
SEVERITY_RANK = {"none": 0, "caution": 1, "warning": 2, "loss": 3}

# The default live tick (1 s; /ws sends one message per service tick) and a long track
# timeout: once the feed has been replayed the tracks stay, but the data clock moves on with
# the wall clock, so alerts may still change; the page is compared with the API until they
# agree, and each comparison is made on one reading of each.
CONFIG = """
[service]
alert_listen = "127.0.0.1:0"
alert_log = "{workdir}/alerts.jsonl"

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
"""


class WebMap(BrowserCase):

    def start_kewd(self):
        self.kewd = Kewd(CONFIG.format(workdir=self.workdir, web_root=WEB_ROOT), self.workdir)
        wait_until(lambda: self.get_or_none("/api/status"), 20, "kewd's HTTP server")

    def get_or_none(self, path):
        try:
            return self.get(path)
        except OSError:
            return None

    def page(self, selector, attribute):
        """The attribute of each element the CSS selector finds, in page order."""
        return self.js("return Array.from(document.querySelectorAll(arguments[0]), e => e.getAttribute(arguments[1]));",
                       selector, attribute)

    def drawn_tracks(self):
        return self.js("return Array.from(document.querySelectorAll('.leaflet-marker-pane [data-track-id]'),"
                       " e => [e.dataset.trackSrc, e.dataset.trackId]);")

    def test_map_draws_the_api_and_acknowledges_on_the_stream(self):
        self.start_kewd()
        recording = os.path.join(self.workdir, "airways.ndjson")
        generate(recording, "airways", aircraft=300, duration=150, seed=8)
        watcher = Subscriber(self.kewd.alert_port)

        # The page opens before any data: it connects its WebSocket and loads the base map.
        self.driver = start_browser()
        self.driver.get(self.url("/"))
        wait_until(lambda: self.js("return document.getElementById('connection-state').dataset.state") == "live",
                   20, "the page's WebSocket (#connection-state live)")
        wait_until(lambda: self.js("return document.getElementById('map').dataset.basemap") == "loaded", 20,
                   "the Natural Earth base map")

        # The scenario arrives while the page watches: the live updates must bring it all.
        replay_to(f"127.0.0.1:{self.kewd.input_port('feed')}", recording, "--max-speed")
        self.kewd.wait_records(count_lines(recording))
        wait_until(lambda: watcher.objects("ALERTS"), 10, "the stream's snapshot")

        # Every live track is drawn, once, and nothing else.
        def tracks_match():
            api = self.get("/api/tracks")["tracks"]
            drawn = self.drawn_tracks()
            return api if len(drawn) == len(api) and sorted(map(tuple, drawn)) == sorted((t["src"], t["id"]) for t in api) else None
        api_tracks = wait_until(tracks_match, 20, "the page to draw every track of /api/tracks")
        self.assertGreater(len(api_tracks), 100)
        self.assertEqual(self.js("return document.getElementById('aircraft-count').dataset.count"), str(len(api_tracks)))

        # The zones of /api/zones are drawn, one outline each, with their track counts.
        def zones_match():
            api = {z["name"]: z["tracks"] for z in self.get("/api/zones")["list"]}
            drawn = dict(zip(self.page("path[data-zone]", "data-zone"), map(int, self.page("path[data-zone]", "data-tracks"))))
            return api if api and drawn == api else None
        zones = wait_until(zones_match, 25, "the page to outline every zone of /api/zones")
        self.assertEqual(sum(zones.values()) >= len(api_tracks), True, "every track is in at least one zone")

        # Every active alert is a pair line of its severity and a row of the list, most
        # severe first.
        def alerts_match():
            api = {a["id"]: a for a in self.get("/api/alerts")["alerts"]}
            lines = dict(zip(self.page("path.alert-line", "data-alert-id"), self.page("path.alert-line", "data-severity")))
            rows = self.page("#alert-list [data-alert-id]", "data-alert-id")
            count = self.js("return document.getElementById('alert-count').dataset.count")
            if lines != {i: a["severity"] for i, a in api.items()} or sorted(rows) != sorted(api) or count != str(len(api)):
                return None
            ranks = [SEVERITY_RANK[api[i]["severity"]] for i in rows]
            self.assertEqual(ranks, sorted(ranks, reverse=True), "the list is most severe first")
            return api, rows
        by_id, rows = wait_until(alerts_match, 20, "the page to draw and list every alert of /api/alerts")
        self.assertGreater(len(by_id), 3, "the scenario must leave alerts active")

        # The feed's health and, as the recording's data time is not now, the replay clock.
        # The page reads /api/status every 2 s and health moves (no_data, then healthy):
        # compare until one reading of each agrees.
        def health_matches():
            status = self.get("/api/status")
            shown = self.js("return document.getElementById('feed-health').dataset.health")
            return status if shown == status["health"] else None
        status = wait_until(health_matches, 10, "the page to show the feed's health as /api/status says")
        replay = abs(status["data_t"] - status["wall_t"]) > 30
        self.assertEqual(self.js("return !document.getElementById('replay-clock').hidden"), replay)

        # A click on a row centres the map on the pair.
        first = rows[0]
        self.driver.find_element("css selector", f'#alert-list li[data-alert-id="{first}"]').click()
        a, b = by_id[first]["a"], by_id[first]["b"]
        wait_until(lambda: self.js("const c = Kew.map.getBounds();"
                                   " return c.contains([arguments[0], arguments[1]]) && c.contains([arguments[2], arguments[3]]);",
                                   a["lat"], a["lon"], b["lat"], b["lon"]),
                   10, "the map to show the selected pair")

        # Acknowledging one alert from the page: an ACK with "by":"web" on the stream.
        self.driver.find_element("css selector", f'button[data-ack-id="{first}"]').click()
        acks = wait_until(lambda: [o for o in watcher.objects("ACK") if o["by"] == "web"], 10,
                          "an ACK object with \"by\":\"web\" on the alert stream")
        self.assertEqual(acks[0]["ids"], [first])
        self.assertTrue(acks[0].get("client", "").startswith("127.0.0.1:"), acks[0])
        wait_until(lambda: self.page(f'#alert-list li[data-alert-id="{first}"]', "data-ack") == ["true"], 10,
                   "the row to show the acknowledgement")
        self.save_screenshot()

        # "Acknowledge all": the others in one ACK (alerts that ended or opened meanwhile
        # aside, every one active before and after the click).
        before = {a["id"] for a in self.get("/api/alerts")["alerts"] if not a["ack"]}
        self.driver.find_element("css selector", "#ack-all").click()
        acks = wait_until(lambda: [o for o in watcher.objects("ACK") if o["by"] == "web"][1:], 10,
                          "a second ACK from the page")
        after = {a["id"] for a in self.get("/api/alerts")["alerts"]}
        acknowledged = set(acks[0]["ids"])
        self.assertLessEqual(before & after, acknowledged)
        self.assertLessEqual(acknowledged, before | after)
        self.assertNotIn(first, acknowledged)
        wait_until(lambda: all(ack == "true" for i, ack in zip(self.page("#alert-list li", "data-alert-id"),
                                                               self.page("#alert-list li", "data-ack"))
                               if i in acknowledged), 10, "the rows to show the acknowledgement")

        # Offline: everything the page loaded came from kewd, and it logged no error.
        foreign = self.js("return performance.getEntriesByType('resource').map(e => e.name)"
                          ".filter(u => !u.startsWith(location.origin + '/'));")
        self.assertEqual(foreign, [], "the page must load nothing from elsewhere")
        errors = [e for e in self.driver.get_log("browser") if e["level"] == "SEVERE"]
        self.assertEqual(errors, [], "the browser's console")

    def save_screenshot(self):
        docs = os.environ.get("KEW_SCREENSHOT_TO_DOCS") == "1"
        self.screenshot("kew-map.png", os.path.join(SOURCE_DIR, "docs", "img", "kew-map.png") if docs else None)

if __name__ == "__main__":
    unittest.main()
