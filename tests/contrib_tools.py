#!/usr/bin/python3
"""The contrib/ tools behave like tools: every contrib/*.py is executable and
answers --help with exit code 0; contrib/iteration_table.py, on a real run of
the elastic patin, prints for each step the Newton total of statistics.csv and
the run's cumulative count up to it (`cumulative_newton_iterations`), also
when the step is printed alone, and stops with an error (exit code 2, nothing
on standard output) for a step the run does not have. The run's CSV files under the
column names of output schema 1 (CHANGELOG.md: plane strain forces `_N`) are read
by contrib/run_output.py under the current ones (`_N_per_mm`), with the same values."""
import glob
import os
import re
import shutil
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
contrib = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
table_tool = os.path.join(contrib, "iteration_table.py")


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    return result.returncode, result.stdout, result.stderr


# --help of every script, run as a user runs it (by its #! line: this checks the executable bit too)
for script in sorted(glob.glob(os.path.join(contrib, "*.py"))):
    name = os.path.basename(script)
    check(os.access(script, os.X_OK), f"{name} is executable")
    with open(script) as f:
        interpreter = f.readline()
    command = [script, "--help"]
    if "pvpython" in interpreter and shutil.which("pvpython") is None:
        command = [sys.executable] + command  # its --help needs no ParaView
    code, out, err = run(command)
    check(code == 0 and "usage:" in out, f"{name} --help: exit code {code}" + (f", {err.strip()[-300:]}" if code else ""))

# a run with a few load steps of different Newton counts
text = sltest.read_prm(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm"))
text = text.replace("set Global refinements = 4", "set Global refinements = 3")
if sltest.run_checked(executable, text, workdir, check, "elastic patin"):
    output = os.path.join(workdir, "output")
    statistics = {int(r["step"]): r for r in sltest.read_csv(os.path.join(output, "statistics.csv"))}
    steps = sorted(statistics)

    def totals(text):
        """{step: (step total, cumulative)} of the table's total rows."""
        rows = re.findall(r"^\| (\d+) \| \| \| \| step total \(cumulative\) \| \*\*(\d+)\*\* \((\d+)\) \|$", text, re.M)
        return {int(s): (int(t), int(c)) for s, t, c in rows}

    code, out, err = run([table_tool, output])
    found = totals(out)
    check(code == 0 and sorted(found) == steps, f"the whole table: exit code {code}, steps {sorted(found)}")
    expected = {s: (int(statistics[s]["newton_iterations"]), int(statistics[s]["cumulative_newton_iterations"]))
                for s in steps}
    check(found == expected, f"step totals and cumulative counts equal statistics.csv's: {found} against {expected}")
    check(len(set(t for t, _ in expected.values())) > 1 and expected[steps[-1]][1] > expected[steps[-1]][0],
          "the run's steps differ in Newton iterations (the check means something)")
    middle = steps[len(steps) // 2]
    code, out, err = run([table_tool, output, str(middle)])
    found = totals(out)
    check(code == 0 and found == {middle: expected[middle]},
          f"step {middle} alone: {found}, statistics.csv {expected[middle]}")

    missing = steps[-1] + 1
    code, out, err = run([table_tool, output, str(missing)])
    check(code == 2 and not out.strip() and f"step {missing} not in" in err,
          f"step {missing}, which the run does not have: exit code {code}, stderr '{err.strip()[-200:]}'")
    code, out, err = run([table_tool, workdir])
    check(code == 2 and "iterations.csv not found" in err,
          f"a directory without iterations.csv: exit code {code}, stderr '{err.strip()[-200:]}'")

    # the run's CSV files under the column names of schema 1 (CHANGELOG.md: plane strain forces
    # `_N`, no schema_version): contrib/run_output.py reads them under the current names too
    run_output = sltest.run_output
    old = os.path.join(workdir, "schema_1")
    shutil.rmtree(old, ignore_errors=True)
    shutil.copytree(output, old)
    renamed = 0
    for name in ("statistics.csv", "iterations.csv", "run_summary.csv"):
        with open(os.path.join(old, name)) as f:
            header, rest = f.read().split("\n", 1)
        columns = [c[:-len("_per_mm")] if c.endswith("_N_per_mm") else c for c in header.split(",")]
        renamed += sum(c.endswith("_N_per_mm") for c in header.split(","))
        keep = [i for i, c in enumerate(columns) if c != "schema_version"]
        lines = [",".join(columns[i] for i in keep)] + [",".join(row.split(",")[i] for i in keep)
                                                         for row in rest.splitlines() if row]
        with open(os.path.join(old, name), "w") as f:
            f.write("\n".join(lines) + "\n")
    with open(os.path.join(output, "run_summary.csv")) as f:
        summary_header = f.readline().strip().split(",")
    check(renamed >= 6 and summary_header[0] == "schema_version",
          f"the plane strain run names {renamed} force columns _N_per_mm, run_summary.csv starts with "
          f"{summary_header[0]}")
    for name in ("statistics.csv", "iterations.csv"):
        new_rows = run_output.read_csv(os.path.join(output, name))
        old_rows = run_output.read_csv(os.path.join(old, name))
        with open(os.path.join(old, name)) as f:
            old_header = f.readline()
        missing = sorted({k for row, o in zip(new_rows, old_rows) for k in row if o.get(k) != row[k]})
        check("_N_per_mm" not in old_header and len(old_rows) == len(new_rows) > 0 and not missing,
              f"{name} with the column names of schema 1: read with every current column and value"
              + (f"; not: {missing[:5]}" if missing else ""))
    value, unit = run_output.force(run_output.read_csv(os.path.join(old, "statistics.csv"))[-1], "normal_force")
    check(unit == "N/mm" and value == statistics[steps[-1]]["normal_force_N_per_mm"],
          f"the normal force of the schema 1 file: {value} {unit} (plane strain: N/mm)")
    code, out, err = run([table_tool, old])
    check(code == 0 and totals(out) == expected, f"iteration_table.py on the schema 1 files: exit code {code}")
check.finish()
