#!/usr/bin/python3
"""Drives the drawing page of `terraweave view RUN --serve 0 --exemplar ...` (docs/networks.md,
"Drawing") in headless Chromium through the DevTools protocol, with real pointer input: draw a
stroke, drag a region, complete, accept one suggestion by a click and others by a lasso, reject
the rest, complete again, accept all, undo that (Ctrl+Z) and accept all again, save; then reload
the page (the saved drawing is shown again), draw strokes starting 2 px from a line and from a
line's end (joined to them) and undo them (the button, Ctrl+Z). Writes what it saw as JSON
(--report) and a screenshot (--screenshot); stops the server and the browser whatever happens.

  network_page_drive.py TERRAWEAVE RUN_DIR WORK_DIR --exemplar SRC [--scale S] --report FILE
      [--screenshot PNG]
"""
import argparse
import base64
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

import websocket  # python3-websocket


def wait_for_line(stream, pattern, seconds, what):
    deadline = time.time() + seconds
    seen = []
    while time.time() < deadline:
        line = stream.readline()
        if not line:
            time.sleep(0.05)
            continue
        seen.append(line)
        match = re.search(pattern, line)
        if match:
            return match
    sys.exit(f"{what}: no line matching {pattern!r} in {seconds} s: {''.join(seen)[-2000:]}")


class Page:
    def __init__(self, ws_url):
        self.ws = websocket.create_connection(ws_url, timeout=30, suppress_origin=True)
        self.next_id = 0

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv())
            if message.get("id") == self.next_id:
                if "error" in message:
                    sys.exit(f"{method}: {message['error']}")
                return message.get("result", {})

    def eval(self, expression):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True,
                           awaitPromise=True)
        if "exceptionDetails" in result:
            sys.exit(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait(self, expression, seconds=20):
        deadline = time.time() + seconds
        while time.time() < deadline:
            if self.eval(expression):
                return
            time.sleep(0.05)
        status = self.eval("document.getElementById('status').textContent")
        sys.exit(f"timed out waiting for {expression}: status {status!r}")

    def mouse(self, kind, x, y, buttons):
        self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left",
                  buttons=buttons, clickCount=1 if kind != "mouseMoved" else 0)

    def drag(self, points):  # CSS pixels of the viewport
        self.mouse("mousePressed", *points[0], 1)
        for p in points[1:]:
            self.mouse("mouseMoved", *p, 1)
        self.mouse("mouseReleased", *points[-1], 0)

    def ctrl_z(self):
        for kind in ("keyDown", "keyUp"):
            self.call("Input.dispatchKeyEvent", type=kind, modifiers=2, key="z", code="KeyZ",
                      windowsVirtualKeyCode=90)

    def click(self, element_id):
        r = self.eval(f"(r => [r.x + r.width / 2, r.y + r.height / 2])"
                      f"(document.getElementById('{element_id}').getBoundingClientRect())")
        self.drag([r])


