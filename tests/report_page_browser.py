#!/usr/bin/env python3
"""kdop taa's report.html in a real browser: Debian's Chromium, headless, driven through the DevTools
protocol over a pipe (no port, no network). Makes a small run with kdop (one of kdop's scenes and a
sequence kdop scene wrote), opens the page with every non-file request blocked, and checks that:
every variant's rows are in the table after the scripts ran, and a click sorts it; every image
loads and nothing was fetched but files beside the page; the viewer follows its URL fragment,
steps, flips, overlays the FLIP map and jumps to worst frames with the keys a user presses; and a
screenshot is not blank (decoded here: PNG is zlib and five filters).

Usage: report_page_browser.py --kdop KDOP --chromium CHROMIUM [--screenshot FILE]
"""

import argparse
import base64
import json
import os
import struct
import select
import subprocess
import sys
import tempfile
import time
import urllib.parse
import zlib
from pathlib import Path

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED: " + message, file=sys.stderr)


class Browser:
    """Chromium with --remote-debugging-pipe: commands on fd 3, replies and events on fd 4, each a
    JSON message ended by a NUL byte."""

    def __init__(self, chromium, profile):
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()
        fds = {3: to_browser_r, 4: from_browser_w}

        def map_fds():
            for target, source in fds.items():
                os.dup2(source, target)
                os.set_inheritable(target, True)

        self.process = subprocess.Popen(
            [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run",
             "--remote-debugging-pipe", "--user-data-dir=" + str(profile), "--window-size=1400,1000",
             # Offline: no name resolves and every proxied request fails, besides the blocking below.
             "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
             "--disable-background-networking", "--disable-component-update", "--disable-sync", "about:blank"],
            preexec_fn=map_fds, pass_fds=(3, 4), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.next_id = 0
        self.buffer = b""
        self.events = []
        self.session = None

    def send(self, method, params=None, session=True):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            message["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        while True:
            reply = self.read()
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def read(self, timeout=60):
        """The next message; fails after `timeout` seconds without one, so that no wait hangs the test."""
        while b"\0" not in self.buffer:
            if not select.select([self.from_browser], [], [], timeout)[0]:
                raise RuntimeError(f"no message from the browser in {timeout} s")
            chunk = os.read(self.from_browser, 1 << 16)
            if not chunk:
                raise RuntimeError("the browser closed its pipe")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def wait_for_event(self, method, timeout=30):
        end = time.time() + timeout
        while time.time() < end:
            for i, event in enumerate(self.events):
                if event.get("method") == method:
                    return self.events.pop(i)
            self.events.append(self.read(max(end - time.time(), 0.01)))
        raise RuntimeError("no " + method)

    def evaluate(self, expression):
        result = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True})
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for_images(self):
        for _ in range(100):
            if self.evaluate("Array.from(document.images).every(i => i.complete)"):
                return
            time.sleep(0.05)

    def press(self, key, code, key_code):
        text = key if len(key) == 1 else ""
        for kind in ("keyDown", "keyUp"):
            params = {"type": kind, "key": key, "code": code, "windowsVirtualKeyCode": key_code}
            if kind == "keyDown" and text:
                params["text"] = text
            self.send("Input.dispatchKeyEvent", params)
        self.wait_for_images()

    def close(self):
        try:
            self.send("Browser.close", session=False)
        except RuntimeError:
            pass
        self.process.wait(timeout=30)


