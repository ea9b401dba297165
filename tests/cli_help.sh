#!/bin/sh
# Every command's --help lists every option it takes, each option with a value says its default (or that
# it is required), and aalab(1) describes the same options for the same commands: the options of each
# command's --help, of its section in docs/aalab.1 (with JOB OPTIONS and CONNECTION OPTIONS where the
# section takes them) and of its option table in client/ are one set. Every option --help lists is one the
# command accepts.
. "$(dirname "$0")/lib.sh"

/usr/bin/python3 - "$AALAB" "$top_srcdir" <<'PY'
import re, subprocess, sys

aalab, src = sys.argv[1], sys.argv[2]
failures = 0

def fail(msg):
    global failures
    failures += 1
    print("FAIL: " + msg)

def ok(msg):
    print("ok: " + msg)

def run(*args):
    p = subprocess.run([aalab] + list(args), capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr

# the commands, from aalab --help
rc, out, _ = run("--help")
commands = re.findall(r"^  ([a-z]+) ", out, re.M)
if rc != 0 or len(commands) < 14:
    fail("aalab --help lists %d commands (exit %d)" % (len(commands), rc))

def help_options(text):
    """Options of a --help text: the flags in the option column of lines that start with '  --', each
    with its description (the rest of the line and the lines indented under it)."""
    opts = {}
    lines = text.split("\n")
    for i, line in enumerate(lines):
        if not line.startswith("  --"):
            continue
        m = re.match(r"^  (.*?)(?:\s{2,}(.*))?$", line)
        column, desc = m.group(1), m.group(2) or ""
        for j in range(i + 1, len(lines)):
            if lines[j].startswith(" " * 10) and not lines[j].startswith("  --"):
                desc += " " + lines[j].strip()
            else:
                break
        for name, arg in re.findall(r"(--[a-z][a-z-]*)( [A-Z][^\s,]*)?", column):
            opts[name] = (arg.strip(), desc)
    return opts

man = open(src + "/docs/aalab.1").read()

def man_block(title):
    m = re.search(r"^\.SH " + title + r"\n(.*?)(?=^\.SH )", man, re.M | re.S)
    return m.group(1) if m else ""

def man_defined(text):
    """Options that a block defines: the first word of a .TP or .TQ item."""
    return set(n.replace("\\-", "-") for n in
               re.findall(r"^\.(?:TP|TQ)\n\.B[IR]? (\\-\\-[a-z\\-]+)", text, re.M))

sections = dict(re.findall(r'^\.SS "aalab ([a-z]+)[^\n]*\n(.*?)(?=^\.S[SH] )', man, re.M | re.S))
job_opts, connect_opts = man_defined(man_block("JOB OPTIONS")), man_defined(man_block("CONNECTION OPTIONS"))
if len(job_opts) < 11 or connect_opts != {"--connect", "--token-file"}:
    fail("aalab(1)'s JOB OPTIONS (%d) or CONNECTION OPTIONS (%s) are not there" % (len(job_opts), connect_opts))

# the option tables in client/: the long options each command's getopt takes
def table(path):
    return set("--" + n for n in re.findall(r'\{"([a-z][a-z-]*)", (?:required|no)_argument', open(src + "/client/" + path).read()))
job_table = set("--" + n for n in re.findall(r'\{"([a-z][a-z-]*)", required_argument, 0, AA_OPT_JOB\}',
                                              open(src + "/client/client.h").read()))
tables = {"run": table("cmd_run.c") | job_table, "submit": table("cmd_submit.c") | job_table,
          "slurm": table("cmd_slurm.c") | job_table, "watch": table("cmd_watch.c"),
          "compare": table("cmd_compare.c"), "diff": table("cmd_diff.c"), "merge": table("cmd_merge.c")}
service = table("remote.c")  # status, list, cancel and get share one table; each help names its part

for cmd in commands:
    rc, text, err = run(cmd, "--help")
    if rc != 0 or not text.startswith("usage: aalab " + cmd):
        fail("aalab %s --help: exit %d, %r" % (cmd, rc, text[:60]))
        continue
    helped = help_options(text)
    names = set(helped) - {"--help"}
    # each option with a value says its default, or that it is required
    for name, (arg, desc) in sorted(helped.items()):
        if arg and not re.search(r"default|required", desc, re.I):
            fail("aalab %s --help: %s %s does not say its default: %r" % (cmd, name, arg, desc[:80]))
    # the same options in aalab(1)
    if cmd not in sections:
        fail("aalab(1) has no section for %s" % cmd)
        continue
    body = sections[cmd]
    documented = man_defined(body)
    if "JOB OPTIONS" in body:
        documented |= job_opts
    if "CONNECTION OPTIONS" in body:
        documented |= connect_opts
    if names == documented:
        ok("aalab %s: --help and aalab(1) list the same %d options" % (cmd, len(names)))
    else:
        fail("aalab %s: only in --help: %s; only in aalab(1): %s" % (cmd, sorted(names - documented),
                                                                      sorted(documented - names)))
    # and the command's own option table
    if cmd in tables:
        taken = tables[cmd] - {"--help"}
        if taken == names:
            ok("aalab %s: --help lists every option its table takes" % cmd)
        else:
            fail("aalab %s: taken but not in --help: %s; in --help but not taken: %s" % (
                cmd, sorted(taken - names), sorted(names - taken)))
    elif cmd in ("status", "list", "cancel", "get"):
        # the shared table refuses what the command's help does not name: each named one is accepted
        for name in sorted(names - {"--json"}):
            if name not in service:
                fail("aalab %s: %s is in --help but not in the service options" % (cmd, name))
            arg = helped[name][0]
            rc, _, err = run(cmd, name, *(["x"] if arg else []), "--help")
            if "does not apply" in err or "unrecognized" in err:
                fail("aalab %s %s is refused: %s" % (cmd, name, err.strip()))
        ok("aalab %s: every option of its --help is accepted" % cmd)
    for name in sorted(names):
        if re.search(r"unrecognized option '%s'" % re.escape(name), err):
            fail("aalab %s refuses %s" % (cmd, name))

sys.exit(1 if failures else 0)
PY
[ $? -eq 0 ] && pass "help and manual agree" || fail "help and manual disagree"
finish