def reload_snap_and_undo(page, url, to_map):
    """Reloads the page (it shows the saved drawing), then draws a stroke starting 2 px from the
    middle of a segment of the first line and undoes it with the button, and one starting 2 px
    from that line's last point and undoes it with Ctrl+Z, then Ctrl+Z once more (nothing left
    to undo: the saved lines stay)."""
    page.eval("window.__old_page = true")
    page.call("Page.navigate", url=url)
    page.wait("!window.__old_page && document.readyState === 'complete' && !!window.__network"
              " && document.body.dataset.loaded !== undefined")
    state = "({lines: window.__network.lines, origins: window.__network.origins})"
    reloaded = page.eval(state)
    rect = page.eval("(r => [r.x, r.y])(document.getElementById('map').getBoundingClientRect())")
    t = page.eval("window.__network.transform")
    screen = lambda p: [rect[0] + (p[0] - t["origin"][0]) / t["pixel"][0],
                        rect[1] + (t["origin"][1] - p[1]) / t["pixel"][1]]
    lines = [[screen(p) for p in line] for line in reloaded["lines"]]

    def clearance(q):  # screen pixels from q to the nearest segment of any line
        best = math.inf
        for line in lines:
            for a, b in zip(line, line[1:]):
                dx, dy = b[0] - a[0], b[1] - a[1]
                f = max(0, min(1, ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) /
                               max(dx * dx + dy * dy, 1e-12)))
                best = min(best, math.hypot(a[0] + f * dx - q[0], a[1] + f * dy - q[1]))
        return best

    def vertex_clearance(q):
        return min(math.hypot(p[0] - q[0], p[1] - q[1]) for line in lines for p in line)

    # A point of the first line at least 12 px from every vertex, whose 2 px offset is at least
    # 6 px from every other line: a stroke from there is joined to that segment.
    first = lines[0]
    target = None
    for a, b in zip(first, first[1:]):
        length = math.hypot(b[0] - a[0], b[1] - a[1])
        normal = [-(b[1] - a[1]) / length, (b[0] - a[0]) / length]
        for f in [i / 20 for i in range(1, 20)]:
            q = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]
            for side in (1, -1):
                start = [q[0] + 2 * side * normal[0], q[1] + 2 * side * normal[1]]
                away = [q[0] + 40 * side * normal[0], q[1] + 40 * side * normal[1]]
                if vertex_clearance(q) > 12 and abs(clearance(start) - 2) < 0.01 and \
                        all(clearance([start[0] + (away[0] - start[0]) * g,
                                       start[1] + (away[1] - start[1]) * g]) > 7
                            for g in (0.25, 0.5, 0.75, 1.0)):
                    target = (start, away)
                    break
            if target:
                break
        if target:
            break
    if target is None:
        sys.exit("no segment of the first line with room for a stroke beside it")
    page.drag([target[0], [(target[0][0] + target[1][0]) / 2, (target[0][1] + target[1][1]) / 2],
               target[1]])
    on_segment = page.eval(state)
    page.click("undo")
    after_button = page.eval(state)

    # 2 px from the first line's last point, moving away from it along its last segment.
    a, b = first[-2], first[-1]
    length = math.hypot(b[0] - a[0], b[1] - a[1])
    ahead = [(b[0] - a[0]) / length, (b[1] - a[1]) / length]
    start = [b[0] + 2 * ahead[0], b[1] + 2 * ahead[1]]
    page.drag([start, [start[0] + 20 * ahead[0], start[1] + 20 * ahead[1] + 10],
               [start[0] + 40 * ahead[0], start[1] + 40 * ahead[1] + 25]])
    at_end = page.eval(state)
    page.ctrl_z()
    after_ctrl_z = page.eval(state)
    page.ctrl_z()
    nothing_left = page.eval(state)
    return {
        "reloaded": reloaded,
        "segment_stroke_dispatched": to_map(*target[0]),
        "on_segment": on_segment,
        "after_undo_button": after_button,
        "end_stroke_dispatched": to_map(*start),
        "at_end": at_end,
        "after_ctrl_z": after_ctrl_z,
        "after_nothing_to_undo": nothing_left,
        "undo_status": page.eval("document.getElementById('status').textContent"),
    }


def die_with_parent():
    """The server and the browser end when the driver does, however it ends (Linux)."""
    import ctypes
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


