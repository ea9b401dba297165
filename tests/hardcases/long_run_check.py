"""Checks a long still run of the temporal methods (tests/hard_cases_long.sh, bench/hard-cases-long): every
frame was scored, no drift (the verdict, and the last tenth's PSNR within 0.5 dB of the second tenth's),
no stall into oscillation (the last quarter's frame-to-frame change not above the second quarter's by more
than 0.1/255). Prints one line per method; exits 1 on a failure."""
import json
import math
import sys

results = json.load(open(sys.argv[1]))
case = results["cases"][0]
frames = case["frames"] if isinstance(case.get("frames"), int) else len(case["reference"]["per_frame"])
failed = 0


def psnr(fs):
    mse = sum(f["mse"] for f in fs) / len(fs)
    return math.inf if mse == 0 else 10 * math.log10(255 * 255 / mse)


def mean(xs):
    return sum(xs) / len(xs)


verdicts = {it["method"]: it["verdicts"] for it in results["verdicts"]["items"]}
for m in case["methods"]:
    fs = m["frames"]
    n = len(fs)
    tenth, quarter = n // 10, n // 4
    early, late = psnr(fs[tenth:2 * tenth]), psnr(fs[n - tenth:])
    change_early = mean([f["change"] for f in fs[quarter:2 * quarter]])
    change_late = mean([f["change"] for f in fs[n - quarter:]])
    problems = []
    if n != frames:
        problems.append("%d of %d frames scored" % (n, frames))
    if verdicts[m["label"]]["drift"]["state"] != "pass":
        problems.append("drift verdict %s" % verdicts[m["label"]]["drift"])
    if not (math.isinf(early) and math.isinf(late)) and late < early - 0.5:
        problems.append("PSNR drifted from %.2f to %.2f dB" % (early, late))
    if change_late > change_early + 0.1:
        problems.append("frame-to-frame change grew from %.3f to %.3f" % (change_early, change_late))
    print("%-24s %6d frames  PSNR %.2f -> %.2f dB  change %.3f -> %.3f  %s" % (
        m["label"], n, early, late, change_early, change_late, "; ".join(problems) or "ok"))
    failed += bool(problems)
sys.exit(1 if failed else 0)
