#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""kanegen animate --format html, opened in headless Chromium.

The page is loaded from file:// in Debian's chromium, driven through
WebDriver (Debian's chromium-driver and python3-selenium: probe_page.py),
and read through its window.kanegen API, which takes
positions from the three.js groups' world matrices (float32). The reference
is what check_vtk.py compares with: the generated kernels' outputs that
`kanegen simulate` wrote for the same rows (frame origins against point
outputs at those origins; a flexible link's nodes, at scale 10 and 1,
against its origin, x axis and node displacement outputs), and in 3-D the
payload of models/spatial_arm2.json against its point output. Tolerance:
1e-5 L, L the largest distance of a frame origin from the world origin over
the run; float32 keeps about 6e-8 L, so this is loose by two orders only to
allow a few roundings in the page's matrix products.

URDF <visual> shapes (tests/data/models/animate_visuals.urdf) against
positions computed by hand (visuals_reference.py), their names as text.

Also: hostile names (tests/data/models/hostile_names.urdf, and CSV columns
that try to end the page's <script>) come back as text, byte for byte, and
run nothing; playback of models/flexible_arm10.json over 10 s draws at least
30 frames a second (requestAnimationFrame count over 3 s of playback); a
missing three.js is an error that says how to get it, with nothing written.

The three.js in the pages is the one kanegen finds: npm's (r185) where
viewer/node_modules has it, else Debian's libjs-three (r111); the test says
which. Skips (exit 77) when chromium, chromium-driver, python3-selenium or
any three.js is missing, unless KANEGEN_REQUIRE_BROWSER is set (.ci/run sets
it): then it fails.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import probe_page  # noqa: E402

MIN_FPS = 30
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(*args, env=None):
    subprocess.run([str(a) for a in args], check=True, env=env)


def browser_missing(kanegen, source, work):
    """What the test needs and this machine lacks: the WebDriver path, and a three.js for kanegen to inline."""
    out = probe_page.missing()
    model, csv_path = hostile_run(source, work)[:2]
    r = subprocess.run([kanegen, "animate", csv_path, model, "-o", os.path.join(work, "three_check"), "--format",
                        "html", "--quiet"], capture_output=True, text=True)
    if r.returncode != 0 and "three.js is not found" in r.stderr:
        out.append("a three.js for kanegen to inline (%s)" % r.stderr.strip())
    else:  # anything else is this test's to fail on
        check(r.returncode == 0, "kanegen animate --format html of hostile_names.urdf: %r" % r.stderr)
    return out


def probe(page, **plan):
    """What the page shows, read in headless chromium (probe_page.py)."""
    try:
        result = probe_page.probe(page, **plan)
    except Exception as e:  # noqa: BLE001 (a failing browser is a failure of this test, with its reason)
        check(False, "%s: the browser probe failed: %s" % (page, e))
        return None
    check(not result["errors"], "%s: errors in the page: %s" % (page, result["errors"]))
    return result


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:] if r]