def main():
    # A SIGTERM (ctest's or timeout's) unwinds through the finally below.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("terminated"))
    parser = argparse.ArgumentParser()
    parser.add_argument("terraweave")
    parser.add_argument("run")
    parser.add_argument("work")
    parser.add_argument("--exemplar", required=True)
    parser.add_argument("--scale", default="1")
    parser.add_argument("--report", required=True)
    parser.add_argument("--screenshot")
    args = parser.parse_args()

    server = subprocess.Popen(
        [args.terraweave, "view", args.run, "--out", os.path.join(args.work, "page.html"),
         "--serve", "0", "--exemplar", args.exemplar, "--scale", args.scale, "--save",
         os.path.join(args.work, "drawn_network.gpkg")],
        cwd=args.work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        preexec_fn=die_with_parent)
    browser = None
    profile = tempfile.TemporaryDirectory()
    try:
        url = wait_for_line(server.stdout, r"serving (http://127\.0\.0\.1:\d+/\S+)", 60,
                            "terraweave view --serve").group(1)
        # The run's 3D page is served from the same folder.
        page_url = url.rsplit("/", 1)[0] + "/page.html"
        with urllib.request.urlopen(page_url) as answer:
            view_page = answer.status == 200 and b"terraweave view" in answer.read()
        browser = subprocess.Popen(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--remote-debugging-port=0", "--remote-allow-origins=*",
             f"--user-data-dir={profile.name}", "--window-size=1000,700", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
            preexec_fn=die_with_parent)
        devtools = wait_for_line(browser.stderr, r"DevTools listening on ws://([^/]+)/", 60,
                                 "chromium").group(1)
        targets = json.load(urllib.request.urlopen(f"http://{devtools}/json/list"))
        page = Page(next(t for t in targets if t["type"] == "page")["webSocketDebuggerUrl"])
        page.call("Page.enable")
        page.call("Page.navigate", url=url)
        page.wait("document.readyState === 'complete' && !!window.__network")

        rect = page.eval("(r => [r.x, r.y, r.width, r.height])"
                         "(document.getElementById('map').getBoundingClientRect())")
        t = page.eval("window.__network.transform")
        left, top, width, height = rect
        to_screen = lambda fx, fy: [left + fx * width, top + fy * height]
        to_map = lambda x, y: [t["origin"][0] + (x - left) * t["pixel"][0],
                               t["origin"][1] - (y - top) * t["pixel"][1]]

        # A stroke across the middle (mode draw is the default), then the region around it.
        stroke = [to_screen(0.3 + 0.04 * i, 0.5 + (0.02 if i % 2 else 0.0)) for i in range(6)]
        page.drag(stroke)
        page.click("region")
        page.drag([to_screen(0.15, 0.2), to_screen(0.5, 0.5), to_screen(0.85, 0.8)])
        page.click("complete")
        page.wait("+document.body.dataset.completed === 1")
        first = page.eval("window.__network.suggestions.length")
        first_status = page.eval("document.getElementById('status').textContent")
        if first < 3:
            sys.exit(f"first completion: {first} suggestions ({first_status})")

        # One by a click on the middle of the longest suggestion's first segment.
        page.click("pick")
        s = page.eval("window.__network.suggestions.reduce((a, b) => a.length >= b.length ? a : b)")
        mid = [(s[0][0] + s[1][0]) / 2, (s[0][1] + s[1][1]) / 2]
        page.drag([[left + (mid[0] - t["origin"][0]) / t["pixel"][0],
                    top + (t["origin"][1] - mid[1]) / t["pixel"][1]]])
        after_click = page.eval("window.__network.lines.length")
        # Those inside a lasso around the region's western half.
        page.click("lasso")
        page.drag([to_screen(0.1, 0.15), to_screen(0.5, 0.15), to_screen(0.5, 0.85),
                   to_screen(0.1, 0.85), to_screen(0.1, 0.16)])
        after_lasso = page.eval("window.__network.lines.length")
        left_over = page.eval("window.__network.suggestions.length")
        if args.screenshot:
            shot = page.call("Page.captureScreenshot", format="png")["data"]
            with open(args.screenshot, "wb") as f:
                f.write(base64.b64decode(shot))
        page.click("reject")
        rejected = page.eval("window.__network.suggestions.length")
        # Complete again over a region drawn as a loop (an octagon around the centre, crossing
        # accepted lines, which it cuts): the accepted lines go back as part of the drawing.
        # Accept all, save.
        page.click("area")
        page.drag([to_screen(0.5 + 0.3 * math.cos(a * math.pi / 4),
                             0.5 + 0.3 * math.sin(a * math.pi / 4)) for a in range(8)])
        region = page.eval("window.__network.region.length")
        # Turned to a bearing of 45°, typed in the box that choosing the lead `bearing` shows.
        bearing_hidden = page.eval(
            "getComputedStyle(document.getElementById('bearing')).display === 'none'")
        page.eval("(s => { s.value = 'bearing'; s.dispatchEvent(new Event('change')); })"
                  "(document.getElementById('lead'))")
        bearing_shown = page.eval(
            "getComputedStyle(document.getElementById('bearing')).display !== 'none'")
        page.eval("document.getElementById('bearing').value = '45'")
        # Every control of the bar within the window's width (the box shown too).
        bar_fits = page.eval("[...document.querySelectorAll('#bar button, #bar select, #bar input')]"
                             ".every(e => e.getBoundingClientRect().right <= innerWidth)")
        page.click("complete")
        page.wait("+document.body.dataset.completed === 2")
        second = page.eval("window.__network.suggestions.length")
        second_status = page.eval("document.getElementById('status').textContent")
        page.click("all")
        all_accepted = page.eval("window.__network.lines.length")
        page.ctrl_z()  # takes "accept all" back: its lines are suggestions again
        after_undo_accept = page.eval("[window.__network.lines.length,"
                                      " window.__network.suggestions.length]")
        page.click("all")
        page.click("save")
        page.wait("window.__network.saved !== null")
        state = page.eval("({lines: window.__network.lines, origins: window.__network.origins,"
                          " saved: window.__network.saved,"
                          " status: document.getElementById('status').textContent})")
        report = {
            "dispatched_map": [to_map(*p) for p in stroke],
            "pixel": t["pixel"],
            "first_suggestions": first,
            "after_click": after_click,
            "after_lasso": after_lasso,
            "left_after_lasso": left_over,
            "after_reject": rejected,
            "second_suggestions": second,
            "second_region_points": region,
            "first_status": first_status,
            "second_status": second_status,
            "bearing_box": [bearing_hidden, bearing_shown],
            "bar_fits": bar_fits,
            "server_pid": server.pid,
            "view_page": view_page,
            "all_accepted": all_accepted,
            "after_undo_accept": after_undo_accept,
            **state,
        }
        report.update(reload_snap_and_undo(page, url, to_map))
        with open(args.report, "w") as f:
            json.dump(report, f)
    finally:
        for process in (browser, server):
            if process is None:
                continue
            process.terminate()
            try:
                process.wait(10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        profile.cleanup()


if __name__ == "__main__":
    main()
