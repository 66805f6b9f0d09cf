"""What the live map's browser tests (test_web_map.py, test_web_map_dense.py,
test_web_map_volumes.py) share: headless Chromium, a test case that is skipped, saying
so, without it, and kewd's page opened at a given size, let settle and photographed.

Needs Debian's chromium, chromium-driver and python3-selenium (deploy/bootstrap.sh); ctest
runs the tests with Debian's python3 (tests/CMakeLists.txt).
"""

import json
import os
import shutil
import sys
import unittest
import urllib.request

from kewd_harness import Subscriber, temporary_directory, wait_until

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD_DIR = os.environ.get("KEW_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))

NOT_CHECKED = "the live map was NOT checked"  # ctest reports the test as skipped on this text


def browser_missing():
    """Why the browser cannot run, or None."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "python3-selenium is not installed (ctest runs Debian's python3)"
    for program in ("chromium", "chromedriver"):
        if shutil.which(program) is None:
            return f"{program} is not installed (Debian chromium, chromium-driver)"
    return None


def start_browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    options = Options()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1600,1000", "--no-first-run", "--disable-extensions",
                "--proxy-server=direct://", "--proxy-bypass-list=*"):
        options.add_argument(arg)
    options.binary_location = shutil.which("chromium")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)


class BrowserCase(unittest.TestCase):
    """A test of the page in Chromium: skipped, saying so, without a browser; a working
    directory, self.kewd and self.driver closed at the end."""

    def setUp(self):
        missing = browser_missing()
        if missing:
            print(f"\n*** {missing}: {NOT_CHECKED} ***\n", file=sys.stderr)
            self.skipTest(f"{missing}: {NOT_CHECKED}")
        self._dir = temporary_directory()
        self.workdir = self._dir.name
        self.kewd = None
        self.driver = None

    def tearDown(self):
        if self.driver:
            self.driver.quit()
        if self.kewd:
            self.kewd.kill()
        while Subscriber.opened:
            Subscriber.opened.pop().close()
        self._dir.cleanup()

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def url(self, path):
        return f"http://127.0.0.1:{self.kewd.http_port}{path}"

    def get(self, path):
        """kewd's JSON answer to GET `path`."""
        with urllib.request.urlopen(self.url(path), timeout=10) as reply:
            self.assertEqual(reply.status, 200, path)
            return json.loads(reply.read())

    def open_map(self, window):
        """Chromium on kewd's page, its viewport (not the window with its frame) `window`
        (width, height) px."""
        self.driver = start_browser()
        self.driver.set_window_size(*window)
        inner = self.js("return [window.innerWidth, window.innerHeight];")
        self.driver.set_window_size(2 * window[0] - inner[0], 2 * window[1] - inner[1])
        self.driver.get(self.url("/"))

    def settle(self):
        """Waits for the map to stop moving and two animation frames (the labels' layout)."""
        wait_until(lambda: self.js("return !document.querySelector('.leaflet-zoom-anim');"), 10, "the zoom to end")
        self.driver.set_script_timeout(10)
        self.driver.execute_async_script(
            "const done = arguments[0]; setTimeout(() => requestAnimationFrame(() => requestAnimationFrame(done)), 400);")

    def screenshot(self, name, copy_to=None):
        """Saves the page as BUILD_DIR/`name`, and copies it to `copy_to` when given."""
        os.makedirs(BUILD_DIR, exist_ok=True)
        path = os.path.join(BUILD_DIR, name)
        self.assertTrue(self.driver.save_screenshot(path))
        print(f"screenshot: {path}", file=sys.stderr)
        if copy_to:
            os.makedirs(os.path.dirname(copy_to) or ".", exist_ok=True)
            shutil.copyfile(path, copy_to)
            print(f"screenshot: {copy_to}", file=sys.stderr)
