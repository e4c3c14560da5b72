# SPDX-License-Identifier: GPL-2.0-or-later
"""Opens a page of `kanegen animate --format html` in headless Chromium.

Debian's chromium, driven through WebDriver (Debian's chromium-driver and
python3-selenium: nothing from npm), loads the page from file:// and the
probe reads what it draws through its window.kanegen API (the three.js
groups' world matrices). check_html.py says what to read and compares.

probe(page, times=[t...] or "page" (every frame's time), scales=[s...],
bodies=[name...], beams=[name...], shapes=[name...] (a rigid part's drawn
corners), columns=[plotted column...], screenshot=PNG path, play_seconds=S,
controls=a beam whose nodes the magnification moves) returns a dict:
errors (console errors, uncaught exceptions, requests that are not file: or
data:), names, at, played, controls.
"""
import json
import os
import time

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def missing():
    """What the probe needs and this machine lacks, each with the Debian package that brings it."""
    out = []
    if not os.path.exists(CHROMIUM):
        out.append("%s (Debian's chromium)" % CHROMIUM)
    if not os.path.exists(CHROMEDRIVER):
        out.append("%s (Debian's chromium-driver)" % CHROMEDRIVER)
    try:
        import selenium  # noqa: F401
    except ImportError:
        out.append("python3's selenium module (Debian's python3-selenium)")
    return out


def _start():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    # No sandbox: CI runs as root in a VM, where chromium's sandbox cannot start; the page is the test's
    # own. SwiftShader: WebGL on the CPU, which headless chromium no longer falls back to by itself.
    for arg in ("--headless=new", "--no-sandbox", "--window-size=1280,720", "--disable-dev-shm-usage",
                "--enable-unsafe-swiftshader", "--hide-scrollbars"):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    # The page's viewport itself 1280 x 720 (--window-size counts the window's frame too).
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                           {"width": 1280, "height": 720, "deviceScaleFactor": 1, "mobile": False})
    return driver


def _errors(driver):
    """Console errors and uncaught exceptions, and every request that left file: and data:."""
    out = []
    for entry in driver.get_log("browser"):
        if entry["level"] == "SEVERE":
            out.append("console: " + entry["message"])
    for entry in driver.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        if message.get("method") == "Network.requestWillBeSent":
            url = message["params"]["request"]["url"]
            if not url.startswith(("file:", "data:")):
                out.append("request: " + url)
    return out


_READ = """
const [t, scale, bodies, beams, shapes] = arguments, k = window.kanegen;
k.setScale(scale);
k.setTime(t);
const out = { t: k.time(), scale, bodies: {}, nodes: {}, shapes: {} };
for (const name of bodies) out.bodies[name] = k.bodyPosition(name);
for (const name of beams) out.nodes[name] = k.nodePositions(name);
for (const name of shapes) out.shapes[name] = k.shapes(name);
return out;
"""

_PLAY = """
const done = arguments[arguments.length - 1], seconds = arguments[0];
const k = window.kanegen, wait = (ms) => new Promise((go) => setTimeout(go, ms));
(async () => {
  k.setTime(k.times()[0]);
  k.play();
  await wait(500);  // past the first frames' shader compilation
  const t0 = k.time(), f0 = k.framesDrawn(), w0 = performance.now();
  await wait(1000 * seconds);
  const t1 = k.time(), f1 = k.framesDrawn(), w1 = performance.now();
  k.pause();
  done({ t0, t1, frames: f1 - f0, seconds: (w1 - w0) / 1000, fps: (f1 - f0) / ((w1 - w0) / 1000) });
})();
"""

_NAMES = """
return {
  title: document.title,
  model: document.getElementById('model').textContent,
  bodies: Array.from(document.querySelectorAll('#bodies li'), (li) => li.textContent),
  columns: Array.from(document.getElementById('columns').options, (o) => o.textContent),
  scripts: document.scripts.length,
  pwned: window.pwned !== undefined,
  api: window.kanegen ? window.kanegen.bodyNames() : null,
};
"""

_PICK_COLUMNS = """
const names = arguments[0], list = document.getElementById('columns');
for (const option of list.options) option.selected = names.includes(option.textContent);
list.dispatchEvent(new Event('change'));
window.kanegen.setTime(window.kanegen.time());
"""


def _controls(driver, beam):
    """The controls as a user works them: the play button, the slider, the speed and the magnification."""
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select

    k = driver.execute_script
    out = {}
    Select(driver.find_element(By.ID, "speed")).select_by_visible_text("0.25")
    k("window.kanegen.setTime(window.kanegen.times()[0])")
    driver.find_element(By.ID, "play").click()
    out["playingAfterClick"] = k("return window.kanegen.playing()")
    time.sleep(0.4)
    driver.find_element(By.ID, "play").click()
    out["pausedAfterClick"] = not k("return window.kanegen.playing()")
    out["timeAfterPlay"] = k("return window.kanegen.time()")
    k("const s = document.getElementById('slider'); s.value = s.max; s.dispatchEvent(new Event('input'));")
    out["timeAfterSlider"] = k("return window.kanegen.time()")
    before = k("return window.kanegen.nodePositions(arguments[0])", beam)
    field = driver.find_element(By.ID, "scale")
    field.clear()
    field.send_keys("0")  # typed: an input event with the value 0
    out["nodesMoveWithScale"] = before != k("return window.kanegen.nodePositions(arguments[0])", beam)
    return out


def probe(page, **plan):
    driver = _start()
    result = {"errors": []}
    try:
        driver.set_script_timeout(60)
        driver.get("file://" + os.path.abspath(page))
        deadline = time.time() + 20
        while not driver.execute_script("return !!(window.kanegen && window.kanegen.framesDrawn() > 0)"):
            if time.time() > deadline:
                raise RuntimeError("%s: the page drew nothing in 20 s: %s" % (page, _errors(driver)))
            time.sleep(0.1)
        result["names"] = driver.execute_script(_NAMES)
        times = plan.get("times") or []
        if times == "page":
            times = driver.execute_script("return window.kanegen.times()")
        result["at"] = [driver.execute_script(_READ, t, s, plan.get("bodies", []), plan.get("beams", []),
                                              plan.get("shapes", []))
                        for s in plan.get("scales", []) for t in times]
        if plan.get("columns"):  # the plotted columns, picked as a user would
            driver.execute_script(_PICK_COLUMNS, plan["columns"])
        if plan.get("screenshot"):  # at the last time and scale read
            driver.save_screenshot(plan["screenshot"])
        if plan.get("play_seconds"):
            result["played"] = driver.execute_async_script(_PLAY, plan["play_seconds"])
        if plan.get("controls"):
            result["controls"] = _controls(driver, plan["controls"])
        result["three"] = driver.execute_script("return THREE.REVISION")
        result["errors"] = _errors(driver)
    finally:
        driver.quit()
    return result


if __name__ == "__main__":  # python3 probe_page.py PLAN.json: the result as JSON (for trying a page by hand)
    import sys

    with open(sys.argv[1]) as f:
        plan = json.load(f)
    print(json.dumps(probe(plan.pop("page"), **plan)))
