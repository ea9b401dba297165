#!/usr/bin/python3
"""The engine's folders are layers: a file may include headers of its own layer and of the layers below
it, never above (docs/architecture.md, "Layers"). Every include of an engine header names it from
engine/ ("render/renderer.h"), so the layer of each include is its first path component. Fails, naming
each include that goes up a layer or does not name its layer."""
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


def main():
    srcdir = os.environ.get("top_srcdir") or os.path.join(os.path.dirname(__file__), "..", "..")
    problems = check(os.path.join(srcdir, "engine")) + check_declarations(os.path.join(srcdir, "engine"))
    for p in problems:
        print(p)
    if problems:
        print(f"FAIL: {len(problems)} include(s) break the layers")
        return 1
    print(f"ok: every include of engine/ follows the layers ({' < '.join(LAYERS)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
