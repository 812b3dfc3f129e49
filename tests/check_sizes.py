#!/usr/bin/env python3
"""Refuses a file in app/ over 700 lines and a function there over 120 lines (issue 25:
the window stays split by concern, README.md, "How it fits together").

Usage: check_sizes.py ROOT [FOLDER...] (default app). Prints one line per violation,
FILE:LINE and what is too long, and exits 1 when there is any. A function's length runs
from the first line of its signature to its closing brace."""
import os
import re
import sys

MAX_FILE_LINES = 700
MAX_FUNCTION_LINES = 120
SOURCE = (".c", ".h")
NAME = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)\s*\(")


def code_only(text):
    """The text with comments, strings and character literals blanked (new lines kept),
    so braces inside them do not count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def long_functions(text):
    """(line, name, lines) of every top-level function body longer than the limit."""
    code = code_only(text)
    found = []
    depth = 0
    start = 0  # where the current top-level declaration began (offset)
    head_start = None
    for i, c in enumerate(code):
        if c == "{":
            if depth == 0:
                head = code[start:i]
                is_function = ")" in head and "=" not in head and not re.search(
                    r"\b(struct|enum|union)\b[^(]*$", head)
                head_start = start if is_function else None
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                if head_start is not None:
                    head = code[head_start:i]
                    first = head_start + len(head) - len(head.lstrip())
                    line0 = code.count("\n", 0, first) + 1
                    line1 = code.count("\n", 0, i) + 1
                    names = NAME.findall(head.split("(")[0] + "(")
                    name = names[-1] if names else "?"
                    if line1 - line0 + 1 > MAX_FUNCTION_LINES:
                        found.append((line0, name, line1 - line0 + 1))
                head_start = None
                start = i + 1
        elif c in ";" and depth == 0:
            start = i + 1
        elif c == "#" and depth == 0:
            # A preprocessor line at top level ends any declaration before it.
            j = code.find("\n", i)
            start = len(code) if j < 0 else j + 1
    return found


def check(root, folders):
    problems = []
    for folder in folders:
        base = os.path.join(root, folder)
        for dirpath, _, files in os.walk(base):
            for f in sorted(files):
                if not f.endswith(SOURCE):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    text = fh.read()
                lines = text.count("\n") + (0 if text.endswith("\n") or not text else 1)
                if lines > MAX_FILE_LINES:
                    problems.append(f"{rel}:1: {lines} lines (at most {MAX_FILE_LINES})")
                for line, name, length in long_functions(text):
                    problems.append(
                        f"{rel}:{line}: {name} is {length} lines (at most {MAX_FUNCTION_LINES})")
    return problems


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    root = argv[1]
    folders = argv[2:] or ["app"]
    for folder in folders:
        if not os.path.isdir(os.path.join(root, folder)):
            print(f"check_sizes: {os.path.join(root, folder)}: no such folder", file=sys.stderr)
            return 2
    problems = check(root, folders)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
