#!/usr/bin/python3
"""report.html's image viewer in a real browser (headless Debian chromium over the DevTools protocol,
tests/integration/cdp.py), opened from file:// as a user would: the A/B pane shows the right method's
frame pixel for pixel; the wheel zooms to 8x with nearest-neighbour blocks; F flips to the reference;
the inspector shows the PNG's values under the cursor; the scrubber, the arrow keys and a click on the
PSNR chart change the frame shown; the difference gain scales the difference; play advances frames.
Every expected pixel comes from the PNGs beside the report, decoded here.

Skipped (77) only when chromium is not installed. With --report DIR --shots DIR it runs the same steps
on an existing job and keeps screenshots of each step (for notes; not part of make check)."""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import shutil
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cdp

failures = 0


def check(cond, what):
    global failures
    print(("ok: " if cond else "FAIL: ") + what)
    sys.stdout.flush()
    if not cond:
        failures += 1
    return cond


def read_png(path):
    """8-bit RGB or RGBA PNG -> (width, height, rows of [r, g, b] lists)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), (path, depth, ctype)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 4 if ctype == 6 else 3
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([list(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


class Viewer:
    def __init__(self, browser, job):
        self.b, self.job = browser, job
        results = json.load(open(os.path.join(job, "results.json")))
        self.labels = [m["label"] for m in results["methods"]]
        self.frames = results["methods"][0]["frames"]
        self.pngs = {}

    def png(self, kind, label, ordinal):
        key = (kind, label, ordinal)
        if key not in self.pngs:
            d = "reference" if label is None else label.replace(":", "_").replace(",", "_").replace("=", "-")
            self.pngs[key] = read_png(os.path.join(self.job, kind, d, "%04d.png" % ordinal))[2]
        return self.pngs[key]

    def state(self):
        return self.b.eval("aalabViewer.state()")

    def rect(self, selector):
        return self.b.eval("(() => { const r = document.querySelector(%s).getBoundingClientRect();"
                           " return {x: r.left, y: r.top, w: r.width, h: r.height}; })()" % json.dumps(selector))

    def settle(self):
        """The viewer changes its state at once but draws on the next animation frame (redraw()), so a
        test that reads the page right after a state change could see the previous drawing: wait two
        animation frames first."""
        self.b.eval("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")

    def pane_pixels(self, pane):
        self.settle()
        return self.b.eval("(() => { const c = document.querySelector('[data-pane=\"%s\"]');"
                           " return [c.width, c.height, Array.from(c.getContext('2d').getImageData(0, 0, c.width,"
                           " c.height).data)]; })()" % pane)

    def pane_mismatches(self, pane, expected):
        """Canvas pixels of a pane that differ from the image `expected` (rows of RGB) placed at the
        viewer's zoom and origin; returns (mismatches, pixels of the image compared)."""
        s = self.state()
        w, h, data = self.pane_pixels(pane)
        z, ox, oy = s["zoom"], s["ox"], s["oy"]
        if pane != "ab:0":  # the small panes have their own size, hence their own origin
            ox, oy = math.floor(w / 2 - s["cx"] * z + 0.5), math.floor(h / 2 - s["cy"] * z + 0.5)  # as Math.round
        bad = seen = 0
        H, W = len(expected), len(expected[0])
        for y in range(h):
            iy = (y - oy) // z
            if not 0 <= iy < H:
                continue
            for x in range(w):
                ix = (x - ox) // z
                if not 0 <= ix < W:
                    continue
                seen += 1
                if data[(y * w + x) * 4:(y * w + x) * 4 + 3] != expected[iy][ix]:
                    bad += 1
        return bad, seen


