#!/usr/bin/python3
"""The browser builds in headless Chromium (make web-test).

  tools/web-test.py WEB-FOLDER NATIVE-FOLDER

WEB-FOLDER is build/web, holding the pages make web built (platformer,
shmup, save-game); NATIVE-FOLDER holds the native headless screenshots
of the same runs (make web-test makes them). For each demo the page runs
the demo's own command line, given in the address's query: a scripted
input (tests/web/NAME-input.scm) for a number of frames, in real time
through the browser's main loop, drawing with WebGL, and a screenshot of
its last frame; that PNG, read out of the page's file system, must match
the native one (same size, every channel of at most MAX_OFF of the pixels
off by more than MAX_DIFF: the simulation is exact, only the drawing of a
different renderer may differ). The platformer's page must have opened
its sound (a running Web Audio context), its title must make no WebGL
texture while it shows (the texts drawn every frame keep theirs), its
canvas must have no depth buffer, and a key sent to it (Escape, the quit
action) must end its run. Then the save page is loaded
twice in one browser profile: the second load must read what the first
saved.

Chromium is driven through its DevTools protocol over a pipe
(--remote-debugging-pipe); the pages are served from 127.0.0.1. Prints
one line per check and last "N passed, N failed". Python's standard
library only.
"""
import base64, functools, http.server, json, os, shutil, struct, subprocess
import sys, tempfile, threading, time, zlib

MAX_DIFF = 16          # a channel's difference still counted as equal
MAX_OFF = 0.005        # the share of pixels that may differ more
DEMOS = [("platformer", 240), ("shmup", 150)]

# ---------------------------------------------------------------- PNG


