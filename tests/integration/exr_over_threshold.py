#!/usr/bin/python3
"""EXR frames and idiff's over-threshold count, as a user gets them in process and through aalabd:
`aalab run --exr --over-threshold X` writes exr/METHOD/NNNN.exr (linear floats: their sRGB encoding is
the PNG) and counts, per frame, the pixels where any channel is off by more than X; the counts equal what
OpenImageIO's idiff prints for the same two PNGs (an independent implementation). The same job through
aalabd stores and lists the EXRs, serves them to `aalab get`, and gives the same counts."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALAB, Daemon, check, finish, crashed, check_log_and_cleanup

THRESHOLD = 0.05
JOB = ["--scene", "hard-edges", "--size", "96x54", "--frames", "2", "--reference-samples", "8",
       "--methods", "none,fxaa", "--over-threshold", str(THRESHOLD), "--quiet"]
METHODS = ["none", "fxaa"]


def idiff_count(ref, test, threshold):
    """idiff's own count of pixels over the threshold (its exit status says pass/warn/fail: not an error)."""
    out = subprocess.run(["idiff", "-fail", str(threshold), "-warn", str(threshold), ref, test],
                         capture_output=True, text=True).stdout
    m = re.search(r"(\d+) pixels \([0-9.]+%\) over", out)
    return int(m.group(1)) if m else (0 if "PASS" in out else None)


def srgb8(v):
    v = min(max(v, 0.0), 1.0)
    s = 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
    return int(s * 255.0 + 0.5)


def check_result(out, what):
    results = json.load(open(os.path.join(out, "results.json")))
    for m in results["methods"]:
        label = m["label"]
        over = m["metrics"]["over_threshold"]
        check(over["threshold"] == THRESHOLD, "%s %s: threshold %g recorded" % (what, label, THRESHOLD))
        per_frame = over["per_frame"]
        check(per_frame == [f["over_threshold"] for f in m["frames"]],
              "%s %s: per-frame counts agree in both places" % (what, label))
        for k, count in enumerate(per_frame):
            ref = os.path.join(out, "frames", "reference", "%04d.png" % k)
            test = os.path.join(out, "frames", label, "%04d.png" % k)
            expected = idiff_count(ref, test, THRESHOLD)
            check(count == expected and count > 0,
                  "%s %s frame %d: %s pixels over %g, idiff says %s" % (what, label, k, count, THRESHOLD, expected))
        share = sum(per_frame) / len(per_frame) / (96 * 54)
        check(abs(over["mean_share"] - share) < 1e-12, "%s %s: mean share %.6f" % (what, label, share))
    for label in METHODS + ["reference"]:
        for k in range(2):
            exr = os.path.join(out, "exr", label, "%04d.exr" % k)
            info = subprocess.run(["oiiotool", "--info", exr], capture_output=True, text=True).stdout
            check(re.search(r"96 x +54, 4 channel, float", info) is not None,
                  "%s %s frame %d: a 96x54 float EXR" % (what, label, k))
    # the EXR is the frame before sRGB encoding: encoded, it is the PNG (to one level)
    dump = lambda path: subprocess.run(["oiiotool", "--dumpdata", path], capture_output=True, text=True).stdout
    pix = lambda text: [[float(x) for x in m.group(1).split()[:3]]
                        for m in re.finditer(r"Pixel \(\d+, \d+\): ([-0-9. e+]+)", text)]
    lin = pix(dump(os.path.join(out, "exr", "none", "0001.exr")))
    enc = pix(dump(os.path.join(out, "frames", "none", "0001.png")))
    worst = max((abs(srgb8(a[c]) - b[c]) for a, b in zip(lin, enc) for c in range(3)), default=99)
    check(len(lin) == 96 * 54 and len(enc) == len(lin) and worst <= 1,
          "%s: EXR encoded to sRGB is the PNG within %d level(s) over %d pixels" % (what, worst, len(lin)))


tmp = tempfile.mkdtemp(prefix="aalab-exr.")
d = None
try:
    local = os.path.join(tmp, "local")
    r = subprocess.run([AALAB, "run", "--local", "--exr", "--out", local] + JOB, capture_output=True, text=True)
    check(r.returncode == 0, "aalab run --local --exr: exit 0 (%s)" % r.stderr.strip()[-300:])
    check("px >5% off" in r.stdout, "the table has the column of pixels over the threshold, named by it")
    check_result(local, "in process")

    r = subprocess.run([AALAB, "run", "--exr", "--no-images", "--local", "--out", os.path.join(tmp, "x")] + JOB,
                       capture_output=True, text=True)
    check(r.returncode == 2 and "--no-images" in r.stderr, "--exr with --no-images: exit 2 naming it")
    for bad, field in ((["--over-threshold", "1.5"], "over_threshold"), (["--over-threshold", "x"], "over_threshold")):
        r = subprocess.run([AALAB, "run", "--local", "--out", os.path.join(tmp, "y")] + JOB + bad,
                           capture_output=True, text=True)
        check(r.returncode == 2 and field in r.stderr, "%s: exit 2 naming %s" % (" ".join(bad), field))

    d = Daemon()
    remote = os.path.join(tmp, "remote")
    r = subprocess.run([AALAB, "run", "--exr", "--connect", "unix:" + d.socket, "--out", remote] + JOB,
                       capture_output=True, text=True)
    check(r.returncode == 0, "aalab run --exr through aalabd: exit 0 (%s)" % r.stderr.strip()[-300:])
    check_result(remote, "through aalabd")
    c = d.connect()
    listing = c.request({"op": "get", "job": "000001"})
    files = listing.get("files", [])
    check("exr/fxaa/0001.exr" in files and "exr/reference/0000.exr" in files, "aalabd lists the EXRs")
    got = c.request({"op": "get", "job": "000001", "file": "exr/none/0000.exr"})
    check(got.get("payload_format") == "image/x-exr" and got.get("_payload", b"")[:4] == b"\x76\x2f\x31\x01",
          "aalabd serves an EXR as image/x-exr (magic 76 2f 31 01)")
    bad = c.request({"op": "get", "job": "000001", "file": "exr/none/0000.png"})
    check(not bad.get("ok") and "exr/NAME/NNNN.exr" in json.dumps(bad), "exr/ with another extension is refused")
    c.close()
except Exception as e:  # noqa: BLE001 - any failure of the test body is a failed check
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