def run_steps(v, shots=None, at=None):
    b = v.b
    last = len(v.labels) - 1

    def shot(name):
        if shots:
            r = v.rect("#viewer")
            b.screenshot(os.path.join(shots, name + ".png"), {"x": 0, "y": r["y"] + b.eval("scrollY"),
                                                              "width": 1400, "height": min(r["h"], 2400)})

    check(b.wait_for("window.aalabViewer && aalabViewer.ready && aalabViewer.state().shown === 0"),
          "the viewer loads frame 0 from file://")
    b.eval("document.getElementById('viewer').scrollIntoView()")  # input goes to what is on screen
    a_label = v.labels[last]
    bad, seen = v.pane_mismatches("ab:0", v.png("frames", a_label, 0))
    check(seen > 0 and bad == 0, "the A/B pane shows %s frame 0 exactly at 1x (%d of %d pixels differ)" % (a_label, bad, seen))
    shot("1-loaded")

    ab = v.rect('[data-pane="ab:0"]')
    # wheel up three times over a point on the image: 1x -> 2x -> 4x -> 8x about that point
    fx, fy = at or (0.55, 0.45)
    mx, my = ab["x"] + ab["w"] * fx, ab["y"] + ab["h"] * fy
    for _ in range(3):
        b.mouse("mouseWheel", mx, my, deltaX=0, deltaY=-120)
    b.wait_for("aalabViewer.state().zoom === 8", 5)
    s = v.state()
    check(s["zoom"] == 8, "three wheel steps zoom to 8x (zoom %s)" % s["zoom"])
    bad, seen = v.pane_mismatches("ab:0", v.png("frames", a_label, 0))
    check(seen > 0 and bad == 0, "at 8x every image pixel is an 8x8 block of its PNG value, nearest neighbour "
          "(%d of %d canvas pixels differ)" % (bad, seen))
    small = "img:0"
    bad, seen = v.pane_mismatches(small, v.png("frames", v.labels[0], 0))
    check(seen > 0 and bad == 0, "the small panes zoom with it (%s: %d of %d differ)" % (small, bad, seen))
    shot("2-zoom8")

    # drag: 16 CSS pixels left and 8 up at 8x move the view 2 image pixels right and 1 down, everywhere
    before = v.state()
    b.mouse("mouseMoved", mx, my)
    b.mouse("mousePressed", mx, my, button="left", clickCount=1)
    b.mouse("mouseMoved", mx - 16, my - 8, buttons=1)
    b.mouse("mouseReleased", mx - 16, my - 8, button="left", clickCount=1)
    b.mouse("mouseMoved", 2, 2)  # off the panes: no outline on the pixel under the cursor
    b.wait_for("!aalabViewer.state().hover", 5)
    s = v.state()
    check((s["cx"] - before["cx"], s["cy"] - before["cy"]) == (2, 1), "a drag pans by the dragged distance / zoom "
          "(centre moved %+g, %+g)" % (s["cx"] - before["cx"], s["cy"] - before["cy"]))
    bad, seen = v.pane_mismatches("ab:0", v.png("frames", a_label, 0))
    bad2, seen2 = v.pane_mismatches("img:0", v.png("frames", v.labels[0], 0))
    check(seen and seen2 and bad == bad2 == 0, "and every pane shows the panned view (%d, %d pixels differ)" % (bad, bad2))

    b.key("f", "KeyF", 70, "f")
    b.wait_for("aalabViewer.state().showB", 5)
    ref0 = v.png("frames", None, 0)
    bad, seen = v.pane_mismatches("ab:0", ref0)
    bad_a, _ = v.pane_mismatches("ab:0", v.png("frames", a_label, 0))
    check(bad == 0 and bad_a > 0, "F flips the A/B pane to the reference (%d pixels differ from it, %d from A)" % (bad, bad_a))
    v.settle()
    check(b.eval("document.querySelector('.vw-ab .vw-cap').dataset.showing") == "B", "the caption says B is shown")
    shot("3-flip-reference")

    # the inspector: the cursor over a known image pixel of the A/B pane
    s = v.state()
    ix, iy = int(s["cx"]) - 2, int(s["cy"]) + 1
    b.mouse("mouseMoved", ab["x"] + s["ox"] + ix * 8 + 4, ab["y"] + s["oy"] + iy * 8 + 4)
    b.wait_for("aalabViewer.state().px === %d && aalabViewer.state().py === %d" % (ix, iy), 5)
    v.settle()
    rows = b.eval("Array.from(document.querySelectorAll('.vw-inspector tr[data-source]')).map(r =>"
                  " [r.dataset.source, r.querySelector('.vw-srgb').textContent, r.querySelector('.vw-lin').textContent])")
    want = {"-1": ref0[iy][ix]}
    for i, label in enumerate(v.labels):
        want[str(i)] = v.png("frames", label, 0)[iy][ix]
    got = {r[0]: [int(c) for c in r[1].split()] for r in rows or []}
    check(got == want, "the inspector shows every pane's sRGB value at pixel (%d, %d): %s, want %s" % (ix, iy, got, want))

    def lin(c):
        c /= 255
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
    lin_ok = all(abs(float(t) - lin(c)) < 6e-5 for r in rows or [] for t, c in zip(r[2].split(), want[r[0]]))
    check(rows and lin_ok, "and its linear value (the sRGB decoding of it)")
    b.mouse("mouseMoved", 2, 2)  # off the panes: the inspected pixel's outline goes
    b.wait_for("!aalabViewer.state().hover", 5)

    # scrub: the slider as a user drags it, then the arrow keys
    b.eval("(() => { const s = document.querySelector('.vw-slider'); s.value = 2; s.dispatchEvent(new Event('input')); })()")
    check(b.wait_for("aalabViewer.state().shown === 2", 10), "the scrubber shows frame 2")
    bad, _ = v.pane_mismatches("ab:0", v.png("frames", None, 2))
    check(bad == 0, "the A/B pane shows the reference of frame 2 (%d pixels differ)" % bad)
    check("frame 2 " in b.eval("document.querySelector('.vw-frame').textContent"), "the frame label says frame 2")
    shot("4-scrub-frame2")
    b.key("ArrowLeft", "ArrowLeft", 37)
    check(b.wait_for("aalabViewer.state().shown === 1", 10), "the left arrow steps back to frame 1")

    # the PSNR chart: a click at frame 0's x position
    c = v.rect(".vw-chart")
    left = float(b.eval("document.querySelector('.vw-chart').dataset.left"))
    b.click(c["x"] + left * c["w"] / 420 + 1, c["y"] + c["h"] / 2)
    check(b.wait_for("aalabViewer.state().shown === 0", 10), "a click on the PSNR chart at frame 0 shows frame 0")
    bad, _ = v.pane_mismatches("ab:0", ref0)
    check(bad == 0, "and the A/B pane shows frame 0 again (%d pixels differ)" % bad)

    # the difference gain: |method - reference| x 16 per channel
    b.eval("(() => { const s = document.querySelector('.vw-gain'); s.value = '16'; s.dispatchEvent(new Event('change')); })()")
    b.wait_for("aalabViewer.state().gain === 16", 5)
    b.eval("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
    m0 = v.png("frames", v.labels[0], 0)
    expected = [[[min(255, abs(p - q) * 16) for p, q in zip(a, r)] for a, r in zip(ra, rr)] for ra, rr in zip(m0, ref0)]
    bad, seen = v.pane_mismatches("diff:0", expected)
    check(seen > 0 and bad == 0, "the difference pane is |%s - reference| x 16 (%d of %d differ)" % (v.labels[0], bad, seen))
    over = sum(1 for ra, rr in zip(m0, ref0) for a, r in zip(ra, rr) if any(abs(p - q) > 2.55 for p, q in zip(a, r)))
    shown_over = b.eval("document.querySelector('.vw-diff .vw-cap').dataset.over")
    check(shown_over == str(over), "its caption counts %s pixels over 0.01 as idiff would (%d)" % (shown_over, over))
    b.eval("(() => { const s = document.querySelector('.vw-threshold'); s.value = '0.05'; s.dispatchEvent(new Event('change')); })()")
    b.eval("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
    over = sum(1 for ra, rr in zip(m0, ref0) for a, r in zip(ra, rr) if any(abs(p - q) > 12.75 for p, q in zip(a, r)))
    shown_over = b.eval("document.querySelector('.vw-diff .vw-cap').dataset.over")
    check(shown_over == str(over), "and %s over 0.05 (%d)" % (shown_over, over))
    shot("5-gain16")

    # method against method: the difference of the first method against the second, then luminance only
    def select(cls, value):
        b.eval("(() => { const s = document.querySelector('.%s'); s.value = '%s'; s.dispatchEvent(new Event('change')); })()" % (cls, value))
        b.eval("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
    m1 = v.png("frames", v.labels[1], 0)
    select("vw-against", 1)
    expected = [[[min(255, abs(p - q) * 16) for p, q in zip(a, c)] for a, c in zip(ra, rc)] for ra, rc in zip(m0, m1)]
    bad, seen = v.pane_mismatches("diff:0", expected)
    check(seen > 0 and bad == 0, "against %s: the pane is |%s - %s| x 16 (%d of %d differ)" % (v.labels[1], v.labels[0], v.labels[1], bad, seen))
    select("vw-mode", "lum")

    def luma(c):
        return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    expected = [[[min(255, round(abs(luma(a) - luma(c)) * 16))] * 3 for a, c in zip(ra, rc)] for ra, rc in zip(m0, m1)]
    w, h, data = v.pane_pixels("diff:0")
    s = v.state()
    ox, oy = math.floor(w / 2 - s["cx"] * 8 + 0.5), math.floor(h / 2 - s["cy"] * 8 + 0.5)
    worst = max(abs(data[(y * w + x) * 4 + ch] - expected[(y - oy) // 8][(x - ox) // 8][ch])
                for y in range(h) for x in range(w) for ch in range(3)
                if 0 <= (y - oy) // 8 < len(m0) and 0 <= (x - ox) // 8 < len(m0[0]))
    check(worst <= 1, "luminance only: |Y(a) - Y(b)| x 16, Rec. 709 luma (largest deviation %d, rounding)" % worst)
    # A/B between two methods
    select("vw-a", 0)
    select("vw-b", 1)
    bad, _ = v.pane_mismatches("ab:0", m1 if v.state()["showB"] else m0)
    check(bad == 0, "A/B between %s and %s shows the chosen one (%d differ)" % (v.labels[0], v.labels[1], bad))

    # worst regions: the first is the tile with the most FLIP over every method and frame, drawn at 8x
    regions = b.eval("JSON.parse(document.getElementById('aa-viewer-data').textContent).regions")
    magma = b.eval("JSON.parse(document.getElementById('aa-viewer-data').textContent).magma")
    index = {}
    for i in range(256):
        index.setdefault(tuple(int(magma[6 * i + k:6 * i + k + 2], 16) for k in (0, 2, 4)), i)
    totals = {}
    for f in range(len(v.frames)):
        for label in v.labels:
            for y, row in enumerate(v.png("flip", label, f)):
                for x, c in enumerate(row):
                    totals[(x // 16, y // 16)] = totals.get((x // 16, y // 16), 0) + index.get(tuple(c), 0)
    top = max(totals, key=totals.get)
    check(regions and (regions[0]["x"], regions[0]["y"]) == (top[0] * 16, top[1] * 16),
          "the first worst region is the tile with the most FLIP error, %s (page: %s)" % (top, regions[:1]))
    if regions:
        g = regions[0]
        b.wait_for("document.querySelectorAll('.vw-region canvas').length > 0", 5)
        v.settle()
        crop = b.eval("(() => { const c = document.querySelector('.vw-region[data-region=\"0\"] canvas');"
                      " return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data); })()")
        refg = v.png("frames", None, g["ordinal"])
        bad = sum(1 for y in range(g["h"] * 8) for x in range(g["w"] * 8)
                  if crop[(y * g["w"] * 8 + x) * 4:(y * g["w"] * 8 + x) * 4 + 3] != refg[g["y"] + y // 8][g["x"] + x // 8])
        check(bad == 0, "its reference close-up is the frame-%d reference at 8x (%d pixels differ)" % (g["ordinal"], bad))
        shot("7-regions")
        b.eval("document.querySelector('.vw-region[data-region=\"0\"]').scrollIntoView()")
        r = v.rect('.vw-region[data-region="0"] .vw-cap')
        b.click(r["x"] + 5, r["y"] + r["h"] / 2)
        check(b.wait_for("aalabViewer.state().shown === %d && aalabViewer.state().zoom === 8 && aalabViewer.state().cx === %s"
                         % (g["ordinal"], g["x"] + g["w"] / 2), 10), "a click on it shows that frame and place at 8x")

    # play: space starts, frames advance, space stops
    b.key(" ", "Space", 32, " ")
    check(b.wait_for("aalabViewer.state().playing && aalabViewer.state().playedFrames >= 3", 15),
          "space plays: frames advance (%s played)" % v.state()["playedFrames"])
    shot("6-playing")
    b.key(" ", "Space", 32, " ")
    check(b.wait_for("!aalabViewer.state().playing", 5), "space pauses")


TOP = os.environ.get("top_builddir", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
JOB = ["--scene", "moving-sphere", "--methods", "none,ssaa:4", "--frames", "3", "--size", "96x54",
       "--reference-samples", "8", "--quiet"]


def make_job(tmp):
    job = os.path.join(tmp, "job")
    subprocess.run([os.path.join(TOP, "aalab"), "run"] + JOB + ["--out", job], check=True, stdout=subprocess.DEVNULL)
    return job


def through_daemon(browser):
    """The same job run by aalabd: its dashboard links the report, which shows the viewer over HTTP."""
    from daemon_lib import Daemon
    d = Daemon(http=True)
    try:
        out = subprocess.run([os.path.join(TOP, "aalab"), "submit", "--watch", "--connect", "unix:" + d.socket] + JOB,
                             check=True, stdout=subprocess.PIPE, text=True).stdout
        job_id = out.split()[0]
        base = "http://127.0.0.1:%d/" % d.http_port
        browser.navigate(base)
        link = "v1/jobs/%s/report.html" % job_id
        check(browser.wait_for("!!document.querySelector('a[href=\"%s\"]')" % link),
              "the dashboard links job %s's report" % job_id)
        browser.navigate(base + link)
        check(browser.wait_for("window.aalabViewer && aalabViewer.ready && aalabViewer.state().shown === 0"),
              "the report served by aalabd loads its viewer (viewer/0000.js over HTTP)")
        v = Viewer(browser, os.path.join(d.state, "jobs", job_id))
        bad, seen = v.pane_mismatches("ab:0", v.png("frames", v.labels[-1], 0))
        check(seen > 0 and bad == 0, "and its A/B pane shows %s frame 0 exactly (%d of %d differ)" % (v.labels[-1], bad, seen))
        got = os.path.join(d.tmp, "got")
        subprocess.run([os.path.join(TOP, "aalab"), "get", job_id, "--out", got, "--connect", "unix:" + d.socket],
                       check=True, stdout=subprocess.DEVNULL)
        mine = os.path.join(got, "viewer", "0002.js")
        same = os.path.exists(mine) and open(mine, "rb").read() == \
            open(os.path.join(d.state, "jobs", job_id, "viewer", "0002.js"), "rb").read()
        check(same, "aalab get downloads the viewer's frame scripts")
        check(d.stop() == 0, "aalabd exits 0")
        log = d.read_log()
        check("Sanitizer" not in log and "runtime error" not in log, "no sanitizer report in aalabd's log")
    finally:
        d.cleanup()


def page_checks(browser, job, tmp):
    """report.html at 1280 px: nothing wider than its card, the verdict in the first screen; and the worst
    regions drawn from the page's own data when the frame scripts cannot load (report.html alone)."""
    browser.send("Emulation.setDeviceMetricsOverride", session=True, width=1280, height=900, deviceScaleFactor=1,
                 mobile=False)
    browser.navigate("file://" + os.path.join(job, "report.html"))
    browser.wait_for("window.aalabViewer && aalabViewer.ready")
    wide = browser.eval("""(() => [...document.querySelectorAll('main table, main figure, main svg, main .card, main .cards')]
        .filter(e => e.getBoundingClientRect().right > e.parentElement.getBoundingClientRect().right + 0.5)
        .map(e => e.tagName + '.' + (e.getAttribute('class') || '')))()""")
    page = browser.eval("document.documentElement.scrollWidth")
    check(not wide and page <= 1280, "at 1280 px nothing overflows its card (page %d px): %s" % (page, wide[:4]))
    cut = browser.eval("""[...document.querySelectorAll('main svg text')].filter(t => {
        const s = t.closest('svg').getBoundingClientRect(), r = t.getBoundingClientRect();
        return r.width > 0 && (r.right > s.right + 1 || r.left < s.left - 1); }).map(t => t.textContent.slice(0, 40))""")
    check(not cut, "no chart text runs past its chart's edge (where it would be cut off): %s" % cut[:4])
    top = browser.eval("document.querySelector('.verdict').getBoundingClientRect().top")
    check(top < 900, "the verdict is in the first screen (top at %d px)" % top)
    bare = browser.eval("[...document.querySelectorAll('table.cost th')].filter(h => !(h.title || '').trim()).map(h => h.textContent)")
    check(not bare and browser.eval("document.querySelectorAll('table.cost th').length") > 0,
          "every column head of the cost table explains itself on hover: %s" % bare)
    uncaptioned = browser.eval("[...document.querySelectorAll('main figure')].filter(f => f.querySelector('svg.chart')).filter(f => !f.querySelector('figcaption')"
                               " || !f.querySelector('figcaption').textContent.trim()).map(f => f.previousElementSibling && "
                               "f.previousElementSibling.textContent)")
    check(not uncaptioned, "every figure says what it shows in a caption: %s" % uncaptioned)
    terms = browser.eval("[...document.querySelectorAll('dl.glossary dt')].map(d => d.textContent)")
    want = ["Reference", "Convergence PSNR", "PSNR", "SSIM", "FLIP", "Flicker", "GPU ms", "Front", "Worst regions"]
    check(all(w in terms for w in want) and browser.eval("!!document.querySelector('a[href=\"#glossary\"]')"),
          "the glossary, linked from the top, explains %s: %s" % (", ".join(want), terms))
    alone = os.path.join(tmp, "alone")
    os.makedirs(alone)
    shutil.copy(os.path.join(job, "report.html"), alone)
    browser.navigate("file://" + os.path.join(alone, "report.html"))
    browser.wait_for("document.querySelectorAll('.vw-region canvas').length > 0", 10)
    v = Viewer(browser, job)
    g = browser.eval("JSON.parse(document.getElementById('aa-viewer-data').textContent).regions[0]")
    ref = v.png("frames", None, g["ordinal"])
    drawn = browser.wait_for("""(() => { const c = document.querySelector('.vw-region[data-region="0"] canvas');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        const r = %s; for (let y = 0; y < c.height; y++) for (let x = 0; x < c.width; x++) {
          const i = (y * c.width + x) * 4, p = r[y >> 3][x >> 3];
          if (d[i] !== p[0] || d[i + 1] !== p[1] || d[i + 2] !== p[2]) return false; }
        return true; })()""" % json.dumps([row[g["x"]:g["x"] + g["w"]] for row in ref[g["y"]:g["y"] + g["h"]]]), 10)
    check(drawn, "without the viewer's frame scripts, the worst region's reference close-up is drawn from the page")


def main():
    if not cdp.find_chromium():
        print("SKIP: chromium is not installed (scripts/install-deps.sh installs it)")
        sys.exit(77)
    args = sys.argv[1:]
    job = args[args.index("--report") + 1] if "--report" in args else None
    shots = args[args.index("--shots") + 1] if "--shots" in args else None
    at = tuple(map(float, args[args.index("--at") + 1].split(","))) if "--at" in args else None
    tmp = tempfile.mkdtemp(prefix="aalab-viewer.")
    browser = None
    try:
        job = os.path.abspath(job or make_job(tmp))
        size = os.path.getsize(os.path.join(job, "report.html"))
        check(size < 2 << 20, "report.html is %d bytes (under 2 MB)" % size)
        browser = cdp.Chromium()
        browser.navigate("file://" + os.path.join(job, "report.html"))
        run_steps(Viewer(browser, job), shots, at)
        page_checks(browser, job, tmp)
        if "--report" not in args:
            through_daemon(browser)
        errors = [e for e in browser.events if e.get("method") == "Runtime.exceptionThrown"]
        check(not errors, "no script errors on the page %s" % (json.dumps(errors)[:800] if errors else ""))
    finally:
        if browser:
            browser.close()
        shutil.rmtree(tmp, ignore_errors=True)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
