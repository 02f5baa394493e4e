#!/usr/bin/python3
"""`Load stepping/Wall time limit`: a run that cannot finish in the time given
stops cleanly at the end of the step that passes the limit, with exit code 3,
the converged steps' results kept and (with `Checkpoint interval` > 0) a
checkpoint written at that step, which `--resume` (with the limit lifted)
continues to the end of the load path, matching the uninterrupted run. The
limit (0.5 s) is far below the run's time (200 steps of the elastic patin,
several seconds), so where the run stops depends on the machine, not whether."""
import os
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    patin = f.read()
steps = 200
text = (patin + sltest.nested_set("Load stepping/Number of load steps", steps) +
        sltest.nested_set("Output/Checkpoint interval", 1000) + sltest.QUIET_OUTPUT)
limited = text + sltest.nested_set("Load stepping/Wall time limit", 0.5)
out = f"{workdir}/limited"
code, log = sltest.run(executable, limited, out, expect_success=False)
rows = sltest.read_csv(out + "/output/statistics.csv")
check(code == 3 and "Stopped at the wall-time limit (Load stepping/Wall time limit = 0.5 s)" in log,
      f"limit 0.5 s: stopped cleanly, exit code {code}")
check(0 < len(rows) < steps and os.path.isdir(out + "/output/checkpoint"),
      f"limit 0.5 s: {len(rows)} of {steps} steps kept, a checkpoint written")
check("WARNING: at the pace of the first load step" in log, "limit 0.5 s: warned after the first step")

# resume with the limit lifted (`Wall time limit` may change on a resume)
with open(f"{out}/input.prm", "w") as f:
    f.write(text)
result = subprocess.run([executable, "--resume", "input.prm"], cwd=out, env=sltest.MPI_ENV,
                        capture_output=True, text=True, timeout=1200)
resumed = sltest.read_csv(out + "/output/statistics.csv")
check(result.returncode == 0 and len(resumed) == steps and abs(resumed[-1]["time"] - 1.0) < 1e-12,
      f"resumed: exit code {result.returncode}, {len(resumed)} steps, ends at t = 1")

code, log = sltest.run(executable, text, f"{workdir}/whole", expect_success=False)
whole = sltest.read_csv(f"{workdir}/whole/output/statistics.csv")
check(code == 0 and len(whole) == steps, f"uninterrupted: exit code {code}")
if whole and resumed:
    for column in ("normal_force_N", "tangential_force_N"):
        check(abs(whole[-1][column] - resumed[-1][column]) <= 1e-9 * abs(whole[-1]["normal_force_N"]),
              f"last step {column}: resumed {resumed[-1][column]:.9g} = uninterrupted {whole[-1][column]:.9g}")
check.finish()
