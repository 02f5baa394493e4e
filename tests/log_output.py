#!/usr/bin/python3
"""What the log says, and that a killed run leaves it.

The log names the solver: the banner of the patin says `linear solver: direct` and why
(`Method = automatic`, 2D). With `Output/Log Newton iterations`, the first Newton iterate
of a body at rest, which has no force yet to scale its residual by, says so instead of
printing `inf`.

A killed run leaves its log. With the standard output redirected to a file (`> log`, as a
batch system does), each line must reach the file when it is printed, not when a buffer
fills: the patin (prm/patin_elastic.prm, here in 200 load steps) runs with its output into a
file and is killed with SIGKILL, once while its first step runs (statistics.csv holds its
header only: the file must hold the banner) and once after two steps (the file must hold the
line of step 1 too)."""
import os
import shutil
import signal
import subprocess
import sys
import time
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
text = (sltest.read_prm(os.path.join(root, "prm", "patin_elastic.prm")) +
        sltest.nested_set("Load stepping/Number of load steps", 200) + sltest.QUIET_OUTPUT)
os.makedirs(workdir, exist_ok=True)
with open(os.path.join(workdir, "input.prm"), "w") as f:
    f.write(text)
statistics = os.path.join(workdir, "output", "statistics.csv")


def killed_run(rows):
    """The log of a run killed once statistics.csv holds @p rows lines (its header first)."""
    log_path = os.path.join(workdir, "log")
    shutil.rmtree(os.path.dirname(statistics), ignore_errors=True)
    with open(log_path, "w") as log:
        process = subprocess.Popen([executable, "input.prm"], cwd=workdir, env=sltest.MPI_ENV,
                                   stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        deadline = time.time() + 600
        while process.poll() is None and time.time() < deadline:
            if os.path.exists(statistics):
                with open(statistics) as f:
                    if len(f.readlines()) >= rows:
                        break
            time.sleep(0.001)
        killed = process.poll() is None
        if killed:
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()
    with open(log_path) as f:
        return killed, f.read().splitlines()


for rows, expected in ((1, ("stabilized_lagrangian: 2D",)),
                       (3, ("stabilized_lagrangian: 2D", "step   1 "))):
    killed, lines = killed_run(rows)
    check(killed, f"killed at {rows} line(s) of statistics.csv, before the run's end")
    check(all(any(line.startswith(start) for line in lines) for start in expected),
          f"killed at {rows} line(s) of statistics.csv: the log holds {expected} ({len(lines)} lines)")

# the banner and the Newton lines of a whole run (2 load steps)
code, log = sltest.run(executable, text + sltest.nested_set("Load stepping/Number of load steps", 2) +
                       sltest.nested_set("Output/Log Newton iterations", "true"),
                       os.path.join(workdir, "newton_log"))
newton = [line for line in log.splitlines() if line.strip().startswith("Newton ")]
check(code == 0 and "linear solver: direct (Amesos_Mumps), by Method = automatic (direct in 2D)"
      in log, f"the banner names the linear solver and why (exit {code})")
check(len(newton) > 2 and not any("inf" in line or "nan" in line for line in newton) and
      "no scale: the body carries no force yet" in newton[0],
      f"{len(newton)} Newton lines, none with inf or nan; the first says it has no force scale")
check.finish()
