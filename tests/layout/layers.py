#!/usr/bin/python3
"""The engine's folders are layers: a file may include headers of its own layer and of the layers below
it, never above (docs/architecture.md, "Layers"). Every include of an engine header names it from
engine/ ("render/renderer.h"), so the layer of each include is its first path component. Fails, naming
each include that goes up a layer or does not name its layer.

The daemon (daemon/) is in groups the same way (DAEMON_GROUPS): no include goes up a group, no header
declares a function another group's file defines, and no two daemon files depend on each other, by
include or by call, even through others (a file and its header count as one)."""
import os
import re
import sys

# lowest first
LAYERS = ["util", "image", "metrics", "scene", "gpu", "types", "render", "reference", "methods", "run",
          "results", "report", "compare"]
RANK = {name: i for i, name in enumerate(LAYERS)}
# headers generated at build time, found on the include path
GENERATED = {"shader_list.h", "viewer_assets.h", "reference_code.h"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def check(engine_dir):
    problems = []
    folders = sorted(d for d in os.listdir(engine_dir) if os.path.isdir(os.path.join(engine_dir, d)))
    for folder in folders:
        if folder not in RANK:
            problems.append(f"engine/{folder}/: a folder that is not a layer (add it to LAYERS in order)")
    loose = sorted(f for f in os.listdir(engine_dir) if os.path.isfile(os.path.join(engine_dir, f)))
    for f in loose:
        problems.append(f"engine/{f}: a file outside every layer folder")
    for folder in folders:
        if folder not in RANK:
            continue
        for root, _, files in os.walk(os.path.join(engine_dir, folder)):
            for name in sorted(files):
                if not name.endswith((".c", ".h", ".cc")):
                    continue
                path = os.path.join(root, name)
                rel = os.path.relpath(path, os.path.dirname(engine_dir))
                with open(path, encoding="utf-8", errors="replace") as f:
                    for lineno, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m or m.group(1) in GENERATED:
                            continue
                        target = m.group(1)
                        layer = target.split("/")[0] if "/" in target else None
                        if layer not in RANK or ".." in target.split("/"):
                            problems.append(f"{rel}:{lineno}: #include \"{target}\" does not name its layer "
                                            "(write it as \"layer/file.h\")")
                        elif not os.path.isfile(os.path.join(engine_dir, target)):
                            problems.append(f"{rel}:{lineno}: #include \"{target}\": no such engine header")
                        elif RANK[layer] > RANK[folder]:
                            problems.append(f"{rel}:{lineno}: #include \"{target}\" goes up from {folder} to "
                                            f"{layer} (a layer may use only the layers below it: "
                                            f"{' < '.join(LAYERS)})")
    return problems


DEFINITION = re.compile(r"^[a-z][^(;=]*?\b(aa_[a-z0-9_]+)\(")
DECLARATION = re.compile(r"^[A-Za-z][^(=;]*?\**\b(aa_[a-z0-9_]+)\s*\(")


def check_declarations(engine_dir):
    """A header declares only functions its own layer or a lower one defines: otherwise a lower layer
    could call up through it without including anything above."""
    defined = {}
    headers = []
    for folder in LAYERS:
        d = os.path.join(engine_dir, folder)
        if not os.path.isdir(d):
            continue
        for name in sorted(os.listdir(d)):
            path = os.path.join(d, name)
            if name.endswith((".c", ".cc")):
                with open(path, encoding="utf-8", errors="replace") as f:
                    for line in f:
                        m = DEFINITION.match(line)
                        if m and not line.startswith("static"):
                            defined.setdefault(m.group(1), folder)
            elif name.endswith(".h"):
                headers.append((folder, path))
    problems = []
    for folder, path in headers:
        rel = os.path.relpath(path, os.path.dirname(engine_dir))
        with open(path, encoding="utf-8", errors="replace") as f:
            for lineno, line in enumerate(f, 1):
                if line.lstrip().startswith(("*", "/*", "#")):
                    continue
                m = DECLARATION.match(line)
                if m and m.group(1) in defined and RANK[defined[m.group(1)]] > RANK[folder]:
                    problems.append(f"{rel}:{lineno}: declares {m.group(1)}, which {defined[m.group(1)]} "
                                    f"defines: declare it in a header of {defined[m.group(1)]}")
    return problems


# daemon/: lowest first. transport knows nothing of jobs and calls the handlers only through the table in
# handlers.h; jobs is the store and the GPU worker; handlers answer requests; aalabd.c puts them together.
DAEMON_GROUPS = {
    "config": ["config.h", "config.c"],
    "transport": ["loop.h", "loop.c", "transport.h", "handlers.h", "listen.c", "conn.c", "line_conn.c", "protocol_parse.h",
                  "protocol_parse.c", "http_parse.h", "http_parse.c", "http_conn.h", "http_conn.c"],
    "jobs": ["jobs.h", "jobs.c", "scene_cache.c", "farm_jobs.c", "render_priority.h", "render_priority.c",
             "worker_job.h", "worker_render.c", "worker_run.c", "worker_process.h", "worker_process.c", "worker.c"],
    "handlers": ["daemon.h", "protocol.c", "stream.h", "stream.c", "http_routes.c", "farm_routes.h",
                 "farm_routes.c"],
    "top": ["aalabd.c"],
}
DAEMON_ORDER = list(DAEMON_GROUPS)
DAEMON_GROUP = {f: g for g, files in DAEMON_GROUPS.items() for f in files}
# a non-static function defined at the start of a line (its name is the last word before the parenthesis)
C_DEFINITION = re.compile(r"^(?!static\b)(?!typedef\b)[a-z][^(;=]*?\b([a-z_][a-z0-9_]*)\(")
C_DECLARATION = re.compile(r"^(?!static\b)(?!typedef\b)[A-Za-z][^(=;]*?\**\b([a-z_][a-z0-9_]*)\s*\(")


def read_lines(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read().split("\n")


def stem(name):
    return name.rsplit(".", 1)[0]


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    return re.sub(r'"(\\.|[^"\\\n])*"', '""', text)


def check_daemon(daemon_dir):
    problems = []
    files = sorted(f for f in os.listdir(daemon_dir) if f.endswith((".c", ".h")))
    for f in files:
        if f not in DAEMON_GROUP:
            problems.append(f"daemon/{f}: in no group (add it to DAEMON_GROUPS in tests/layout/layers.py)")
    files = [f for f in files if f in DAEMON_GROUP]
    rank = {g: i for i, g in enumerate(DAEMON_ORDER)}
    defined = {}  # function -> the .c file that defines it
    for f in files:
        if f.endswith(".c"):
            for line in read_lines(os.path.join(daemon_dir, f)):
                m = C_DEFINITION.match(line)
                if m and not line.rstrip().endswith(";"):
                    defined.setdefault(m.group(1), f)
    edges = {stem(f): set() for f in files}  # a file and its header are one node
    for f in files:
        lines = read_lines(os.path.join(daemon_dir, f))
        group = DAEMON_GROUP[f]
        for lineno, line in enumerate(lines, 1):
            m = INCLUDE.match(line)
            if not m or "/" in m.group(1):
                continue  # engine/ headers are named "layer/file.h"
            target = m.group(1)
            if target not in DAEMON_GROUP:
                problems.append(f"daemon/{f}:{lineno}: #include \"{target}\": not a daemon header in a group")
                continue
            if stem(target) != stem(f):
                edges[stem(f)].add(stem(target))
            if rank[DAEMON_GROUP[target]] > rank[group]:
                problems.append(f"daemon/{f}:{lineno}: #include \"{target}\" goes up from {group} to "
                                f"{DAEMON_GROUP[target]} (daemon groups: {' < '.join(DAEMON_ORDER)})")
        if f.endswith(".h"):
            for lineno, line in enumerate(lines, 1):
                m = C_DECLARATION.match(line)
                if m and m.group(1) in defined and DAEMON_GROUP[defined[m.group(1)]] != group:
                    other = defined[m.group(1)]
                    problems.append(f"daemon/{f}:{lineno}: declares {m.group(1)}, which daemon/{other} of "
                                    f"{DAEMON_GROUP[other]} defines: declare it in a header of "
                                    f"{DAEMON_GROUP[other]}")
        else:
            text = strip_comments("\n".join(lines))
            for name in set(re.findall(r"\b([a-z_][a-z0-9_]*)\s*\(", text)):
                g = defined.get(name)
                if g and stem(g) != stem(f):
                    edges[stem(f)].add(stem(g))
    problems += [f"daemon: files depend on each other in a circle: {' -> '.join(c)}" for c in cycles(edges)]
    return problems


def cycles(edges):
    """One circle per strongly connected component of more than one node (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(circle(edges, set(comp)))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def circle(edges, comp):
    """A path through comp that comes back to its start, for the message."""
    start = min(comp)
    path, seen = [start], {start}
    while True:
        nxt = sorted(w for w in edges[path[-1]] if w in comp)
        back = [w for w in nxt if w == start]
        if back and len(path) > 1:
            return path + [start]
        fresh = [w for w in nxt if w not in seen]
        if not fresh:
            return path + [nxt[0]] if nxt else path
        path.append(fresh[0])
        seen.add(fresh[0])


def main():
    srcdir = os.environ.get("top_srcdir") or os.path.join(os.path.dirname(__file__), "..", "..")
    problems = check(os.path.join(srcdir, "engine")) + check_declarations(os.path.join(srcdir, "engine"))
    problems += check_daemon(os.path.join(srcdir, "daemon"))
    for p in problems:
        print(p)
    if problems:
        print(f"FAIL: {len(problems)} problem(s) with the layers")
        return 1
    print(f"ok: every include of engine/ follows the layers ({' < '.join(LAYERS)}), and of daemon/ the "
          f"groups ({' < '.join(DAEMON_ORDER)}) with no circle")
    return 0


if __name__ == "__main__":
    sys.exit(main())
