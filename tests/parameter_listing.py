#!/usr/bin/python3
"""`--print-parameters [2|3]` lists every entry with its default: the listing is a parameter
file of its dimension, and run as it is, it runs there (issue 50: the 3D listing started with
`set Dimension = 2`, and the program refused its own 3D defaults)."""
import os
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
os.makedirs(workdir, exist_ok=True)
for dim in (2, 3):
    listing = subprocess.run([executable, "--print-parameters", str(dim)], capture_output=True,
                             text=True)
    check(listing.returncode == 0, f"--print-parameters {dim}: exit code {listing.returncode}")
    check(f"set Dimension = {dim}" in listing.stdout,
          f"--print-parameters {dim}: the listing sets Dimension = {dim}")
    code, log = sltest.run(executable, listing.stdout, os.path.join(workdir, f"{dim}d"),
                           expect_success=False, timeout=600)
    check(code == 0, f"the {dim}D listing run as it is: exit code {code}")
    if code != 0:
        print(log[-2000:])
    check(f"stabilized_lagrangian: {dim}D," in log, f"the {dim}D listing runs in {dim}D")
check.finish()
