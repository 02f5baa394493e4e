#!/usr/bin/python3
"""The size of the code's parts, against the limits of doc/architecture.md:
files of source/ and include/ over 600 lines, functions over 80 lines, and
the member functions and header lines of ContactProblem.

    contrib/code_metrics.py            # the table
    contrib/code_metrics.py --check    # exit 1 when a limit is exceeded

Functions are found in the clang-formatted sources (.clang-format): a
definition's body opens with a brace alone on its line at the indentation of
its name, and closes at the same indentation. Lambdas and class bodies are
not counted as functions; a function's lines are those from its name to its
closing brace."""
import argparse
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 80
MAX_PROBLEM_MEMBERS = 70
MAX_PROBLEM_HEADER_LINES = 600
PROBLEM_HEADER = "include/stabilized_lagrangian/solver/contact_problem.h"

NAME = re.compile(r"^(\s*)(?:[\w:<>,~*& ]+::)?(~?\w+|operator\S+)\s*\(")
KEYWORDS = {"if", "for", "while", "switch", "return", "catch", "sizeof", "static_assert",
            "decltype", "AssertThrow", "Assert"}


def source_files():
    for top in ("source", "include"):
        for folder, _, names in os.walk(os.path.join(ROOT, top)):
            for name in sorted(names):
                if name.endswith((".cc", ".h")):
                    yield os.path.relpath(os.path.join(folder, name), ROOT)


def functions(lines):
    """(name, first line, number of lines) of each function definition."""
    found = []
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped != "{":
            continue
        indent = line[: len(line) - len(line.lstrip())]
        # the signature: the lines above indented deeper continue it (parameters,
        # initialisers); the first one at this indentation names the function
        j = i - 1
        while j >= 0 and (lines[j].startswith(indent + " ") or not lines[j].strip()):
            j -= 1
        if j < 0 or not NAME.match(lines[j]) or lines[j].rstrip().endswith(";"):
            continue
        match = NAME.match(lines[j])
        name = match.group(2)
        if name in KEYWORDS or lines[j].lstrip().startswith(("class ", "struct ", "namespace ")):
            continue
        end = i + 1
        while end < len(lines) and lines[end].rstrip() != indent + "}":
            end += 1
        found.append((name, j + 1, end - j + 1))
    return found


def problem_members():
    """The member functions of ContactProblem: declared in its header (by name and line)."""
    with open(os.path.join(ROOT, PROBLEM_HEADER)) as f:
        text = f.read()
    start = text.index("class ContactProblem")
    depth, body = 0, []
    for k in range(text.index("{", start), len(text)):
        c = text[k]
        depth += c == "{"
        depth -= c == "}"
        body.append(c)
        if depth == 0:
            break
    members, level = 0, 0
    for line in "".join(body).splitlines():
        # at the class's own level (not a nested class's): `    name(` after its
        # return type's line, or `    Type name(` on one line
        declaration = r"^    (?=[\w~])(?:[\w:<>,*& ]+ )?[*&]?(~?\w+|operator\S+)\("
        if level == 1 and re.match(declaration, line) \
                and not re.match(r"^    (return|if|for|while|Assert\w*|\w)\b", line):
            members += 1
        level += line.count("{") - line.count("}")
    return members


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="exit 1 when a limit is exceeded")
    args = parser.parse_args()
    long_files, long_functions = [], []
    for path in source_files():
        with open(os.path.join(ROOT, path)) as f:
            lines = f.read().splitlines()
        if len(lines) > MAX_FILE_LINES:
            long_files.append((len(lines), path))
        for name, first, count in functions(lines):
            if count > MAX_FUNCTION_LINES:
                long_functions.append((count, f"{path}:{first}", name))
    with open(os.path.join(ROOT, PROBLEM_HEADER)) as f:
        header_lines = len(f.read().splitlines())
    members = problem_members()
    print(f"ContactProblem: {members} member functions (limit {MAX_PROBLEM_MEMBERS}), "
          f"header {header_lines} lines (limit {MAX_PROBLEM_HEADER_LINES})")
    print(f"\nfiles over {MAX_FILE_LINES} lines: {len(long_files)}")
    for count, path in sorted(long_files, reverse=True):
        print(f"  {count:5d}  {path}")
    print(f"\nfunctions over {MAX_FUNCTION_LINES} lines: {len(long_functions)}")
    for count, where, name in sorted(long_functions, reverse=True):
        print(f"  {count:5d}  {name}  ({where})")
    exceeded = (long_files or long_functions or members > MAX_PROBLEM_MEMBERS or
                header_lines > MAX_PROBLEM_HEADER_LINES)
    return 1 if args.check and exceeded else 0


if __name__ == "__main__":
    sys.exit(main())
