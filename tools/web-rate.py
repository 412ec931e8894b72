#!/usr/bin/python3
"""How often headless Chromium runs a page's main loop: emscripten's
Browser.mainLoop.currentFrameNumber over ten seconds, three loads
(docs/performance.org, "In the browser"). The browser is driven as
tools/web-bench.py drives it (DevTools' Runtime domain off).

  tools/web-rate.py PAGES-FOLDER PAGE      (e.g. build/web platformer)
"""
import importlib.util, os, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("web_bench", os.path.join(HERE, "web-bench.py"))
web_bench = importlib.util.module_from_spec(spec)
spec.loader.exec_module(web_bench)

FRAMES = "(typeof Browser !== 'undefined' && Browser.mainLoop.currentFrameNumber) || 0"


def main():
    folder, page = sys.argv[1], sys.argv[2]
    httpd, base = web_bench.web_test.serve(folder)
    browser = web_bench.Browser(tempfile.mkdtemp(prefix="downstroke-web-rate-"))
    try:
        for load in range(3):
            browser.open("%s/%s/index.html" % (base, page))
            browser.wait(FRAMES + " >= 30", 60)
            time.sleep(2)           # past the first frames' loading
            n0, t0 = browser.js(FRAMES), time.time()
            time.sleep(10)
            n1, t1 = browser.js(FRAMES), time.time()
            print("%s, load %d: %.1f main loop passes a second" % (page, load + 1, (n1 - n0) / (t1 - t0)))
    finally:
        browser.close()
        httpd.shutdown()


main()