def png_pixels(data):
    """The RGB(A) rows of an 8-bit, non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and color in (2, 6) and interlace == 0, "an 8-bit RGB(A) PNG"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    channels = 3 if color == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, channels, rows


def state(browser):
    return dict(part.split("=", 1) for part in browser.evaluate("document.getElementById('viewer').dataset.state")
                .split("&"))


def shown_images(browser):
    """The images the viewer shows: the frames, and the FLIP maps where they are not hidden."""
    return browser.evaluate("Array.from(document.querySelectorAll('#views img'))"
                            ".filter(i => getComputedStyle(i).display !== 'none' && "
                            "getComputedStyle(i).visibility !== 'hidden').map(i => i.getAttribute('src'))")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--kdop", required=True)
    parser.add_argument("--chromium", required=True)
    parser.add_argument("--screenshot", help="also write the screenshot here")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="kdop-report-page-") as tmp:
        tmp = Path(tmp)
        scenes, out = tmp / "scenes", tmp / "taa"
        subprocess.run([args.kdop, "scene", "--scenes", "grass", "--size", "64x36", "--frames", "16", "--out",
                        str(scenes)], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        # The sequence under a name of its own: the scene's own frames are grass-ghosting.
        (scenes / "grass-ghosting").rename(scenes / "captured")
        subprocess.run([args.kdop, "taa", "--scenes", "grass", "--size", "64x36", "--warmup", "4", "--frames", "8",
                        "--sequence", str(scenes / "captured"), "--sets", "aabb", "dop22", "dop32", "--modes",
                        "clip", "--timing-rounds", "2", "--viewer-frames", "4", "--out", str(out)], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        variants = ["aabb-clip-n9", "dop22-clip-n9", "dop32-clip-n9"]
        page = (out / "report.html").resolve().as_uri()

        browser = Browser(args.chromium, tmp / "profile")
        try:
            target = browser.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
            browser.session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                           session=False)["sessionId"]
            browser.send("Page.enable")
            browser.send("Network.enable")
            browser.send("Network.setBlockedURLs", {"urls": ["http://*", "https://*", "ws://*", "wss://*", "ftp://*"]})
            # Without a fragment: the table sorted by ghosting, least first, within the 1400-pixel page, and
            # the viewer on the first ghosting sequence, its least ghosting variant as A against its most
            # as B, at B's worst frame.
            browser.send("Page.navigate", {"url": page})
            browser.wait_for_event("Page.loadEventFired")
            column = browser.evaluate("Array.from(document.querySelectorAll('#results th'))"
                                      ".findIndex(th => th.textContent.startsWith('ghosting (mean)'))")
            values = browser.evaluate(f"Array.from(document.querySelectorAll('#results tbody tr'))"
                                      f".map(r => Number(r.cells[{column}].dataset.value))")
            check(column > 0 and values == sorted(values), f"sorted by ghosting to begin with: {values}")
            widths = browser.evaluate("[document.documentElement.scrollWidth, "
                                      "document.querySelector('.table-wrap').scrollWidth, "
                                      "document.querySelector('.table-wrap').clientWidth]")
            check(widths[0] <= 1400 and widths[1] <= widths[2], f"the page and its table fit 1400 pixels: {widths}")
            data = json.loads(browser.evaluate("document.getElementById('kdop-data').textContent"))
            first = next(s for s in data["viewer"] if s["figure"] == "ghosting")
            measured = sorted((m, v) for v, m in enumerate(first["means"]) if m is not None)
            best, worst = data["variants"][measured[0][1]], data["variants"][measured[-1][1]]
            s = state(browser)
            check(s["a"] == best and s["b"] == worst and s["frame"] == str(first["worst"][measured[-1][1]]) and
                  urllib.parse.unquote(s["sequence"]) == (first["name"] if first["scene"] == first["name"] else
                                                          first["scene"] + "/" + first["name"]),
                  f"opens on {best} against {worst} at the latter's worst frame: {s}")
            check(browser.evaluate("document.getElementById('frame-note').textContent") == "", "no note")

            fragment = ("#sequence=captured&frame=9&a=aabb-clip-n9&b=dop32-clip-n9&mode=side&map=frame")
            # A page of its own in between: a fragment alone would navigate within the document, with no load.
            browser.send("Page.navigate", {"url": "about:blank"})
            browser.wait_for_event("Page.loadEventFired")
            browser.send("Page.navigate", {"url": page + fragment})
            browser.wait_for_event("Page.loadEventFired")
            browser.wait_for_images()

            # The table, after the scripts ran: every variant on the scene and on the sequence.
            rows = browser.evaluate("Array.from(document.querySelectorAll('#results tbody tr'))"
                                    ".map(r => [r.cells[0].textContent, r.cells[1].textContent])")
            for variant in variants:
                for scene in ("grass", "captured"):
                    check([variant, scene] in rows, f"the table has {variant} on {scene}: {rows}")
            # A click on "ghosting (mean)", which the table is sorted by to begin with, sorts by it
            # descending; then a click on "shimmer (mean)" sorts by that, ascending (empty cells last).
            for title, descending in (("ghosting (mean)", True), ("shimmer (mean)", False)):
                column = browser.evaluate("Array.from(document.querySelectorAll('#results th'))"
                                          f".findIndex(th => th.textContent === '{title}')")
                check(column > 0, f"a {title} column")
                browser.evaluate(f"document.querySelectorAll('#results th')[{column}].click()")
                values = browser.evaluate(f"Array.from(document.querySelectorAll('#results tbody tr'))"
                                          f".map(r => r.cells[{column}].dataset.value)")
                numbers = [float(v) for v in values if v != ""]
                check(numbers == sorted(numbers, reverse=descending) and values[len(numbers):] == [""] * (
                    len(values) - len(numbers)), f"sorted by {title}: {values}")

            # Every image loaded; nothing but files was asked for.
            check(browser.evaluate("document.body.dataset.brokenImages") == "0", "no image failed to load")
            check(browser.evaluate("Array.from(document.images).every(i => i.naturalWidth > 0)"), "every image shown")
            requests = [e["params"]["request"]["url"] for e in browser.events
                        if e.get("method") == "Network.requestWillBeSent"]
            check(requests and all(url.startswith("file:") or url.startswith("data:") for url in requests),
                  f"only files beside the page were read: {requests}")

            # The viewer follows the fragment: the sequence, the kept frame nearest 9, A and B side by side.
            data = json.loads(browser.evaluate("document.getElementById('kdop-data').textContent"))
            sequence = next(s for s in data["viewer"] if s["name"] == "captured" and s["scene"] == "captured")
            frames = sequence["frames"]
            nearest = min(frames, key=lambda f: (abs(f - 9), f))
            s = state(browser)
            check(s["frame"] == str(nearest) and s["mode"] == "side", f"the fragment's state: {s}")
            # A frame that was not kept is said to be another.
            note = browser.evaluate("document.getElementById('frame-note').textContent")
            check((nearest == 9) == (note == "") and (nearest == 9 or f"showing the nearest kept frame, {nearest}" in note),
                  f"frame 9 said to be {nearest}: {note!r}")
            base = f"viewer/captured/captured/{nearest:04}/"
            check(shown_images(browser) == [base + "aabb-clip-n9.png", base + "dop32-clip-n9.png"],
                  f"A and B side by side: {shown_images(browser)}")

            # F starts flipping, showing A; F again shows B.
            browser.press("f", "KeyF", 70)
            check(shown_images(browser) == [base + "aabb-clip-n9.png"], f"flip shows A: {shown_images(browser)}")
            browser.press("f", "KeyF", 70)
            check(shown_images(browser) == [base + "dop32-clip-n9.png"], f"then B: {shown_images(browser)}")
            # M puts the FLIP map over the frame, then instead of it.
            browser.press("m", "KeyM", 77)
            check(state(browser)["map"] == "overlay", "M: the map over the frame")
            check(shown_images(browser) == [base + "dop32-clip-n9.png", base + "flip/dop32-clip-n9.png"],
                  f"the map over B: {shown_images(browser)}")
            browser.press("m", "KeyM", 77)
            check(shown_images(browser) == [base + "flip/dop32-clip-n9.png"], f"the map alone: {shown_images(browser)}")
            # The arrow steps to the next kept frame.
            browser.press("ArrowRight", "ArrowRight", 39)
            following = frames[frames.index(nearest) + 1] if nearest != frames[-1] else nearest
            check(state(browser)["frame"] == str(following), f"→ steps to frame {following}: {state(browser)}")
            # W steps to a worst frame; a worst-frame button shows it with its variant as B.
            browser.press("w", "KeyW", 87)
            worst = [f for f in sequence["worst"] if f is not None]
            check(int(state(browser)["frame"]) in worst, f"W: a worst frame {worst}: {state(browser)}")
            browser.evaluate("document.querySelector('#worst button[data-variant=\"dop22-clip-n9\"]').click()")
            s = state(browser)
            check(s["frame"] == str(sequence["worst"][1]) and s["b"] == "dop22-clip-n9",
                  f"dop22's worst frame, dop22 as B: {s}")
            # The fragment follows the state, so a state can be linked to.
            check(browser.evaluate("location.hash").lstrip("#") ==
                  browser.evaluate("document.getElementById('viewer').dataset.state"), "the URL holds the state")

            # A screenshot of the viewer is not blank: many colors, the frames' among them.
            browser.evaluate("document.getElementById('viewer-section').scrollIntoView()")
            browser.wait_for_images()
            shot = base64.b64decode(browser.send("Page.captureScreenshot", {"format": "png"})["data"])
            if args.screenshot:
                Path(args.screenshot).write_bytes(shot)
            width, height, channels, pixels = png_pixels(shot)
            colors = set()
            for row in pixels[::4]:
                for x in range(0, width * channels, channels * 4):
                    colors.add(row[x:x + 3])
            check(width == 1400 and len(colors) > 200, f"a screenshot with many colors: {len(colors)}")
        finally:
            browser.close()

    if failures:
        print(f"{len(failures)} checks failed", file=sys.stderr)
        return 1
    print("report.html in Chromium: every check passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
