#!/usr/bin/python3
"""Where a page's frame time goes in headless Chromium: a trace of a few
seconds of its main loop, read per thread (docs/performance.org, "Where
the platformer's frame goes").

  tools/web-trace.py [--seconds S] [--gl] [--detail N] PAGES-FOLDER PAGE [ARG...]

The page (PAGES-FOLDER/PAGE/index.html, ARGs as its command line) is
loaded as tools/web-rate.py loads it; once its main loop has run 30
passes and two more seconds, S seconds (default 5) of it are traced
through DevTools' Tracing domain. Printed:
- the main loop's passes a second and the gaps between them;
- the page's own time per pass (the animation frame callback on the
  renderer's main thread), as median, 90th percentile and largest;
- each busy thread's share of the traced time (the renderer's main
  thread; the GPU process's thread, where SwiftShader draws the WebGL
  calls; the compositor);
WEB_TRACE_SAVE=FILE keeps the trace (for chrome://tracing or Perfetto).
With --detail N, the N event names taking most time on the two busiest
threads. With --gl (a separate load, because counting costs time): the WebGL
calls a pass makes, by name, and the canvas's size.
The tracing costs little and is the same for any two pages compared, so
compare pages or builds traced alike, in one run. DevTools' Runtime
domain stays off (tools/web-bench.py says why).
"""
import importlib.util, os, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("web_bench", os.path.join(HERE, "web-bench.py"))
web_bench = importlib.util.module_from_spec(spec)
spec.loader.exec_module(web_bench)

FRAMES = "(typeof Browser !== 'undefined' && Browser.mainLoop.currentFrameNumber) || 0"
CATEGORIES = ["toplevel", "devtools.timeline", "disabled-by-default-devtools.timeline.frame", "gpu"] + os.environ.get("WEB_TRACE_MORE", "").split(",")

# Counts each WebGL call by name, and the animation frames, in the page.
COUNT_GL = """
window.glCounts = {}; window.glFrames = 0;
(function () {
  function wrap(proto) {
    Object.getOwnPropertyNames(proto).forEach(function (name) {
      var d = Object.getOwnPropertyDescriptor(proto, name);
      if (!d || typeof d.value !== 'function' || name === 'constructor') return;
      var f = d.value;
      proto[name] = function () { glCounts[name] = (glCounts[name] || 0) + 1; return f.apply(this, arguments); };
    });
  }
  if (window.WebGLRenderingContext) wrap(WebGLRenderingContext.prototype);
  if (window.WebGL2RenderingContext) wrap(WebGL2RenderingContext.prototype);
  var raf = window.requestAnimationFrame;
  window.requestAnimationFrame = function (cb) {
    return raf.call(window, function (t) { glFrames++; cb(t); });
  };
})();
"""


def descendants(pid):
    """pid and the processes under it (Linux /proc)."""
    out = [pid]
    try:
        for tid in os.listdir("/proc/%d/task" % pid):
            with open("/proc/%d/task/%s/children" % (pid, tid)) as f:
                for child in f.read().split():
                    out.extend(descendants(int(child)))
    except OSError:
        pass
    return out


def cpu_times(root):
    """{(process kind, thread name): CPU seconds so far} of Chromium's
    processes: the kind from the --type= of a process's command line
    ("browser" without one), the thread's name from the kernel."""
    tick, out = os.sysconf("SC_CLK_TCK"), {}
    for pid in descendants(root):
        try:
            with open("/proc/%d/cmdline" % pid) as f:
                args = f.read().replace("\0", " ").split()
            kind = ([a[7:] for a in args if a.startswith("--type=")] or ["browser"])[0]
            for tid in os.listdir("/proc/%d/task" % pid):
                with open("/proc/%d/task/%s/stat" % (pid, tid)) as f:
                    stat = f.read()
                name = stat[stat.index("(") + 1:stat.rindex(")")]
                fields = stat[stat.rindex(")") + 2:].split()
                key = (kind, name.rstrip("0123456789") or name)
                out[key] = out.get(key, 0) + (int(fields[11]) + int(fields[12])) / float(tick)
        except (OSError, ValueError):
            pass
    return out


class Browser(web_bench.Browser):
    def trace(self, seconds):
        """The trace events of `seconds` seconds of the page; self.cpu:
        the CPU seconds each kind of thread used meanwhile."""
        self.call("Tracing.start", session=False, transferMode="ReportEvents",
                  traceConfig={"includedCategories": CATEGORIES, "recordMode": "recordContinuously"})
        before = cpu_times(self.proc.pid)
        time.sleep(seconds)
        after = cpu_times(self.proc.pid)
        self.cpu = {k: v - before.get(k, 0) for k, v in after.items()}
        self.events = []
        self.call("Tracing.end", session=False)
        events = []
        while True:
            for m in self.events:
                if m.get("method") == "Tracing.dataCollected":
                    events.extend(m["params"]["value"])
                elif m.get("method") == "Tracing.tracingComplete":
                    return events
            self.events = [self._read()]


def pct(xs, p):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(p * len(xs)))] if xs else 0