def point(header, row, name):
    return [row[header.index(name + "." + a)] for a in "xyz"]


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def check_missing_three(kanegen, csv_path, model, work):
    """A three.js that is not there: the error says where to get it, and no page is written."""
    out = os.path.join(work, "no_three")
    env = dict(os.environ, KANEGEN_THREE_JS=os.path.join(work, "missing", "three.cjs"))
    r = subprocess.run([kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--quiet"],
                       capture_output=True, text=True, env=env)
    check(r.returncode == 1 and "KANEGEN_THREE_JS=" in r.stderr and "three.cjs" in r.stderr,
          "a missing three.js is refused: %r" % r.stderr)
    check(not os.path.exists(out), "nothing written without three.js")
    r = subprocess.run([kanegen, "simulate", model, "--t-end", "0.1", "--animate", out], capture_output=True,
                       text=True, env=env)
    check(r.returncode == 1 and "KANEGEN_THREE_JS=" in r.stderr and "kanegen: generating" not in r.stderr,
          "simulate --animate (html) without three.js is refused before the run: %r" % r.stderr)
    check(not os.path.exists(out), "nothing written by simulate --animate without three.js")


def check_arm(kanegen, model, work):
    csv_path = os.path.join(work, "arm.csv")
    run(kanegen, "simulate", model, "--t-end", "0.3", "-o", csv_path, "--quiet")
    header, rows = read_csv(csv_path)
    check_missing_three(kanegen, csv_path, model, work)
    out = os.path.join(work, "arm_html")
    run(kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--frames", "3", "--scale", "10",
        "--quiet")
    page = os.path.join(out, "animate_arm.html")
    check(os.listdir(out) == ["animate_arm.html"], "one file, the page: %s" % os.listdir(out))
    result = probe(page, times="page", scales=[10, 1], bodies=["hub", "motor", "link2"],
                   beams=["link2"], play_seconds=1, controls="link2")
    if not result:
        return
    print("three.js r%s, inlined by kanegen, draws the pages" % result["three"])
    by_time = {row[0]: row for row in rows}
    reach = max(distance(point(header, row, name), [0, 0, 0]) for row in rows
                for name in ("hub_origin", "motor_origin", "link2_origin"))
    tol = 1e-5 * reach
    check(len(result["at"]) == 6, "3 frames at 2 scales read, got %d" % len(result["at"]))
    worst = 0.0
    for at in result["at"]:
        row = by_time.get(at["t"])
        check(row is not None, "t=%r of the page is a row of the CSV" % at["t"])
        if row:
            worst = max(worst, check_arm_frame(header, row, at, tol))
    print("arm: largest position difference %.3g m (tolerance %.3g m = 1e-5 x reach %.3g m)" % (worst, tol, reach))
    played = result.get("played")
    check(played and played["frames"] > 0 and played["t1"] != played["t0"], "the arm plays: %r" % played)
    c = result.get("controls") or {}
    check(c.get("playingAfterClick") and c.get("pausedAfterClick") and 0 < c.get("timeAfterPlay", 0) < rows[-1][0],
          "the play button plays and pauses, at speed 0.25: %r" % c)
    check(c.get("timeAfterSlider") == rows[-1][0] and c.get("nodesMoveWithScale"),
          "the slider sets the time, the magnification field moves the nodes: %r" % c)


def check_arm_frame(header, row, at, tol):
    where = "t=%g scale %g" % (at["t"], at["scale"])
    worst = 0.0
    for body, name in (("hub", "hub_origin"), ("motor", "motor_origin"), ("link2", "link2_origin")):
        err = distance(at["bodies"][body], point(header, row, name))
        worst = max(worst, err)
        check(err < tol, "%s: %s off by %.3g" % (where, name, err))
    o2 = point(header, row, "link2_origin")
    ex = [a - b for a, b in zip(point(header, row, "link2_x"), o2)]
    ey = [-ex[1], ex[0], 0.0]  # link2 turns about z
    nodes = at["nodes"]["link2"]
    check(len(nodes) == 5, "%s: link2 has 5 nodes, got %d" % (where, len(nodes)))
    s = at["scale"]
    for node, name in ((4, "tip2"), (2, "mid2")):
        ux, uy = (row[header.index(name + "." + a)] for a in "xy")
        expected = [o + e * (0.25 * node + s * ux) + f * (s * uy) for o, e, f in zip(o2, ex, ey)]
        err = distance(nodes[node], expected)
        worst = max(worst, err)
        check(err < tol, "%s: link2 node %d off by %.3g" % (where, node, err))
    return worst


def check_spatial(kanegen, model, work):
    """models/spatial_arm2.json: turns about z, then about y on a flexible link's tip node, in 3-D."""
    csv_path = os.path.join(work, "spatial.csv")
    run(kanegen, "simulate", model, "--t-end", "0.5", "-o", csv_path, "--quiet")
    header, rows = read_csv(csv_path)
    out = os.path.join(work, "spatial_html")
    run(kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--frames", "3", "--quiet")
    result = probe(os.path.join(out, "spatial_arm2.html"), times="page", scales=[1],
                   bodies=["payload"])
    if not result:
        return
    by_time = {row[0]: row for row in rows}
    reach = max(distance(point(header, row, "payload"), [0, 0, 0]) for row in rows)
    worst = 0.0
    for at in result["at"]:
        err = distance(at["bodies"]["payload"], point(header, by_time[at["t"]], "payload"))
        worst = max(worst, err)
        check(err < 1e-5 * reach, "spatial_arm2: t=%g: the payload off by %.3g" % (at["t"], err))
    check(len(result["at"]) == 3, "spatial_arm2: 3 frames read, got %d" % len(result["at"]))
    print("spatial_arm2: payload at most %.3g m off (tolerance %.3g m)" % (worst, 1e-5 * reach))


def check_free_body(kanegen, model, work):
    """A box on a free joint carrying an arm on a spherical one: both turned by quaternions."""
    csv_path = os.path.join(work, "free_body.csv")
    run(kanegen, "simulate", model, "--t-end", "0.5", "-o", csv_path, "--quiet", "--u0", "base_wx=3",
        "--u0", "base_wy=-2", "--u0", "wrist_wz=5")
    header, rows = read_csv(csv_path)
    out = os.path.join(work, "free_body_html")
    run(kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--frames", "3", "--quiet")
    result = probe(os.path.join(out, "free_body.html"), times="page", scales=[1],
                   bodies=["box", "arm"])
    if not result:
        return
    by_time = {row[0]: row for row in rows}
    reach = max(distance(point(header, row, "arm_origin"), [0, 0, 0]) for row in rows)
    worst = 0.0
    for at in result["at"]:
        for body in ("box", "arm"):
            err = distance(at["bodies"][body], point(header, by_time[at["t"]], body + "_origin"))
            worst = max(worst, err)
            check(err < 1e-5 * reach, "free_body: t=%g: %s off by %.3g" % (at["t"], body, err))
    check(len(result["at"]) == 3, "free_body: 3 frames read, got %d" % len(result["at"]))
    print("free_body: origins at most %.3g m off (tolerance %.3g m)" % (worst, 1e-5 * reach))


def check_visuals(kanegen, source, work):
    """URDF <visual> shapes as drawn (three.js world matrices, float32) against visuals_reference.py; the
    visuals' names and the mesh's file name, which try to end the page's script, stay text."""
    import visuals_reference as ref
    model = os.path.join(source, ref.MODEL)
    csv_path = os.path.join(work, "visuals.csv")
    with open(csv_path, "w") as f:
        f.write(ref.csv_text())
    out = os.path.join(work, "visuals_html")
    run(kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--quiet")
    page = os.path.join(out, "animate_visuals.html")
    with open(page, encoding="utf-8") as f:
        text = f.read().lower()
    check(text.count("</script") == 3 and "hand.stl" not in text,
          "the page ends 3 scripts, no visual name ends one, the mesh's file is not in it: %d" %
          text.count("</script"))
    result = probe(page, times="page", scales=[1], shapes=["arm", "hand"])
    if not result:
        return
    check(len(result["at"]) == 3, "visuals: 3 frames read, got %d" % len(result["at"]))
    tol = 1e-5 * 0.6  # the hand's sphere reaches 0.55 m from the origin
    worst = 0.0
    for at, (t, q1, q2) in zip(result["at"], ref.ROWS):
        check(at["t"] == t, "visuals: the page's frame at t=%r is the CSV's row t=%r" % (at["t"], t))
        arm = [(s["kind"], s["points"]) for s in at["shapes"]["arm"]]
        hand = [(s["kind"], s["points"]) for s in at["shapes"]["hand"]]
        worst = max(worst, ref.compare(arm, hand, q1, q2, tol, check))
    names = [s["name"] for s in result["at"][0]["shapes"]["arm"] + result["at"][0]["shapes"]["hand"]]
    check(names == ["</script><script>window.pwned=1</script>", "<!-- tube & 'x' \"", "ball", ""],
          "the visuals' names come back as text, byte for byte: %r" % names)
    check(result["names"]["scripts"] == 3 and not result["names"]["pwned"], "no script from a visual's name")
    print("visuals: shapes at most %.3g m off the hand-computed positions (tolerance %.3g m)" % (worst, tol))


def hostile_run(source, work):
    """hostile_names.urdf and a 3-row CSV of it whose extra columns try to end the page's script."""
    model = os.path.join(source, "tests/data/models/hostile_names.urdf")
    robot = ET.parse(model).getroot()
    joints = [j.get("name") for j in robot.iter("joint")]
    links = [l.get("name") for l in robot.iter("link")][1:]  # the first is the ground
    extra = ["</script><script>window.pwned=1</script>", "<!-- <script>", "</SCRIPT", "\u2028 & ' \" \\"]
    csv_path = os.path.join(work, "hostile.csv")
    with open(csv_path, "w", encoding="utf-8") as f:
        f.write(",".join(["t"] + joints + [j + "_dot" for j in joints] + extra) + "\n")
        for k in range(3):
            f.write(",".join(["%g" % (0.1 * k)] + ["%g" % (0.2 * k)] * (2 * len(joints) + len(extra))) + "\n")
    return model, csv_path, joints, links, extra


def check_hostile(kanegen, source, work):
    """Names that try to end the page's script or open a comment stay text."""
    model, csv_path, joints, links, extra = hostile_run(source, work)
    out = os.path.join(work, "hostile_html")
    run(kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--quiet")
    page = [os.path.join(out, p) for p in os.listdir(out)]
    check(len(page) == 1 and page[0].endswith(".html"), "one page: %s" % page)
    with open(page[0], encoding="utf-8") as f:
        text = f.read().lower()
    check(text.count("</script") == 3, "the page ends 3 scripts, and no name ends one: %d" % text.count("</script"))
    result = probe(page[0], times=[0.1], scales=[1], bodies=links)
    if not result:
        return
    names = result["names"]
    check(names["api"] == links, "body names come back byte for byte: %r" % names["api"])
    check(names["bodies"] == links, "the body list shows the names as text: %r" % names["bodies"])
    check(names["columns"] == joints + [j + "_dot" for j in joints] + extra,
          "the column names come back as text: %r" % names["columns"])
    check(names["scripts"] == 3 and not names["pwned"], "no script from a name: %r" % names)
    check(names["title"] == names["model"] + " - kanegen animate", "the title is the model's name: %r" % names)


def check_fps(kanegen, source, work):
    """models/flexible_arm10.json over 10 s: 10 flexible links (4 modes each), 200 frames.

    The fps depend on what is drawn, not on the values, and generating,
    compiling and running this model takes about a minute (53 s here), so
    the run is made up: every coordinate a smooth function of t, in the
    columns simulate writes. (A real run plays at the same rate: docs/animation.md.)"""
    model = os.path.join(source, "models/flexible_arm10.json")
    with open(model) as f:
        m = json.load(f)
    q = [j["name"] for j in m["joints"] if j["type"] != "fixed"]
    q += ["%s.mode%d" % (b["name"], k) for b in m["bodies"] if "flexible" in b
          for k in range(1, b["flexible"]["modes"] + 1)]
    csv_path = os.path.join(work, "arm10.csv")
    with open(csv_path, "w") as f:
        f.write(",".join(["t"] + q + [c + "_dot" for c in q]) + "\n")
        for r in range(1001):
            t = 0.01 * r
            values = [(0.5 if "." not in c else 2e-3) * math.sin(0.7 * t + i) for i, c in enumerate(q)]
            f.write(",".join("%.9g" % v for v in [t] + values + [0.0] * len(q)) + "\n")
    out = os.path.join(work, "arm10_html")
    run(kanegen, "animate", csv_path, model, "-o", out, "--format", "html", "--scale", "20", "--quiet")
    result = probe(os.path.join(out, "flexible_arm10.html"), play_seconds=3)
    if not result:
        return
    played = result["played"]
    print("flexible_arm10: %.1f frames/s over %.2f s of playback (%d frames), simulated time %.2f -> %.2f s" %
          (played["fps"], played["seconds"], played["frames"], played["t0"], played["t1"]))
    check(played["fps"] >= MIN_FPS, "flexible_arm10 plays at %.1f frames/s, under %d" % (played["fps"], MIN_FPS))
    check(abs((played["t1"] - played["t0"]) - played["seconds"]) < 0.2 * played["seconds"],
          "at speed 1 the page's time moves with the clock: %r" % played)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--kanegen", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)  # a stale page would pass for a new one
    os.makedirs(a.work)
    missing = browser_missing(a.kanegen, a.source, a.work)
    if missing:
        message = "the browser test needs " + ", ".join(missing) + " (scripts/install-deps.sh installs them)"
        if os.environ.get("KANEGEN_REQUIRE_BROWSER"):
            print("FAIL: " + message + "; KANEGEN_REQUIRE_BROWSER is set, so this is not skipped")
            return 1
        print("SKIP: " + message)
        return 77
    check_arm(a.kanegen, os.path.join(a.source, "tests/data/models/animate_arm.json"), a.work)
    check_spatial(a.kanegen, os.path.join(a.source, "models/spatial_arm2.json"), a.work)
    check_free_body(a.kanegen, os.path.join(a.source, "tests/consistency/data/free_body.json"), a.work)
    check_hostile(a.kanegen, a.source, a.work)
    check_visuals(a.kanegen, a.source, a.work)
    check_fps(a.kanegen, a.source, a.work)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
