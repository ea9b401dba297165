#!/bin/sh
# The pictures of docs/hard-cases.md, from real runs: each hard case at 320x180 with its reference
# ("auto", cap 256) on the left and the case's worst method on the right (far-from-origin: the control's
# reference and the far scene's), labelled in the image ("reference, 256 samples" | "smaa, 17.8 dB"), the
# worst region (report.html's first, the 16-pixel tile with the most FLIP error) boxed in red and shown
# below each at 6x. The frame shown is the worst region's frame; for hdr-fireflies, the frame and tile
# with the most pixels the method saturates where the reference does not (its blobs). Composed as a small HTML page and
# photographed by headless Debian chromium (nothing downloaded).
# Run from the build directory:  sh scripts/make_hard_case_pictures.sh
set -e
src=$(cd "$(dirname "$0")/.." && pwd)
out="$src/docs/img/hard-cases"
aalab=${AALAB:-./aalab}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/aalab-pictures.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
render() { # scene method frames
	"$aalab" run --local --quiet --scene "$1" --size 320x180 --frames "${3:-1}" --methods "$2" \
		--reference-samples auto --out "$tmp/$1" >/dev/null
}
# picture OUT LEFT_RUN LEFT_SOURCE RIGHT_RUN RIGHT_SOURCE [saturated]: SOURCE is "reference" or a method's label
picture() {
	/usr/bin/python3 - "$tmp" "$@" <<'PY'
import html, json, os, re, struct, sys, zlib
tmp, out, lrun, lsrc, rrun, rsrc = sys.argv[1:7]
saturated = len(sys.argv) > 7 and sys.argv[7] == "saturated"


def read_png(path):
    """8-bit RGB(A) PNG -> (width, height, rows of (r, g, b))."""
    data, pos, idat = open(path, "rb").read(), 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, _, ctype = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 4 if ctype == 6 else 3
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a, b, c = (line[i - bpp] if i >= bpp else 0), prev[i], (prev[i - bpp] if i >= bpp else 0)
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                q = a + b - c
                pa, pb, pc = abs(q - a), abs(q - b), abs(q - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows

def data(run):
    page = open(os.path.join(run, "report.html")).read()
    return json.loads(re.search(r'id="aa-viewer-data">(.*?)</script>', page, re.S).group(1).replace("\\u003c", "<"))

def results(run):
    return json.load(open(os.path.join(run, "results.json")))

region = (data(rrun)["regions"] or data(lrun)["regions"] or [{"x": 152, "y": 82, "w": 16, "h": 16, "ordinal": 0}])[0]
if saturated:  # the 16-pixel tile and frame where the method saturates most pixels the reference does not
    best = (-1, 0, 0, 0)
    for k in range(len(results(rrun)["reference"]["per_frame"])):
        w, h, ref = read_png(os.path.join(lrun, "frames", "reference", "%04d.png" % k))
        _, _, mine = read_png(os.path.join(rrun, "frames", rsrc.replace(":", "_"), "%04d.png" % k))
        count = {}
        for y in range(h):
            for x in range(w):
                if min(mine[y][x]) >= 250 and max(ref[y][x]) < 200:
                    count[(x // 16, y // 16)] = count.get((x // 16, y // 16), 0) + 1
        for (tx, ty), n in count.items():
            best = max(best, (n, k, tx, ty))
    if best[0] > 0:
        region = {"x": best[2] * 16, "y": best[3] * 16, "w": 16, "h": 16, "ordinal": best[1]}
f = region["ordinal"]

def panel(run, source):
    r = results(run)
    if source == "reference":
        n = r["reference"]["per_frame"][f]["samples"]
        scene = r["scene"]["name"]
        where = {"far-from-origin-control": "at the origin: ", "far-from-origin": "far from the origin: "}.get(scene, "")
        text = "%sreference, %d samples" % (where, n)
        path = os.path.join(run, "frames", "reference", "%04d.png" % f)
    else:
        m = next(m for m in r["methods"] if m["label"] == source)
        p = m["frames"][f]["psnr"]
        text = "%s, %s" % (source, "identical" if m["frames"][f]["identical"] else "%.1f dB PSNR" % p)
        path = os.path.join(run, m["frames"][f]["image"]) if m["frames"][f].get("image") else \
            os.path.join(run, "frames", source.replace(":", "_"), "%04d.png" % f)
    return text, path

x, y, w, h, Z = region["x"], region["y"], region["w"], region["h"], 6
cols = ""
for run, source in ((lrun, lsrc), (rrun, rsrc)):
    text, path = panel(run, source)
    url = "file://" + os.path.abspath(path)
    cols += f"""<div class="col"><div class="cap">{html.escape(text)}</div>
<div class="img"><img src="{url}" width="320" height="180"><div class="box" style="left:{x}px;top:{y}px;width:{w}px;height:{h}px"></div></div>
<div class="zoom-cap">red box at {Z}x: frame {f}, pixels {x}-{x + w - 1} x {y}-{y + h - 1}</div>
<div class="zoom" style="width:{w * Z}px;height:{h * Z}px"><img src="{url}" style="width:{320 * Z}px;height:{180 * Z}px;left:{-x * Z}px;top:{-y * Z}px"></div></div>"""
page = f"""<!doctype html><meta charset="utf-8"><style>
body{{margin:0;background:#fff;font:600 13px system-ui,sans-serif;color:#0f172a}}
.row{{display:flex;gap:8px;padding:6px}} .cap{{height:20px;width:320px;white-space:nowrap;overflow:hidden;text-overflow:ellipsis}} .img{{position:relative;width:320px;height:180px}}
.box{{position:absolute;outline:2px solid #e11d48}} img{{image-rendering:pixelated;display:block}}
.zoom-cap{{font-weight:400;font-size:11px;color:#475569;margin:6px 0 2px}}
.zoom{{position:relative;overflow:hidden;outline:2px solid #e11d48}} .zoom img{{position:absolute;max-width:none}}
</style><div class="row">{cols}</div>"""
open(os.path.join(tmp, "page.html"), "w").write(page)
PY
	timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --disable-background-networking \
		--disable-component-update --disable-sync --no-first-run --user-data-dir="$tmp/profile" \
		--allow-file-access-from-files --window-size=660,330 --screenshot="$1" "file://$tmp/page.html" 2>/dev/null
}
for pair in specular-aliasing:smaa subpixel-specks:none moire:none depth-extremes:none; do
	scene=${pair%%:*}
	method=${pair#*:}
	render "$scene" "$method"
	picture "$out/$scene.png" "$tmp/$scene" reference "$tmp/$scene" "$method"
done
render hdr-fireflies asaa 8
picture "$out/hdr-fireflies.png" "$tmp/hdr-fireflies" reference "$tmp/hdr-fireflies" asaa saturated
render far-from-origin-control none
render far-from-origin none
picture "$out/far-from-origin.png" "$tmp/far-from-origin-control" reference "$tmp/far-from-origin" reference
ls -l "$out"
