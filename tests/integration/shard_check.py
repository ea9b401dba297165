"""Compares the merged results of a job's shards with an unsharded run of the job (docs/farm.md, "What
merging guarantees"): methods without history equal to the last digit (every per-frame metric, flicker
across shard borders, the summaries, the reference, which render ran where in the method order), methods
with history within a tolerance of PSNR and SSIM per frame. Timings are measured anew by every run and
compared by count only.

    shard_check.py WHOLE MERGED --exact none,fxaa --tolerant taa=0.05,0.002

prints one line per check (ok:/FAIL:) and exits 1 when one fails. Standard library only."""
import json
import os
import sys

FRAME_KEYS = ["frame", "psnr", "identical", "ssim", "mse", "rmsd", "snr", "max_abs", "flip", "fourier",
              "nonfinite", "flicker", "image", "diff", "flip_map"]
SUMMARY_KEYS = ["psnr", "mse", "rmsd", "snr", "ssim", "max_abs", "flip", "flicker", "fourier",
                "error_threshold_curve"]


def load(d):
    with open(os.path.join(d, "results.json")) as f:
        return json.load(f)


def by_label(doc):
    return {m["label"]: m for m in doc["methods"]}


def same_file(p, q):
    if not os.path.exists(p) or not os.path.exists(q):
        return False
    with open(p, "rb") as f, open(q, "rb") as g:
        return f.read() == g.read()


def compare(whole, merged, exact, tolerant, out=sys.stdout):
    """exact: labels; tolerant: {label: (psnr_db, ssim)}. Returns the number of failed checks."""
    a, b = load(whole), load(merged)
    fails = 0

    def check(cond, what):
        nonlocal fails
        print(("ok: " if cond else "FAIL: ") + what, file=out)
        fails += 0 if cond else 1

    check(a["job_hash"] == b["job_hash"], "the merged job hash is the unsharded run's (%s)" % a["job_hash"])
    check(a["job"] == b["job"] and a["frames"] == b["frames"], "the same job and frames")
    ra, rb = a["reference"], b["reference"]
    same_ref = [(f["frame"], f["convergence_mse"], f["convergence_psnr"]) for f in ra["per_frame"]] == \
        [(f["frame"], f["convergence_mse"], f["convergence_psnr"]) for f in rb["per_frame"]]
    check(same_ref and ra["convergence_psnr"] == rb["convergence_psnr"],
          "reference: every frame's convergence and the mean equal")
    ma, mb = by_label(a), by_label(b)
    for label in exact:
        x, y = ma[label], mb[label]
        diffs = ["frame %d %s: %r vs %r" % (fx["frame"], k, fx.get(k), fy.get(k))
                 for fx, fy in zip(x["frames"], y["frames"]) for k in FRAME_KEYS if fx.get(k) != fy.get(k)]
        check(len(x["frames"]) == len(y["frames"]) and not diffs,
              "%s: every per-frame metric equal over %d frames%s" % (label, len(x["frames"]),
                                                                    "" if not diffs else ": " + "; ".join(diffs[:4])))
        sdiff = [k for k in SUMMARY_KEYS if x["metrics"][k] != y["metrics"][k]]
        check(not sdiff, "%s: summaries equal (PSNR of the mean MSE %s, best/worst, flicker %s)%s" % (
            label, x["metrics"]["psnr"]["mean"], x["metrics"]["flicker"]["mean"],
            "" if not sdiff else ": differ in " + ", ".join(sdiff)))
        images = [f[k] for f in x["frames"] for k in ("image", "diff", "flip_map") if f.get(k)]
        images += [f["image"] for f in ra["per_frame"] if f.get("image")]
        differ = [p for p in images if not same_file(os.path.join(whole, p), os.path.join(merged, p))]
        check(not differ, "%s: %d images (frame, diff, FLIP map, reference) equal byte for byte%s" % (
            label, len(images), "" if not differ else ": not " + ", ".join(differ[:3])))
        order = lambda m: [(t["frame"], t["repeat"], t["position"], sorted(t["passes"])) for t in m["timed_renders"]]
        check(order(x) == order(y) and x["gpu_ms"]["n"] == y["gpu_ms"]["n"],
              "%s: the same %d timed renders in the same places of the method order" % (label, x["gpu_ms"]["n"]))
    for label, (db, ssim) in tolerant.items():
        x, y = ma[label], mb[label]
        worst_db = worst_ssim = 0.0
        equal = 0
        for fx, fy in zip(x["frames"], y["frames"]):
            px = 1e9 if fx["identical"] else fx["psnr"]
            py = 1e9 if fy["identical"] else fy["psnr"]
            worst_db = max(worst_db, abs(px - py))
            worst_ssim = max(worst_ssim, abs(fx["ssim"] - fy["ssim"]))
            equal += all(fx.get(k) == fy.get(k) for k in FRAME_KEYS)
        check(len(x["frames"]) == len(y["frames"]) and worst_db <= db and worst_ssim <= ssim,
              "%s: per frame within %.3g dB and %.3g SSIM of the unsharded run (worst %.4f dB, %.5f; %d of %d "
              "frames equal)" % (label, db, ssim, worst_db, worst_ssim, equal, len(x["frames"])))
    return fails


