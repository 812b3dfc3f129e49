#!/usr/bin/env python3
"""Refuses an #include that runs the wrong way between folders, an include of a file
that does not exist, and any circle between files (README.md, "How it fits together").

Usage: check_layering.py ROOT. Prints one line per violation and exits 1 when there is
any. A .c file and its own header are one unit; a circle is units that include each
other directly or through others."""
import os
import re
import sys

# Which folders each folder may use (its own is always allowed). Folders not listed
# (tests, bench, tools) may use everything and are not checked.
ALLOWED = {
    "io": [],
    "ui": [],
    # Edit layers' pure model (the stack, blends, masks, material rules): functions of
    # heights, saved with the parameters, so below them.
    "editor/layers": ["io"],
    "editor/params": ["editor/layers", "io"],
    "editor/gen": ["editor/params", "editor/layers", "io"],
    "editor/world": ["editor/gen", "editor/params", "editor/layers", "io"],
    "editor/edit": ["editor/world", "editor/gen", "editor/params", "editor/layers", "io"],
    "editor/tools": ["editor/edit", "editor/world", "editor/gen", "editor/params", "editor/layers", "io"],
    "editor/interchange": ["editor/edit", "editor/world", "editor/gen", "editor/params", "editor/layers", "io"],
    "editor/cmd": ["editor/interchange", "editor/tools", "editor/edit", "editor/world", "editor/gen", "editor/params",
                   "editor/layers", "io"],
    # The renderer reads the world; it knows neither the command language nor the edits.
    "renderer": ["editor/world", "editor/gen", "editor/params", "editor/layers", "io", "ui"],
    # The viewport's commands sit above both.
    "view": ["renderer", "editor/cmd", "editor/interchange", "editor/tools", "editor/edit", "editor/world",
             "editor/gen", "editor/params", "editor/layers", "io", "ui"],
    "app": None,  # everything
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
SOURCE = (".c", ".h", ".cpp")


def folder_of(path):
    """The checked folder a repository path belongs to, or None."""
    best = None
    for folder in ALLOWED:
        if path == folder or path.startswith(folder + "/"):
            if best is None or len(folder) > len(best):
                best = folder
    return best


def includes(root, path):
    """(line number, included path) of every quoted include, outside comments."""
    out = []
    in_comment = False
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            text = line
            if in_comment:
                end = text.find("*/")
                if end < 0:
                    continue
                text = text[end + 2:]
                in_comment = False
            # Strings and line comments first, so "/*" inside either opens nothing.
            code = re.sub(r'"(\\.|[^"\\])*"', '""', text)
            code = code.split("//", 1)[0]
            code = re.sub(r"/\*.*?\*/", " ", code)
            start = code.find("/*")
            if start >= 0:
                in_comment = True
                text = code[:start]
            m = INCLUDE.match(text)
            if m:
                out.append((number, m.group(1)))
    return out


def main():
    if len(sys.argv) != 2:
        print("usage: check_layering.py ROOT", file=sys.stderr)
        return 2
    root = sys.argv[1]
    files = []
    for folder in ALLOWED:
        top = os.path.join(root, folder)
        if not os.path.isdir(top):
            continue
        for name in sorted(os.listdir(top)):
            if name.endswith(SOURCE) and os.path.isfile(os.path.join(top, name)):
                files.append(folder + "/" + name)
    problems = 0
    graph = {}  # unit -> {unit: (file, line)}
    for path in files:
        here = folder_of(path)
        unit = os.path.splitext(path)[0]
        edges = graph.setdefault(unit, {})
        for number, target in includes(root, path):
            if not os.path.isfile(os.path.join(root, target)):
                # A sibling include ("x.h" next to the file) is not our style: paths are
                # from the root. Anything that does not resolve is an error.
                print(f"{path}:{number}: includes \"{target}\", which is not a file in the tree")
                problems += 1
                continue
            there = folder_of(target)
            allowed = ALLOWED[here]
            if there is not None and there != here and allowed is not None and there not in allowed:
                print(f"{path}:{number}: includes \"{target}\" (folder {here} may not use {there})")
                problems += 1
            target_unit = os.path.splitext(target)[0]
            if target_unit != unit and there is not None:
                edges.setdefault(target_unit, (path, number))
    # Circles: depth-first search for back edges.
    state = {}
    stack = []
    circles = set()

    def visit(u):
        state[u] = 1
        stack.append(u)
        for v in sorted(graph.get(u, {})):
            if state.get(v) == 1:
                cycle = stack[stack.index(v):] + [v]
                key = tuple(sorted(set(cycle)))
                if key not in circles:
                    circles.add(key)
                    print("circle: " + " -> ".join(cycle))
            elif v not in state:
                visit(v)
        stack.pop()
        state[u] = 2

    sys.setrecursionlimit(10000)
    for u in sorted(graph):
        if u not in state:
            visit(u)
    problems += len(circles)
    print(f"check_layering: {len(files)} files, {problems} problem{'s' if problems != 1 else ''}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
