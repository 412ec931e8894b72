#!/usr/bin/python3
"""The benchmark scenes in headless Chromium and natively, in one run
(make web-bench; docs/performance.org, "In the browser").

  tools/web-bench.py [--rounds R] [--profile] [--until TEXT] PAGE-FOLDER[,PAGE-FOLDER...] NATIVE-PROGRAM ARGS...

PAGE-FOLDER holds bench/scenes.scm built for the browser (make web
GAME=bench/scenes.scm); its page runs ARGS as its command line (the
address's query), and its console output is printed, each line marked
"web:" (with the folder's name when several are given, to compare
builds). Then NATIVE-PROGRAM (build/bench-scenes, or - for none) runs the
same ARGS, its lines marked "native:". Rounds alternate (--rounds R,
default 1) so that a load on the machine falls on all alike. --profile
samples the page's CPU use (DevTools' profiler) and prints the functions
taking most of it (a build linked with --profiling-funcs names them).
A page's run ends at the first console line that starts with TEXT
(--until; default "wrote ", the bench's last line), or at an error. Any
game's page works the same way: with --until "profile: frames 540-599" a
game run with --frames 600 --profile (docs/guide.org) gives its frame
profile in the browser and natively (the page's working folder is its
root, so relative paths name the same files in both).
Chromium is driven as tools/web-test.py drives it.
"""
import importlib.util, os, subprocess, sys, tempfile, time, shutil

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("web_test", os.path.join(HERE, "web-test.py"))
web_test = importlib.util.module_from_spec(spec)
spec.loader.exec_module(web_test)


# The page's console lines, kept in the page (read by Browser.console).
KEEP_CONSOLE = """
window.benchLines = [];
(function (log, error) {
  console.log = function () { benchLines.push(Array.prototype.join.call(arguments, ' ')); log.apply(console, arguments); };
  console.error = function () { benchLines.push(Array.prototype.join.call(arguments, ' ')); error.apply(console, arguments); };
})(console.log, console.error);
"""


class Browser(web_test.Browser):
    """web-test's browser, reading long answers (a CPU profile) in linear
    time, and without DevTools' Runtime domain: with it enabled, V8 makes a
    message with a stack trace for every exception thrown, and each of
    CHICKEN's minor collections is one (docs/performance.org, "Where the
    browser's time goes"). The
    page's console lines are kept in the page instead, and read from there."""

    def __init__(self, profile):
        web_test.Browser.__init__(self, profile)
        if os.environ.get("WEB_BENCH_RUNTIME") != "1":
            self.call("Runtime.disable", session=True)
        self.call("Page.addScriptToEvaluateOnNewDocument", session=True, source=KEEP_CONSOLE)

    def console(self):
        return self.js("window.benchLines || []") or []

    def _read(self):
        while True:
            end = self.buf.find(b"\0")
            if end >= 0:
                msg, self.buf = self.buf[:end], self.buf[end + 1:]
                return web_test.json.loads(msg)
            chunks = [self.buf]
            while True:
                chunk = os.read(self.res_r, 1 << 20)
                if not chunk:
                    raise RuntimeError("chromium closed its pipe")
                chunks.append(chunk)
                if b"\0" in chunk:
                    break
            self.buf = b"".join(chunks)


def run_page(browser, base, args, timeout, label, until):
    browser.open("%s/index.html?%s" % (base, "&".join(args)))
    seen, end = 0, time.time() + timeout
    while time.time() < end:
        lines = browser.console()
        for line in lines[seen:]:
            print(label + line)
            sys.stdout.flush()
        seen = len(lines)
        if any(l.startswith(until) or "Error" in l or "Aborted" in l for l in lines):
            return True
        time.sleep(0.5)
    print(label + "no end after %d s" % timeout)
    return False


def print_profile(profile, top=45):
    """Self time per function from a DevTools CPU profile, largest first."""
    nodes = {n["id"]: n for n in profile["nodes"]}
    counts = {}
    for s in profile["samples"]:
        f = nodes[s]["callFrame"]
        name = f["functionName"] or "(%s)" % f["url"].split("/")[-1]
        counts[name] = counts.get(name, 0) + 1
    total = len(profile["samples"])
    for name, n in sorted(counts.items(), key=lambda kv: -kv[1])[:top]:
        print("profile: %5.1f%%  %s" % (100.0 * n / total, name))


def main():
    argv = sys.argv[1:]
    rounds, profile_page, until = 1, False, "wrote "
    while argv[:1] in (["--rounds"], ["--profile"], ["--until"]):
        if argv[0] == "--rounds":
            rounds, argv = int(argv[1]), argv[2:]
        elif argv[0] == "--until":
            until, argv = argv[1], argv[2:]
        else:
            profile_page, argv = True, argv[1:]
    pages, native, args = argv[0].split(","), argv[1], argv[2:]
    servers = [web_test.serve(page) for page in pages]
    profile = tempfile.mkdtemp(prefix="downstroke-web-bench-")
    browser = Browser(profile)
    try:
        for r in range(rounds):
            print("round %d" % (r + 1))
            for page, (httpd, base) in zip(pages, servers):
                label = "web:    " if len(pages) == 1 else "web %s: " % os.path.basename(page.rstrip("/"))
                if profile_page:
                    browser.call("Profiler.enable", session=True)
                    browser.call("Profiler.setSamplingInterval", session=True, interval=200)
                    browser.call("Profiler.start", session=True)
                run_page(browser, base, args + (["--csv", "/web-bench.csv"] if until == "wrote " else []),
                         1800, label, until)
                if profile_page:
                    print_profile(browser.call("Profiler.stop", session=True)["profile"])
            if native == "-":
                continue
            out = subprocess.run([native] + args + (["--csv", "/dev/null"] if until == "wrote " else []), stdout=subprocess.PIPE,
                                 env=dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy"),
                                 universal_newlines=True).stdout
            for line in out.splitlines():
                print("native: " + line)
            sys.stdout.flush()
    finally:
        browser.close()
        for httpd, base in servers:
            httpd.shutdown()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    main()