# times, and where this run found its references (the store, or rendered): of the run, not of its results
TIMES = {"gpu_ms", "cpu_ms", "p10", "p90", "min", "mean", "median", "n", "started_at", "wall_seconds",
         "timed_renders", "passes", "cache"}
# what is computed from the times: the verdict (its front and ties rest on them), and the warnings about them
FROM_TIMES = {"verdict"}
TIME_WARNINGS = {"timing-spread"}


def differences(x, y, path=""):
    """Every value of two results documents that differs, but times, the store's outcomes (outside
    metrics) and what is computed from the times, as "path: x vs y"."""
    if isinstance(x, dict) and isinstance(y, dict):
        out = []
        for k in sorted(set(x) | set(y)):
            if (k in TIMES and ".metrics" not in path) or k in FROM_TIMES:
                continue
            if k == "warnings" and isinstance(x.get(k), list) and isinstance(y.get(k), list):
                keep = lambda ws: [w for w in ws if not (isinstance(w, dict) and w.get("code") in TIME_WARNINGS)]
                out += differences(keep(x[k]), keep(y[k]), path + "." + k)
                continue
            if k not in x or k not in y:
                out.append("%s.%s: only in one" % (path, k))
            else:
                out += differences(x[k], y[k], path + "." + k)
        return out
    if isinstance(x, list) and isinstance(y, list):
        if len(x) != len(y):
            return ["%s: %d vs %d items" % (path, len(x), len(y))]
        return [d for i, (u, v) in enumerate(zip(x, y)) for d in differences(u, v, "%s[%d]" % (path, i))]
    return [] if x == y else ["%s: %r vs %r" % (path, x, y)]


def main(argv):
    if argv[:1] == ["--all"]:  # every value but times: a suite of methods without history
        diffs = differences(load(argv[1]), load(argv[2]))
        print(("FAIL: " if diffs else "ok: ") + "every value but times equal" + "".join("\n  " + d for d in diffs[:10]))
        return 1 if diffs else 0
    args = {"--exact": "", "--tolerant": ""}
    pos = []
    i = 0
    while i < len(argv):
        if argv[i] in args:
            args[argv[i]] = argv[i + 1]
            i += 2
        else:
            pos.append(argv[i])
            i += 1
    exact = [m for m in args["--exact"].split(",") if m]
    tolerant = {}
    for item in filter(None, args["--tolerant"].split(";")):
        label, limits = item.split("=", 1)
        db, ssim = limits.split(",")
        tolerant[label] = (float(db), float(ssim))
    return 1 if compare(pos[0], pos[1], exact, tolerant) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
