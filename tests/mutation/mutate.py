#!/usr/bin/python3
"""Mutation testing of aalab: applies realistic one-line bugs ("mutants") from catalogue.ini one at a time
to a clean copy of the project, builds it and runs the tests that cover the mutated part. A mutant is
killed when one of those tests fails (or runs past its time limit); a mutant that survives is a bug the
test suite cannot see. Prints each result, the score and every survivor.

  mutate.py --list                      the catalogue, one line a mutant
  mutate.py --check-applies             every mutant applies exactly once to the tree (make check runs this)
  mutate.py --show ID                   the mutant as a diff
  nice -n 19 mutate.py [--only ID,...] [--part PART] [--full]   the campaign (about an hour; not in CI)

See tests/mutation/README.md. Standard library only."""
import argparse
import configparser
import difflib
import json
import os
import shutil
import signal
import subprocess
import sys
import tarfile
import io
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SRC = os.path.abspath(os.path.join(HERE, "..", ".."))
CATALOGUE = os.path.join(HERE, "catalogue.ini")
KEYS = {"part", "file", "find", "replace", "tests", "about"}


class Mutant:
    def __init__(self, ident, fields):
        self.id = ident
        self.part = fields.get("part", "")
        self.file = fields.get("file", "")
        self.find = fields.get("find", "")
        self.replace = fields.get("replace", "")
        self.tests = fields.get("tests", "").split()
        self.about = " ".join(fields.get("about", "").split())
        self.unknown = sorted(set(fields) - KEYS)

    def problems(self, srcdir):
        """What stops this mutant from applying to srcdir exactly once (empty: it applies)."""
        out = []
        if self.unknown:
            out.append("unknown keys: " + ", ".join(self.unknown))
        for key in ("part", "file", "find", "tests", "about"):
            if not getattr(self, key):
                out.append("missing '%s'" % key)
        if self.find == self.replace:
            out.append("the replacement equals the snippet")
        path = os.path.join(srcdir, self.file)
        if self.file and not os.path.isfile(path):
            out.append("%s does not exist" % self.file)
        elif self.file and self.find:
            with open(path, encoding="utf-8") as f:
                n = f.read().count(self.find)
            if n != 1:
                out.append("the snippet occurs %d times in %s (must be exactly once): %r" % (n, self.file, self.find))
        for t in self.tests:
            if t != "check" and not any(os.path.isfile(os.path.join(srcdir, t + ext)) for ext in ("", ".c")):
                out.append("test %s has no source (%s or %s.c)" % (t, t, t))
        return out

    def apply(self, text):
        assert text.count(self.find) == 1, self.id
        return text.replace(self.find, self.replace, 1)


def load_catalogue(path=CATALOGUE):
    """Sections [part:NAME] give a part's tests (cheapest first); every other section is a mutant, whose
    tests are its part's unless it names its own."""
    parser = configparser.ConfigParser(interpolation=None, delimiters=("=",), comment_prefixes=("#",),
                                       inline_comment_prefixes=None, empty_lines_in_values=False,
                                       strict=True)
    parser.optionxform = str
    with open(path, encoding="utf-8") as f:
        parser.read_file(f)
    parts = {s[5:]: dict(parser[s]) for s in parser.sections() if s.startswith("part:")}
    mutants = []
    for s in parser.sections():
        if s.startswith("part:"):
            continue
        fields = dict(parser[s])
        part = parts.get(fields.get("part", ""))
        if part is None:
            sys.exit("mutate.py: %s: part '%s' has no [part:%s] section" % (s, fields.get("part", ""),
                                                                         fields.get("part", "")))
        fields.setdefault("tests", part.get("tests", ""))
        mutants.append(Mutant(s, fields))
    return mutants


def select(mutants, only, part):
    if only:
        want = set(only.split(","))
        unknown = want - {m.id for m in mutants}
        if unknown:
            sys.exit("mutate.py: unknown mutant(s): " + ", ".join(sorted(unknown)))
        mutants = [m for m in mutants if m.id in want]
    if part:
        mutants = [m for m in mutants if m.part == part]
    return mutants


