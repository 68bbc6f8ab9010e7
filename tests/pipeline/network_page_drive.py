#!/usr/bin/python3
"""Drives the drawing page of `terraweave view RUN --serve 0 --exemplar ...` (docs/networks.md,
"Drawing") in headless Chromium through the DevTools protocol, with real pointer input: draw a
stroke, drag a region, complete, accept one suggestion by a click and others by a lasso, reject
the rest, complete again, accept all, save. Writes what it saw as JSON (--report) and a
screenshot (--screenshot); stops the server and the browser whatever happens.

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

    def click(self, element_id):
        r = self.eval(f"(r => [r.x + r.width / 2, r.y + r.height / 2])"
                      f"(document.getElementById('{element_id}').getBoundingClientRect())")
        self.drag([r])


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
        error = page.eval("document.getElementById('status').textContent")
        if first < 3:
            sys.exit(f"first completion: {first} suggestions ({error})")

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
        page.click("complete")
        page.wait("+document.body.dataset.completed === 2")
        second = page.eval("window.__network.suggestions.length")
        second_status = page.eval("document.getElementById('status').textContent")
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
            "second_status": second_status,
            "server_pid": server.pid,
            "view_page": view_page,
            **state,
        }
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
