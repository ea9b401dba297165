#!/usr/bin/python3
"""results.json and report.html of `aalab run` are written atomically (issue 20): the recorded calls show a
temporary file, fsync, rename and a directory fsync for each; and when a write, an fsync or a rename fails
(fault injection by tests/durability/fault_shim.so), aalab says so and exits non-zero, the previous
results stay byte for byte, and no temporary file is left."""
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from durability_lib import TOP_BUILD, check_atomic, leftovers, preload_env, read_log

AALAB = os.path.join(TOP_BUILD, "aalab")
failures = 0


def check(cond, what):
    global failures
    print(("ok: " if cond else "FAIL: ") + what)
    failures += 0 if cond else 1
    return cond


def run(out, frames, log=None, fault=None):
    env = preload_env(AALAB, out, log, fault)
    env["AALAB_CONNECT"] = "unix:/nonexistent/aalabd.sock"  # in-process, never a running daemon
    return subprocess.run([AALAB, "run", "--local", "--scene", "thin-wires", "--methods", "none", "--frames",
                           str(frames), "--size", "32x18", "--reference-samples", "2", "--out", out, "--quiet"],
                          env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


tmp = tempfile.mkdtemp(prefix="aalab-durability.")
try:
    out = os.path.join(tmp, "results-dir")
    os.makedirs(out)
    log = os.path.join(tmp, "calls.log")
    r = run(out, 1, log=log)
    check(r.returncode == 0, "aalab run under the shim succeeds (%s)" % r.stderr.strip()[-300:])
    calls = read_log(log)
    problems, seen = check_atomic(calls)
    check(seen.get("results.json") == 1 and seen.get("report.html") == 1,
          "results.json and report.html are each written once by a rename (%s)" % seen)
    for p in problems:
        check(False, p)
    check(not problems, "every atomic write: temporary, fsync, rename, directory fsync (%d calls)" % len(calls))
    with open(os.path.join(out, "results.json"), "rb") as f:
        before = {"results.json": f.read()}
    with open(os.path.join(out, "report.html"), "rb") as f:
        before["report.html"] = f.read()

    # A second run that fails at each step of each atomic write: the first run's files stay whole.
    faults = [("write:.results.json.*", "results.json", "cannot write"),
              ("fsync:.results.json.*", "results.json", "cannot sync"),
              ("rename:results.json", "results.json", "cannot rename"),
              ("write:.report.html.*", "report.html", "cannot write"),
              ("fsync:.report.html.*", "report.html", "cannot sync"),
              ("rename:report.html", "report.html", "cannot rename"),
              ("fsync:results-dir", "results.json", "cannot sync directory")]
    for fault, name, message in faults:
        r = run(out, 2, fault=fault)
        check(r.returncode != 0 and message in r.stderr,
              "%s: aalab run fails and says '%s' (exit %d: %s)" % (fault, message, r.returncode,
                                                                 r.stderr.strip()[-200:]))
        if not fault.startswith("fsync:results-dir"):
            with open(os.path.join(out, name), "rb") as f:
                check(f.read() == before[name], "%s: the previous %s is intact" % (fault, name))
        check(not leftovers(out), "%s: no temporary file left (%s)" % (fault, leftovers(out)))
finally:
    shutil.rmtree(tmp, ignore_errors=True)
sys.exit(1 if failures else 0)