def check_applies(mutants, srcdir):
    bad = 0
    for m in mutants:
        for p in m.problems(srcdir):
            print("%s: %s" % (m.id, p))
            bad += 1
    parts = sorted({m.part for m in mutants})
    print("%d mutants in %d parts (%s); %s" % (len(mutants), len(parts), ", ".join(parts),
                                              "all apply exactly once" if not bad else "%d problems" % bad))
    return 1 if bad else 0


def show(m, srcdir):
    with open(os.path.join(srcdir, m.file), encoding="utf-8") as f:
        text = f.read()
    print("# %s (%s): %s\n# tests: %s" % (m.id, m.part, m.about, " ".join(m.tests)))
    sys.stdout.writelines(difflib.unified_diff(text.splitlines(True), m.apply(text).splitlines(True),
                                               "a/" + m.file, "b/" + m.file, n=2))


# ---------------------------------------------------------------- the campaign

def log(msg, fh=None):
    line = time.strftime("%H:%M:%S ") + msg
    print(line, flush=True)
    if fh:
        fh.write(line + "\n")
        fh.flush()


def run(cmd, cwd, timeout=None, out=None):
    """Runs cmd in its own process group; returns (status, seconds). On timeout the group is killed and
    the status is None; so is it when the campaign itself is stopped (SIGTERM, SIGINT)."""
    t0 = time.time()
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=out or subprocess.DEVNULL, stderr=subprocess.STDOUT,
                            start_new_session=True)
    try:
        status = proc.wait(timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        status = None
    except BaseException:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        raise
    return status, time.time() - t0


def stop_on_sigterm():
    """SIGTERM stops the campaign like Ctrl-C: the running build or test is killed and the mutated file
    restored before exiting."""
    def handler(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, handler)


def restore_pending(workdir):
    """A campaign killed without the chance to restore (SIGKILL) left a note of the mutated file: put the
    original back before the copy is used again."""
    note = os.path.join(workdir, "pending.json")
    if os.path.exists(note):
        with open(note) as f:
            pending = json.load(f)
        with open(pending["path"], "w", encoding="utf-8") as f:
            f.write(pending["original"])
        os.remove(note)
        print("restored %s, left mutated by an interrupted campaign" % pending["path"])


def copy_tree(srcdir, dest, source):
    """A clean copy of the project: the committed tree (git archive HEAD) or, with source 'working',
    the tracked and untracked-but-not-ignored files as they are now."""
    os.makedirs(dest)
    if source == "head":
        data = subprocess.run(["git", "-C", srcdir, "archive", "--format=tar", "HEAD"], check=True,
                              stdout=subprocess.PIPE).stdout
        with tarfile.open(fileobj=io.BytesIO(data)) as tar:
            tar.extractall(dest)
        return
    files = subprocess.run(["git", "-C", srcdir, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                           check=True, stdout=subprocess.PIPE).stdout.decode().split("\0")
    for f in filter(None, files):
        src = os.path.join(srcdir, f)
        if os.path.isfile(src):
            os.makedirs(os.path.dirname(os.path.join(dest, f)), exist_ok=True)
            shutil.copy2(src, os.path.join(dest, f))


def tree_id(srcdir, source):
    head = subprocess.run(["git", "-C", srcdir, "rev-parse", "HEAD"], check=True, stdout=subprocess.PIPE,
                          text=True).stdout.strip()
    if source == "head":
        return head
    diff = subprocess.run(["git", "-C", srcdir, "diff", "HEAD"], stdout=subprocess.PIPE).stdout
    import hashlib
    return head + "+" + hashlib.sha1(diff).hexdigest()


def prepare(args, fh):
    """Returns the build directory: a copy of the project, configured and built, reused when it was made
    from the same tree with the same flags."""
    src = os.path.join(args.workdir, "src")
    stamp = os.path.join(args.workdir, "stamp")
    restore_pending(args.workdir)
    want = "%s %s" % (tree_id(args.srcdir, args.source), args.configure_flags)
    if os.path.isfile(stamp) and open(stamp).read() == want:
        log("reusing the build in %s" % src, fh)
        return src
    shutil.rmtree(src, ignore_errors=True)
    if os.path.exists(stamp):
        os.remove(stamp)
    log("copying the project (%s) to %s" % (args.source, src), fh)
    copy_tree(args.srcdir, src, args.source)
    with open(os.path.join(args.workdir, "build.log"), "w") as out:
        for cmd in (["autoreconf", "-fi"], ["./configure"] + args.configure_flags.split(),
                    ["make", "-j%d" % args.jobs], ["make", "-j%d" % args.jobs, "check", "TESTS="]):
            log("  " + " ".join(cmd), fh)
            status, _ = run(cmd, src, out=out)
            if status != 0:
                sys.exit("mutate.py: '%s' failed; see %s/build.log" % (" ".join(cmd), args.workdir))
    with open(stamp, "w") as f:
        f.write(want)
    return src


# Check programs that script tests run (a script's log does not depend on them, so make would not rebuild
# them for a mutant of the code they link).
SCRIPT_HELPERS = ["tests/tools/metrics_tool"]


def build(src, jobs, logfile, tests):
    """Rebuilds the programs and libraries, the helpers script tests run and the mutant's C tests only
    (not every check program: relinking them all costs more than most tests)."""
    targets = ["all"] + SCRIPT_HELPERS + [t for t in tests if os.path.isfile(os.path.join(src, t + ".c"))]
    if "check" in tests:
        targets = ["check", "TESTS="]
    with open(logfile, "w") as out:
        status, secs = run(["make", "-j%d" % jobs] + targets, src, out=out)
    return status == 0, secs


def run_test(src, test, jobs, timeout, logfile):
    """One test through the project's harness (its environment, validation on). Returns
    ('pass'|'fail'|'timeout', seconds). check_PROGRAMS is emptied for a single test: its own program is
    rebuilt through its log's dependency, the others are not needed."""
    tests = "" if test == "check" else "TESTS=" + test
    cmd = ["make", "-j%d" % jobs, "check"] + ([tests, "check_PROGRAMS="] if tests else [])
    with open(logfile, "w") as out:
        status, secs = run(cmd, src, timeout=timeout, out=out)
    return ("timeout" if status is None else "pass" if status == 0 else "fail"), secs


def campaign(args, mutants):
    os.makedirs(args.workdir, exist_ok=True)
    fh = open(os.path.join(args.workdir, "report.txt"), "w")
    t_start = time.time()
    src = prepare(args, fh)
    logs = os.path.join(args.workdir, "logs")
    shutil.rmtree(logs, ignore_errors=True)
    os.makedirs(logs)
    if args.full:
        for m in mutants:
            m.tests = ["check"]
    missing = [p for m in mutants for p in m.problems(src)]
    if missing:
        for p in missing:
            log("does not apply: " + p, fh)
        sys.exit("mutate.py: the catalogue does not apply to this tree (run --check-applies)")

    # Baseline: every test the campaign uses passes on the unmutated code, and takes this long.
    baseline = {}
    for t in sorted({t for m in mutants for t in m.tests}) if not args.skip_baseline else []:
        result, secs = run_test(src, t, args.jobs, None, os.path.join(logs, "baseline-" + t.replace("/", "_")))
        log("baseline %-52s %s (%.0f s)" % (t, result, secs), fh)
        if result != "pass":
            sys.exit("mutate.py: %s fails on the unmutated code; fix that first (logs in %s)" % (t, logs))
        baseline[t] = secs

    results = []
    for i, m in enumerate(mutants, 1):
        path = os.path.join(src, m.file)
        with open(path, encoding="utf-8") as f:
            original = f.read()
        note = os.path.join(args.workdir, "pending.json")
        with open(note, "w") as f:
            json.dump({"path": path, "original": original}, f)
        with open(path, "w", encoding="utf-8") as f:
            f.write(m.apply(original))
        t0 = time.time()
        outcome, killer = "survived", ""
        try:
            ok, _ = build(src, args.jobs, os.path.join(logs, m.id + ".build"), m.tests)
            if not ok:
                outcome = "not built"
            else:
                for t in m.tests:
                    limit = max(120.0, 5.0 * baseline[t]) if t in baseline else 600.0
                    result, _ = run_test(src, t, args.jobs, limit, os.path.join(logs, "%s.%s" % (m.id, t.replace("/", "_"))))
                    if result != "pass":
                        outcome, killer = "killed", "%s (%s)" % (t, result)
                        break
        finally:
            with open(path, "w", encoding="utf-8") as f:
                f.write(original)
            os.remove(note)
        secs = time.time() - t0
        results.append({"id": m.id, "part": m.part, "outcome": outcome, "killed_by": killer, "seconds": round(secs),
                        "about": m.about, "file": m.file})
        log("[%d/%d] %-34s %-9s %s (%.0f s)" % (i, len(mutants), m.id, outcome.upper(), killer, secs), fh)
    # leave the copy built from the unmutated code
    build(src, args.jobs, os.path.join(logs, "final.build"), ["check"])

    scored = [r for r in results if r["outcome"] != "not built"]
    killed = sum(r["outcome"] == "killed" for r in scored)
    survivors = [r for r in scored if r["outcome"] == "survived"]
    minutes = (time.time() - t_start) / 60
    log("", fh)
    log("by part:", fh)
    for part in sorted({r["part"] for r in scored}):
        rs = [r for r in scored if r["part"] == part]
        log("  %-12s %d/%d killed" % (part, sum(r["outcome"] == "killed" for r in rs), len(rs)), fh)
    for r in results:
        if r["outcome"] == "not built":
            log("NOT BUILT (not scored; fix the catalogue): %s" % r["id"], fh)
    log("survivors (%d):" % len(survivors), fh)
    for r in survivors:
        log("  %s (%s, %s): %s" % (r["id"], r["part"], r["file"], r["about"]), fh)
    score = 100.0 * killed / len(scored) if scored else 0.0
    log("mutation score: %d/%d killed = %.1f%% in %.0f minutes" % (killed, len(scored), score, minutes), fh)
    with open(os.path.join(args.workdir, "results.json"), "w") as f:
        json.dump({"score": score, "killed": killed, "total": len(scored), "minutes": round(minutes, 1),
                   "results": results}, f, indent=1)
    fh.close()
    return 0 if score >= args.threshold else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--catalogue", default=CATALOGUE)
    ap.add_argument("--srcdir", default=DEFAULT_SRC, help="the project (default: this checkout)")
    ap.add_argument("--list", action="store_true", help="list the mutants")
    ap.add_argument("--check-applies", action="store_true", help="check that every mutant applies exactly once")
    ap.add_argument("--show", metavar="ID", help="print one mutant as a diff")
    ap.add_argument("--only", metavar="ID,...", help="run only these mutants")
    ap.add_argument("--part", help="run only the mutants of one part")
    ap.add_argument("--full", action="store_true", help="run all of make check for every mutant (slow)")
    ap.add_argument("--workdir", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "aalab-mutation"),
                    help="scratch folder for the copy, logs and report (default $TMPDIR/aalab-mutation)")
    ap.add_argument("--source", choices=("head", "working"), default="head",
                    help="copy the committed tree (default) or the working tree with uncommitted changes")
    ap.add_argument("--configure-flags", default="", help="flags for ./configure of the copy")
    ap.add_argument("--jobs", type=int, default=2, help="make -j (default 2)")
    ap.add_argument("--skip-baseline", action="store_true",
                    help="do not run the tests on the unmutated code first (only when they are known to pass on "
                         "this commit; time limit 600 s a test)")
    ap.add_argument("--threshold", type=float, default=90.0, help="exit 1 below this score (default 90)")
    args = ap.parse_args()
    args.srcdir = os.path.abspath(args.srcdir)
    args.workdir = os.path.abspath(args.workdir)
    mutants = load_catalogue(args.catalogue)
    ids = [m.id for m in mutants]
    if len(set(ids)) != len(ids):
        sys.exit("mutate.py: duplicate mutant ids")
    if args.check_applies:
        return check_applies(mutants, args.srcdir)
    mutants = select(mutants, args.only, args.part)
    if args.list:
        for m in mutants:
            print("%-34s %-12s %-40s %s" % (m.id, m.part, m.file, m.about))
        print("%d mutants" % len(mutants))
        return 0
    if args.show:
        m = {m.id: m for m in mutants}.get(args.show)
        if not m:
            sys.exit("mutate.py: no mutant %s" % args.show)
        show(m, args.srcdir)
        return 0
    if os.path.realpath(args.workdir).startswith(os.path.realpath(args.srcdir) + os.sep):
        sys.exit("mutate.py: --workdir must be outside the project")
    stop_on_sigterm()
    try:
        return campaign(args, mutants)
    except KeyboardInterrupt:
        print("mutate.py: stopped; the copy in %s is restored to the unmutated code" % args.workdir)
        return 130


if __name__ == "__main__":
    sys.exit(main())
