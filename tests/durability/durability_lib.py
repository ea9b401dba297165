"""Helpers of the durability tests: run a program under tests/durability/fault_shim.so (LD_PRELOAD) and
check the order of the calls it recorded. Standard library only.

An atomic write of DIR/NAME is correct when, in the recorded order:
  1. the data goes to a temporary file created by mkstemp in DIR (".NAME.XXXXXX"), never to DIR/NAME;
  2. that file is fsynced after its last write and before the rename;
  3. rename(temporary, DIR/NAME) replaces the file in one step;
  4. DIR itself is fsynced after the rename, before the next atomic write begins."""
import os
import re
import subprocess

TOP_SRC = os.environ.get("top_srcdir") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TOP_BUILD = os.environ.get("top_builddir") or TOP_SRC
SHIM = os.path.join(TOP_BUILD, "tests", "durability", "fault_shim.so")
TEMP = re.compile(r"^\.(?P<name>.+)\.[A-Za-z0-9]{6}$")


def preload_env(program, root, log=None, fault=None):
    """The environment that runs `program` under the shim, recording calls under root into log and
    injecting fault (AALAB_FAULT, see fault_shim.c). Sanitizer builds link the ASan runtime, which must
    come first among the preloaded libraries: it is put there, ahead of the shim."""
    env = dict(os.environ)
    libs = [SHIM]
    out = subprocess.run(["ldd", program], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    for line in out.splitlines():
        m = re.search(r"(\S*lib(asan|ubsan)\.so\S*) => (\S+)", line)
        if m and m.group(2) == "asan":
            libs.insert(0, m.group(3))
    env["LD_PRELOAD"] = " ".join(libs)
    env["AALAB_FAULT_ROOT"] = root
    env.pop("AALAB_FAULT_LOG", None)
    env.pop("AALAB_FAULT", None)
    if log:
        env["AALAB_FAULT_LOG"] = log
    if fault:
        env["AALAB_FAULT"] = fault
    return env


def read_log(path):
    """[(op, path, path2 or None)] in the order recorded."""
    calls = []
    if not os.path.exists(path):
        return calls
    with open(path) as f:
        for line in f:
            parts = line.rstrip("\n").split(" ")
            calls.append((parts[0], parts[1], parts[2] if len(parts) > 2 else None))
    return calls


def atomic_writes(calls):
    """Every rename in the log, as (index of the rename, temporary, final)."""
    return [(i, a, b) for i, (op, a, b) in enumerate(calls) if op == "rename"]


def check_atomic(calls, finals=("job.json", "scene.json", "results.json", "report.html")):
    """Problems with the atomic writes in calls (empty list: all correct), and how many were seen of each
    final name."""
    problems = []
    seen = {}
    renames = atomic_writes(calls)
    for k, (i, tmp, final) in enumerate(renames):
        name = os.path.basename(final)
        seen[name] = seen.get(name, 0) + 1
        m = TEMP.match(os.path.basename(tmp))
        if tmp == final or not m or m.group("name") != name or os.path.dirname(tmp) != os.path.dirname(final):
            problems.append("%s was not written through a temporary .%s.XXXXXX beside it (rename %s)" %
                            (final, name, tmp))
            continue
        created = [j for j in range(i) if calls[j][0] == "mkstemp" and calls[j][1] == tmp]
        if not created:
            problems.append("%s: its temporary %s was not made by mkstemp" % (final, tmp))
            continue
        start = created[-1]
        writes = [j for j in range(start, i) if calls[j][0] == "write" and calls[j][1] == tmp]
        syncs = [j for j in range(start, i) if calls[j][0] == "fsync" and calls[j][1] == tmp]
        if not syncs or (writes and syncs[-1] < writes[-1]):
            problems.append("%s: %s was renamed without an fsync after its last write" % (final, tmp))
        end = renames[k + 1][0] if k + 1 < len(renames) else len(calls)
        dir_syncs = [j for j in range(i + 1, end) if calls[j][0] == "fsync-dir" and
                     calls[j][1] == os.path.dirname(final)]
        if not dir_syncs:
            problems.append("%s: its directory was not fsynced after the rename" % final)
    for i, (op, a, _) in enumerate(calls):
        if op in ("write", "open-truncate", "open-write") and os.path.basename(a) in finals:
            problems.append("%s was written in place (%s), not replaced by a rename" % (a, op))
    return problems, seen


def leftovers(root):
    """Temporary files (".NAME.XXXXXX") under root."""
    return sorted(os.path.join(d, f) for d, _, fs in os.walk(root) for f in fs if TEMP.match(f))