def report(events, page, detail=0):
    names, procs = {}, {}
    for e in events:
        if e.get("ph") == "M" and e.get("name") == "thread_name":
            names[(e["pid"], e["tid"])] = e["args"]["name"]
        if e.get("ph") == "M" and e.get("name") == "process_name":
            procs[e["pid"]] = e["args"]["name"]
    timed = [e for e in events if e.get("ph") == "X" and "dur" in e]
    t0 = min(e["ts"] for e in timed)
    t1 = max(e["ts"] + e["dur"] for e in timed)
    span = (t1 - t0) / 1e6
    # the page's passes: animation frame callbacks on the renderer's main thread
    rafs = sorted((e["ts"], e["dur"]) for e in timed if e["name"] == "FireAnimationFrame")
    gaps = [(b[0] - a[0]) / 1000.0 for a, b in zip(rafs, rafs[1:])]
    durs = [d / 1000.0 for _, d in rafs]
    print("%s: %d passes in %.2f s traced: %.1f a second" % (page, len(rafs), span, len(rafs) / span))
    if rafs:
        print("%s: gap between passes ms: median %.1f, 90%% %.1f, largest %.1f; over 20 ms: %d" %
              (page, pct(gaps, 0.5), pct(gaps, 0.9), max(gaps or [0]), sum(1 for g in gaps if g > 20)))
        print("%s: the page's time per pass ms: median %.2f, 90%% %.2f, largest %.2f; over 10 ms: %d" %
              (page, pct(durs, 0.5), pct(durs, 0.9), max(durs), sum(1 for d in durs if d > 10)))
    # each thread's busy time: its top-level tasks
    busy = {}
    for e in timed:
        if e.get("cat") == "toplevel" and e["name"] in ("ThreadControllerImpl::RunTask", "RunTask"):
            key = (e["pid"], e["tid"])
            busy[key] = busy.get(key, 0) + e["dur"]
    for key, us in sorted(busy.items(), key=lambda kv: -kv[1])[:6]:
        print("%s: busy %5.1f%% (%.2f ms a pass)  %s / %s" %
              (page, 100.0 * us / 1e6 / span, us / 1000.0 / max(1, len(rafs)),
               procs.get(key[0], "?"), names.get(key, "?")))
    if detail:
        # the events inside the two busiest threads, by their time in all
        # (nested events are counted in their parents' time too)
        for key, _ in sorted(busy.items(), key=lambda kv: -kv[1])[:2]:
            by = {}
            for e in timed:
                if (e["pid"], e["tid"]) == key:
                    n = by.setdefault(e["name"], [0, 0])
                    n[0] += e["dur"]
                    n[1] += 1
            for name, (us, count) in sorted(by.items(), key=lambda kv: -kv[1][0])[:detail]:
                print("%s:   %s: %.2f ms a pass, %.1f calls a pass  %s" %
                      (page, names.get(key, "?"), us / 1000.0 / max(1, len(rafs)),
                       count / float(max(1, len(rafs))), name))


def main():
    argv = sys.argv[1:]
    seconds, gl, detail = 5, False, 0
    while argv[:1] in (["--seconds"], ["--gl"], ["--detail"]):
        if argv[0] == "--seconds":
            seconds, argv = float(argv[1]), argv[2:]
        elif argv[0] == "--detail":
            detail, argv = int(argv[1]), argv[2:]
        else:
            gl, argv = True, argv[1:]
    folder, page, args = argv[0], argv[1], argv[2:]
    httpd, base = web_bench.web_test.serve(folder)
    browser = Browser(tempfile.mkdtemp(prefix="downstroke-web-trace-"))
    url = "%s/%s/index.html%s" % (base, page, "?" + "&".join(args) if args else "")
    try:
        browser.open(url)
        browser.wait(FRAMES + " >= 30", 60)
        time.sleep(2)
        events = browser.trace(seconds)
        if os.environ.get("WEB_TRACE_SAVE"):
            with open(os.environ["WEB_TRACE_SAVE"], "w") as f:
                web_bench.web_test.json.dump({"traceEvents": events}, f)
        report(events, page, detail)
        passes = sum(1 for e in events if e.get("name") == "FireAnimationFrame" and e.get("ph") == "X")
        cpu = browser.cpu
        print("%s: CPU time a pass (all threads, ms): %.2f in all; by process: %s" %
              (page, 1000.0 * sum(cpu.values()) / max(1, passes),
               ", ".join("%s %.2f" % (k, 1000.0 * v / max(1, passes)) for k, v in sorted(
                   [(kind, sum(v for (k2, _), v in cpu.items() if k2 == kind))
                    for kind in set(k for k, _ in cpu)], key=lambda kv: -kv[1]) if v > 0)))
        for (kind, name), v in sorted(cpu.items(), key=lambda kv: -kv[1])[:8]:
            if v > 0:
                print("%s:   %.2f ms a pass  %s / %s" % (page, 1000.0 * v / max(1, passes), kind, name))
        if gl:
            browser.call("Page.addScriptToEvaluateOnNewDocument", session=True, source=COUNT_GL)
            browser.open(url)
            browser.wait(FRAMES + " >= 30", 60)
            time.sleep(2)
            c0, f0 = browser.js("JSON.stringify(glCounts)"), browser.js("glFrames")
            time.sleep(seconds)
            c1, f1 = browser.js("JSON.stringify(glCounts)"), browser.js("glFrames")
            c0, c1 = web_bench.web_test.json.loads(c0), web_bench.web_test.json.loads(c1)
            n = max(1, f1 - f0)
            calls = {k: (v - c0.get(k, 0)) / float(n) for k, v in c1.items()}
            print("%s: WebGL calls a pass: %.1f in all (%d passes counted); canvas %s" %
                  (page, sum(calls.values()), n,
                   browser.js("canvas.width + 'x' + canvas.height")))
            for k, v in sorted(calls.items(), key=lambda kv: -kv[1]):
                if v >= 0.05:
                    print("%s:   %7.1f  %s" % (page, v, k))
    finally:
        browser.close()
        httpd.shutdown()


main()
