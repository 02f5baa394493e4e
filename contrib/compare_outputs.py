#!/usr/bin/python3
"""Check that two builds give the same results: every scene of prm/ (or those
named) runs with both executables, on 1 and 2 MPI ranks, and statistics.csv,
iterations.csv, every profile-*.csv and run_summary.csv are compared.

Integer-valued columns (iteration counts, steps, points, DoFs) must be equal;
every other value must agree to --tolerance (1e-12 by default) of its scale:
the largest magnitude in the run's files of the quantities of its unit (`_mm`, `_MPa`,
`_N`: a slip of 1e-16 mm in a patch test is measured against the coordinates
and displacements, a final residual against the forces), 1 for the
dimensionless scaled residuals (their criterion is absolute), else its
column's; the time and memory columns (`*_s`, `*_MiB`) are left out. A refactoring that keeps the
arithmetic gives bitwise-equal files on one rank; on several, MUMPS sums in an
order that changes from run to run, which moves the values at round-off.

    contrib/compare_outputs.py --before old/stabilized_lagrangian \\
        --after build/stabilized_lagrangian --workdir /tmp/compare

Exit code 0 when every file agrees, 1 otherwise; a table of the comparisons on
standard output, and in FOLDER/compare_outputs.md with --output FOLDER."""
import argparse
import concurrent.futures
import csv
import glob
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               PMIX_MCA_gds="hash")


def scene_text(path, output):
    """The scene with its relative mesh files made absolute and its output in `output`."""
    with open(path) as f:
        text = f.read()
    directory = os.path.dirname(os.path.abspath(path))
    text = re.sub(r"(set Mesh file\s*=\s*)(\S+)",
                  lambda m: m.group(1) + (m.group(2) if os.path.isabs(m.group(2))
                                          else os.path.join(directory, m.group(2))), text)
    return text + f"\nsubsection Output\n  set Output directory = {output}\nend\n"


def run(executable, scene, ranks, workdir):
    os.makedirs(workdir, exist_ok=True)
    prm = os.path.join(workdir, "input.prm")
    with open(prm, "w") as f:
        f.write(scene_text(scene, os.path.join(workdir, "output")))
    command = [os.path.abspath(executable), prm]
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
    with open(os.path.join(workdir, "log"), "w") as log:
        return subprocess.run(command, cwd=workdir, env=MPI_ENV, stdout=log,
                              stderr=subprocess.STDOUT).returncode


def read(path):
    with open(path) as f:
        return list(csv.reader(f))


def unit(column):
    for suffix in ("_mm", "_MPa", "_N", "_N_per_mm"):
        if column.endswith(suffix):
            return suffix
    return column


def scales(paths):
    """The scale of each unit (or unitless column) over the CSV files of a run."""
    scale = {}
    for path in paths:
        rows = read(path)
        for row in rows[1:]:
            for column, value in zip(rows[0], row):
                try:
                    scale[unit(column)] = max(scale.get(unit(column), 0.), abs(float(value)))
                except ValueError:
                    pass
    for key in list(scale):
        if "scaled_residual" in key:
            scale[key] = max(1., scale[key])
    return scale


def compare_file(a_path, b_path, tolerance, scale):
    """The differences between two CSV files, in words (empty if they agree), each value
    against the `scale` of its unit."""
    a, b = read(a_path), read(b_path)
    if not a or not b or a[0] != b[0]:
        return ["headers differ"]
    if len(a) != len(b):
        return [f"{len(a) - 1} against {len(b) - 1} rows"]
    problems = []
    for row, (ra, rb) in enumerate(zip(a[1:], b[1:]), start=1):
        for column, va, vb in zip(a[0], ra, rb):
            if column.endswith(("_s", "_MiB")):  # wall times and memory vary from run to run
                continue
            try:
                x, y = float(va), float(vb)
            except ValueError:
                if va != vb:
                    problems.append(f"row {row} {column}: {va} against {vb}")
                continue
            if x.is_integer() and y.is_integer():
                ok = x == y
            else:
                ok = abs(x - y) <= tolerance * scale[unit(column)]
            if not ok:
                problems.append(f"row {row} {column}: {va} against {vb}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--before", required=True, type=tool_cli.executable, help="the reference executable")
    parser.add_argument("--after", required=True, type=tool_cli.executable, help="the executable to check")
    parser.add_argument("--workdir", required=True)
    parser.add_argument("--scenes", nargs="*", type=tool_cli.existing_file,
                        default=sorted(glob.glob(os.path.join(ROOT, "prm", "*.prm"))))
    parser.add_argument("--ranks", nargs="*", type=tool_cli.positive_int, default=[1, 2])
    parser.add_argument("--tolerance", type=tool_cli.positive_float, default=1e-12)
    parser.add_argument("--jobs", type=tool_cli.positive_int, default=1, help="runs at a time (each uses `ranks` cores)")
    parser.add_argument("--output", metavar="FOLDER", help="also write the table to FOLDER/compare_outputs.md")
    args = parser.parse_args()
    if args.output and os.path.exists(args.output) and not os.path.isdir(args.output):
        parser.error(f"argument --output: '{args.output}' exists and is not a directory")
    table = []

    def report(line):
        print(line, flush=True)
        table.append(line)

    cases = [(scene, ranks, which, executable) for scene in args.scenes for ranks in args.ranks
             for which, executable in (("before", args.before), ("after", args.after))]
    directory = {case: os.path.join(args.workdir, os.path.splitext(os.path.basename(case[0]))[0],
                                    f"np{case[1]}", case[2]) for case in cases}
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        codes = dict(zip(cases, pool.map(lambda c: run(c[3], c[0], c[1], directory[c]), cases)))

    failures = 0
    report("| scene | ranks | files | result |\n|---|---|---|---|")
    for scene in args.scenes:
        for ranks in args.ranks:
            name = os.path.splitext(os.path.basename(scene))[0]
            before, after = (directory[(scene, ranks, w, e)] for w, e in
                             (("before", args.before), ("after", args.after)))
            code_a = codes[(scene, ranks, "before", args.before)]
            code_b = codes[(scene, ranks, "after", args.after)]
            files = sorted(os.path.basename(p) for p in glob.glob(os.path.join(before, "output", "*.csv")))
            files_b = sorted(os.path.basename(p) for p in glob.glob(os.path.join(after, "output", "*.csv")))
            problems = []
            if code_a != code_b:
                problems.append(f"exit codes {code_a} and {code_b}")
            if files != files_b:
                problems.append(f"files differ: {sorted(set(files) ^ set(files_b))}")
            common = [f for f in files if f in files_b]
            scale = scales([os.path.join(d, "output", f) for d in (before, after) for f in common])
            for f in common:
                problems += [f"{f}: {p}" for p in
                             compare_file(os.path.join(before, "output", f),
                                          os.path.join(after, "output", f), args.tolerance, scale)]
            failures += bool(problems)
            result = "same" if not problems else "; ".join(problems[:5]) + \
                (f" (and {len(problems) - 5} more)" if len(problems) > 5 else "")
            report(f"| {name} | {ranks} | {len(files)} | {result} |")
    if args.output:
        os.makedirs(args.output, exist_ok=True)
        with open(os.path.join(args.output, "compare_outputs.md"), "w") as f:
            f.write("\n".join(table) + "\n")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
