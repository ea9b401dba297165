#!/usr/bin/python3
"""aalab run's results are durable: results.json and report.html are written atomically (a
temporary file, fsync, rename and a directory fsync each, in the recorded calls) into a temporary folder
beside --out, which is synced as a whole (syncfs: the frames too) and renamed into place when complete, and
its parent directory synced after that rename.
When a write, an fsync or a rename fails (fault injection by tests/durability/fault_shim.so), aalab says
so and exits non-zero, the previous results (replaced with --force) stay byte for byte, and no temporary
file or folder is left."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from durability_lib import TOP_BUILD, check_atomic, leftovers, preload_env, read_log

PARTIAL = re.compile(r"^\.results-dir\.aalab-partial\.[A-Za-z0-9]{6}$")

AALAB = os.path.join(TOP_BUILD, "aalab")
failures = 0


def check(cond, what):
    global failures
    print(("ok: " if cond else "FAIL: ") + what)
    failures += 0 if cond else 1
    return cond


def run(out, frames, log=None, fault=None, force=False):
    env = preload_env(AALAB, os.path.dirname(out), log, fault)
    env["AALAB_CONNECT"] = "unix:/nonexistent/aalabd.sock"  # in-process, never a running daemon
    return subprocess.run([AALAB, "run", "--local", "--scene", "thin-wires", "--methods", "none", "--frames",
                           str(frames), "--size", "32x18", "--reference-samples", "2", "--out", out, "--quiet"] +
                          (["--force"] if force else []),
                          env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


tmp = tempfile.mkdtemp(prefix="aalab-durability.")
try:
    out = os.path.join(tmp, "results-dir")
    os.makedirs(out)
    log = os.path.join(tmp, "calls.log")
    r = run(out, 1, log=log)
    check(r.returncode == 0, "aalab run under the shim succeeds (%s)" % r.stderr.strip()[-300:])
    calls = read_log(log)
    # the files' writes, apart from the folder's own renames (checked below)
    folder_renames = [c for c in calls if c[0] == "rename" and out in (c[1], c[2])]
    problems, seen = check_atomic([c for c in calls if c not in folder_renames])
    folder_renames = [c for c in folder_renames if c[2] == out]  # the empty --out is moved aside first
    check(seen.get("results.json") == 1 and seen.get("report.html") == 1,
          "results.json and report.html are each written once by a rename (%s)" % seen)
    for p in problems:
        check(False, p)
    check(not problems, "every atomic write: temporary, fsync, rename, directory fsync (%d calls)" % len(calls))
    check(len(folder_renames) == 1 and PARTIAL.match(os.path.basename(folder_renames[0][1])) is not None,
          "the results are written in a temporary folder beside --out, renamed into place (%s)" % folder_renames)
    if folder_renames:
        i = calls.index(folder_renames[0])
        files = [j for j, c in enumerate(calls) if c[0] == "rename" and c not in folder_renames]
        check(files and max(files) < i, "the folder is renamed after the files in it are complete")
        check(any(c[0] == "fsync-dir" and c[1] == tmp for c in calls[i + 1:]),
              "the folder holding --out is synced after the rename")
        check(any(c[0] == "syncfs" and c[1] == folder_renames[0][1] for c in calls[:i]),
              "the frames and every file in the folder are synced (syncfs) before it is renamed")
    with open(os.path.join(out, "results.json"), "rb") as f:
        before = {"results.json": f.read()}
    with open(os.path.join(out, "report.html"), "rb") as f:
        before["report.html"] = f.read()

    # A second run (--force) that fails at each step of each atomic write: the first run's files stay whole.
    faults = [("write:.results.json.*", "results.json", "cannot write"),
              ("fsync:.results.json.*", "results.json", "cannot sync"),
              ("rename:results.json", "results.json", "cannot rename"),
              ("write:.report.html.*", "report.html", "cannot write"),
              ("fsync:.report.html.*", "report.html", "cannot sync"),
              ("rename:report.html", "report.html", "cannot rename"),
              ("fsync:.results-dir.aalab-partial.*", "results.json", "cannot sync directory"),
              ("syncfs:.results-dir.aalab-partial.*", "results.json", "cannot sync the results"),
              ("rename:results-dir:1", "results.json", "cannot move"),  # the earlier result, moved aside
              ("rename:results-dir:2", "results.json", "cannot rename")]  # the new one, into place
    for fault, name, message in faults:
        r = run(out, 2, fault=fault, force=True)
        check(r.returncode != 0 and message in r.stderr,
              "%s: aalab run fails and says '%s' (exit %d: %s)" % (fault, message, r.returncode,
                                                                 r.stderr.strip()[-200:]))
        path = os.path.join(out, name)
        now = open(path, "rb").read() if os.path.exists(path) else None
        check(now == before[name], "%s: the previous %s is intact (%s)" % (fault, name,
                                                                        "same" if now == before[name] else "changed" if now else "gone"))
        check(not leftovers(out), "%s: no temporary file left (%s)" % (fault, leftovers(out)))
        beside = sorted(f for f in os.listdir(tmp) if f.startswith(".results-dir.") or ".aalab-old." in f)
        check(not beside, "%s: no temporary folder left beside --out (%s)" % (fault, beside))
    # the last step: the folder holding --out cannot be synced after the rename
    r = run(out, 2, fault="fsync:" + os.path.basename(tmp), force=True)
    check(r.returncode != 0 and "cannot sync directory" in r.stderr,
          "fsync of the folder holding --out fails: aalab run says so (exit %d: %s)" % (r.returncode,
                                                                                  r.stderr.strip()[-200:]))
finally:
    shutil.rmtree(tmp, ignore_errors=True)
sys.exit(1 if failures else 0)
