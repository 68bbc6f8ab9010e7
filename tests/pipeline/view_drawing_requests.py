#!/usr/bin/python3
"""Asks the drawing server of `terraweave view RUN --serve 0 --exemplar ...` what the page would:
the drawing saved before (GET /drawing), completes one drawn stroke inside one region (POST
/complete), saves the stroke and the suggestions (POST /save), and prints {"drawing": {"status":
HTTP status, "body": answer}, "suggestions": [...], "saved": PATH} as JSON. The server's own
options follow the run folder; it is stopped whatever happens.

  view_drawing_requests.py TERRAWEAVE RUN_DIR WORK_DIR STROKE REGION [SERVER OPTION ...]

STROKE and REGION are JSON lists of [x, y] points in the run's CRS. With COMPLETE_METHOD set to
a comma-separated list of methods ("-": none named), it completes once per method as the page's
method choice asks, saves nothing and prints {"drawing": ..., "completions": {METHOD: {"status":
HTTP status, "body": answer}}}. With COMPLETE_LEADS set to a JSON list of leads (null: none), it
completes once per lead as the page's lead choice asks (the method named by COMPLETE_METHOD's
first entry, when set) and prints {"drawing": ..., "completions": [{"status", "body"} per lead]}.
"""
import ctypes
import json
import os
import re
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request


def post(url, body):
    request = urllib.request.Request(url, data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            return json.loads(answer.read())
    except urllib.error.HTTPError as error:
        sys.exit(f"{url}: {error.code} {error.read().decode()}")


def get(url, body=None):
    """GET url, or POST body as JSON when given: {"status": HTTP status, "body": answer}."""
    request = url if body is None else urllib.request.Request(
        url, data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            return {"status": answer.status, "body": json.loads(answer.read())}
    except urllib.error.HTTPError as error:
        return {"status": error.code, "body": json.loads(error.read())}


def main():
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("terminated"))
    terraweave, run, work, stroke, region, *options = sys.argv[1:]
    server = subprocess.Popen(
        [terraweave, "view", run, "--out", os.path.join(work, "page.html"), "--serve", "0",
         *options], cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        preexec_fn=lambda: ctypes.CDLL("libc.so.6").prctl(1, signal.SIGKILL))  # PR_SET_PDEATHSIG
    try:
        deadline, seen, match = time.time() + 60, "", None
        while not match and time.time() < deadline:
            line = server.stdout.readline()
            if not line and server.poll() is not None:
                break
            seen += line
            match = re.search(r"serving (http://127\.0\.0\.1:\d+)/", line)
        if not match:
            sys.exit(f"no 'serving' line from terraweave view: {seen[-2000:]}")
        base = match.group(1)
        drawing = get(base + "/drawing")
        drawn = json.loads(stroke)
        if "COMPLETE_LEADS" in os.environ:
            completions = []
            for lead in json.loads(os.environ["COMPLETE_LEADS"]):
                request = {"lines": [drawn], "region": json.loads(region), "lead": lead}
                if os.environ.get("COMPLETE_METHOD", "-") != "-":
                    request["method"] = os.environ["COMPLETE_METHOD"].split(",")[0]
                completions.append(get(base + "/complete", request))
            print(json.dumps({"drawing": drawing, "completions": completions}))
            return
        if "COMPLETE_METHOD" in os.environ:
            completions = {}
            for method in os.environ["COMPLETE_METHOD"].split(","):
                request = {"lines": [drawn], "region": json.loads(region)}
                if method != "-":
                    request["method"] = method
                completions[method] = get(base + "/complete", request)
            print(json.dumps({"drawing": drawing, "completions": completions}))
            return
        suggestions = post(base + "/complete",
                           {"lines": [drawn], "region": json.loads(region)})["suggestions"]
        saved = post(base + "/save", {"lines": [drawn] + suggestions,
                                      "origins": ["drawn"] + ["suggested"] * len(suggestions)})
        print(json.dumps({"drawing": drawing, "suggestions": suggestions,
                          "saved": saved["path"]}))
    finally:
        server.kill()
        server.wait()


if __name__ == "__main__":
    main()
