#!/usr/bin/python3
"""The PVD time series of a run on two MPI ranks loads in ParaView (pvpython)
with every field the output promises (tests/check_pvd_fields.py)."""
import os
import shutil
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    text = f.read().replace("output-patin-elastic", "output")
text = text.replace("set Global refinements = 4", "set Global refinements = 2")
text = text.replace("set Number of load steps = 10", "set Number of load steps = 4")
sltest.run(executable, text, workdir, ranks=2)
pvpython = shutil.which("pvpython")
check(pvpython is not None, "pvpython is installed (package python3-paraview)")
if pvpython:
    script = os.path.join(os.path.dirname(__file__), "check_pvd_fields.py")
    result = subprocess.run([pvpython, script, os.path.join(workdir, "output"), "2"],
                            capture_output=True, text=True, timeout=600)
    print(result.stdout + result.stderr)
    check(result.returncode == 0, "the PVD loads in ParaView with the promised fields")
check.finish()
