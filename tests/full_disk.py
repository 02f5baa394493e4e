#!/ usr / bin / python3
"""A write that fails mid-run (a full disk) stops the run at that write, naming
the file, the directory and the reason, and leaves what was written before
whole: no half-written piece of the failing step, statistics.csv with whole rows.

The full disk is emulated without privileges by a file size limit
(RLIMIT_FSIZE, with SIGXFSZ ignored so that the write fails with EFBIG): 60 kB
lets parameters.prm (44 kB) and the first solution file (39 kB, the undeformed
state) through, and stops the second (118 kB, step 1)."""
import os
import resource
import signal
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    text = (f.read() + sltest.nested_set("Geometry/block/Global refinements", 5) +
            sltest.nested_set("Load stepping/Number of load steps", 3) +
            sltest.nested_set("Output/Output directory", "output"))
os.makedirs(workdir, exist_ok=True)
with open(f"{workdir}/input.prm", "w") as f:
    f.write(text)


def limit_file_size():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (60000, 60000))

#(Open MPI's start-up keeps its shared-memory store in files: the hash store keeps it in memory)
result = subprocess.run([executable, "input.prm"], cwd=workdir, env=dict(sltest.MPI_ENV, PMIX_MCA_gds="hash"),
                        capture_output=True, text=True, timeout=600, preexec_fn=limit_file_size)
log = result.stdout + result.stderr
out = f"{workdir}/output"
check(result.returncode == 1, f"exit code {result.returncode}")
check("cannot write the solution of step 1 (solution_00001.pvtu) into output" in log and
      "File too large" in log,
      "the message names the step, the file and the directory: " +
      next((line for line in log.splitlines() if line.startswith("Error")), "(none)"))
names = os.listdir(out)
check(not any(n.startswith("solution_00001") or n.endswith(".tmp") for n in names),
      f"no half-written file of step 1 is left: {sorted(names)}")
check("solution_00000.0.vtu" in names and "solution_00002.pvtu" not in names,
      "the undeformed state is kept, nothing after the failing write is written")
with open(f"{out}/statistics.csv") as f:
    content = f.read()
check(content.endswith("\n") and len(sltest.read_csv(f"{out}/statistics.csv")) == 0,
      "statistics.csv: whole rows only (the header; step 1 is not recorded)")
with open(f"{out}/solution.pvd") as f:
    pvd = f.read()
check("solution_00000.pvtu" in pvd and "solution_00001" not in pvd, "solution.pvd lists step 0 only")
check.finish()