def png_pixels(data):
    """(width, height, rows of RGBA tuples) of an 8-bit RGB/RGBA PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, "unsupported PNG"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 4 if ctype == 6 else 3
    raw, stride = zlib.decompress(idat), w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def compare(a, b):
    """None when the two PNGs match, else what differs."""
    (wa, ha, ra), (wb, hb, rb) = png_pixels(a), png_pixels(b)
    if (wa, ha) != (wb, hb):
        return "sizes differ: %dx%d against %dx%d" % (wa, ha, wb, hb)
    off = sum(1 for y in range(ha) for x in range(wa)
              if max(abs(p - q) for p, q in zip(ra[y][x], rb[y][x])) > MAX_DIFF)
    if off > MAX_OFF * wa * ha:
        return "%d of %d pixels differ" % (off, wa * ha)
    return None

# ---------------------------------------------------------------- Chromium


class Browser:
    """Headless Chromium over --remote-debugging-pipe (fds 3 and 4)."""

    def __init__(self, profile):
        cmd_r, self.cmd_w = os.pipe()
        self.res_r, res_w = os.pipe()
        os.set_inheritable(cmd_r, True)
        os.set_inheritable(res_w, True)
        # the child sees them as fds 3 (commands) and 4 (answers)
        prep = "exec 3<&%d 4>&%d; exec \"$@\"" % (cmd_r, res_w)
        self.proc = subprocess.Popen(
            ["sh", "-c", prep, "sh", shutil.which("chromium") or "chromium",
             "--headless", "--no-sandbox", "--remote-debugging-pipe",
             "--user-data-dir=" + profile, "--no-first-run", "--mute-audio",
             "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
             "--autoplay-policy=no-user-gesture-required", "about:blank"],
            pass_fds=(cmd_r, res_w), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(cmd_r)
        os.close(res_w)
        self.buf, self.next_id, self.events = b"", 0, []
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        self.call("Runtime.enable", session=True)
        self.call("Page.enable", session=True)

    def _read(self):
        while b"\0" not in self.buf:
            chunk = os.read(self.res_r, 1 << 16)
            if not chunk:
                raise RuntimeError("chromium closed its pipe")
            self.buf += chunk
        msg, self.buf = self.buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method, session=False, **params):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params}
        if session:
            msg["sessionId"] = self.session
        os.write(self.cmd_w, json.dumps(msg).encode() + b"\0")
        while True:
            m = self._read()
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m.get("result", {})
            self.events.append(m)

    def console(self):
        """The console lines so far."""
        out = []
        for m in self.events:
            if m.get("method") == "Runtime.consoleAPICalled":
                out.append(" ".join(str(a.get("value", "")) for a in m["params"]["args"]))
        return out

    def js(self, expr):
        r = self.call("Runtime.evaluate", session=True, expression=expr, returnByValue=True)
        if "exceptionDetails" in r:
            return None
        return r["result"].get("value")

    def open(self, url):
        self.events = []
        self.call("Page.navigate", session=True, url=url)

    def wait(self, expr, seconds):
        end = time.time() + seconds
        while time.time() < end:
            v = self.js(expr)
            if v:
                return v
            time.sleep(0.25)
        return None

    def close(self):
        try:
            self.call("Browser.close")
        except Exception:
            pass
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()


# Counts the WebGL textures a page makes (window.texturesMade).
COUNT_TEXTURES = """
window.texturesMade = 0;
(function (make) {
  WebGLRenderingContext.prototype.createTexture = function () {
    window.texturesMade++; return make.apply(this, arguments); };
})(WebGLRenderingContext.prototype.createTexture);
"""


class Quiet(http.server.SimpleHTTPRequestHandler):
    extensions_map = dict(http.server.SimpleHTTPRequestHandler.extensions_map,
                          **{".wasm": "application/wasm", ".js": "text/javascript"})

    def log_message(self, *args):
        pass


def serve(folder):
    handler = functools.partial(Quiet, directory=folder)
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd, "http://127.0.0.1:%d" % httpd.server_address[1]


def main():
    web, native = sys.argv[1], sys.argv[2]
    httpd, base = serve(web)
    profile = tempfile.mkdtemp(prefix="downstroke-web-test-")
    passed = failed = 0

    def check(ok, what, detail=""):
        nonlocal passed, failed
        print(("ok   " if ok else "FAIL ") + what + ("" if ok else ": " + detail))
        sys.stdout.flush()
        if ok: passed += 1
        else: failed += 1

    browser = Browser(profile)
    try:
        for name, frames in DEMOS:
            query = "&".join(["--frames", str(frames), "--script", "/tests/web/%s-input.scm" % name,
                              "--screenshot", "/web-test-shot.png"])
            t0 = time.time()
            browser.open("%s/%s/index.html?%s" % (base, name, query))
            done = browser.wait("typeof FS !== 'undefined' && FS.analyzePath('/web-test-shot.png').exists",
                                60 + frames / 10)
            took = time.time() - t0
            if not done:
                check(False, "%s: the page ran %d frames and saved its screenshot" % (name, frames),
                      "no screenshot after %.0f s; console: %s" % (took, browser.console()[-5:]))
                continue
            check(True, "%s: the page ran %d frames and saved its screenshot (%.1f s)" % (name, frames, took))
            data = base64.b64decode(browser.js(
                "(function(){var d=FS.readFile('/web-test-shot.png'),s='';"
                "for(var i=0;i<d.length;i++)s+=String.fromCharCode(d[i]);return btoa(s);})()"))
            with open(os.path.join(native, "%s-web.png" % name), "wb") as f:
                f.write(data)
            with open(os.path.join(native, "%s.png" % name), "rb") as f:
                diff = compare(data, f.read())
            check(diff is None, "%s: frame %d matches the native headless run's" % (name, frames), diff or "")

        # a key sent to the page reaches the game: Escape (the quit action)
        # ends the platformer's run, and with it the browser's main loop
        browser.call("Page.addScriptToEvaluateOnNewDocument", session=True, source=COUNT_TEXTURES)
        browser.open("%s/platformer/index.html" % base)
        frames = "(typeof Browser !== 'undefined' && Browser.mainLoop.currentFrameNumber) || 0"
        # (its first frames make the level's and the texts' textures; the
        # counter exists in the new page only, not in the one before it,
        # and the loop's pass count may start again as the game starts)
        browser.wait("typeof window.texturesMade === 'number' && " + frames + " >= 10", 60)
        time.sleep(1)
        browser.wait(frames + " >= 30", 60)
        t0 = browser.js("window.texturesMade")
        n0 = browser.js(frames); time.sleep(1); n1 = browser.js(frames)
        # its title draws the same four texts every frame: their textures
        # are kept (shell/text.scm), so none is made while it shows; and
        # the canvas has no depth buffer (shell/sdl2.scm)
        t1 = browser.js("window.texturesMade")
        check(t1 == t0, "the platformer's title makes no texture per frame",
              "%s textures made in %s main loop passes" % (None if t0 is None else t1 - t0, n1 - n0))
        depth = browser.js("GL.currentContext.GLctx.getContextAttributes().depth")
        check(depth is False, "the page's WebGL canvas has no depth buffer", "depth: %s" % depth)
        # its sound: SDL's Web Audio context, opened by init-audio! (this
        # Chromium lets a page play without a click)
        audio = browser.js("Module.SDL2 && Module.SDL2.audioContext ? "
                           "Module.SDL2.audioContext.state + ' ' + Module.SDL2.audioContext.sampleRate : null")
        check(audio == "running 44100", "the platformer's page plays sound (Web Audio at 44100 Hz)",
              "audio context: %s" % audio)
        key = dict(key="Escape", code="Escape", windowsVirtualKeyCode=27, nativeVirtualKeyCode=27)
        browser.js("document.getElementById('canvas').focus()")
        browser.call("Input.dispatchKeyEvent", session=True, type="keyDown", **key)
        time.sleep(0.5)
        browser.call("Input.dispatchKeyEvent", session=True, type="keyUp", **key)
        time.sleep(1); n2 = browser.js(frames); time.sleep(1); n3 = browser.js(frames)
        check(n1 > n0 and n3 == n2, "the Escape key quits the platformer's run in the page",
              "main loop passes %s, %s before the key, %s, %s after" % (n0, n1, n2, n3))

        # the save page twice, in one profile
        seen = []
        for load in range(2):
            browser.open("%s/save-game/index.html" % base)
            end = time.time() + 60
            while time.time() < end:
                lines = [l for l in browser.console() if l.startswith("web-save: saved")]
                if lines:
                    break
                time.sleep(0.25)
                browser.js("1")            # gathers the events that came meanwhile
            starts = [l for l in browser.console() if l.startswith("web-save: starts before")]
            seen.append(starts[0].split(": ")[-1] if starts else None)
            time.sleep(1.5)                # IndexedDB's write is asynchronous
        check(seen[0] is not None and seen[1] is not None and int(seen[1]) == int(seen[0]) + 1,
              "a save written in one page load is read in the next", "starts seen: %s" % seen)
    finally:
        browser.close()
        httpd.shutdown()
        shutil.rmtree(profile, ignore_errors=True)
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(0 if failed == 0 else 1)


if __name__ == "__main__":
    main()
