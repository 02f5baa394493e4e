#!/usr/bin/python3
"""Bad input: each case exits non-zero with one clear message naming the entry
and what is allowed, and writes no NaN into any output file; more BLAS threads
than the machine or the address-space limit holds are capped with a note."""
import os
import shutil
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    base = f.read().replace("output-patin-elastic", "output")

cases = {
    "unknown entry": (base.replace("set Poisson's ratio = 0.3", "set Poissons ratio = 0.3"),
                      ["Poissons ratio"]),
    "bad value": (base.replace("set Friction coefficient = 0.1", "set Friction coefficient = abc"),
                  ["Friction coefficient", "abc"]),
    "non-positive E": (base.replace("set Young's modulus = 200000", "set Young's modulus = -5"),
                       ["Young's modulus", "> 0"]),
    "zero E": (base.replace("set Young's modulus = 200000", "set Young's modulus = 0"),
               ["Young's modulus", "> 0"]),
    "negative mu": (base.replace("set Friction coefficient = 0.1", "set Friction coefficient = -0.2"),
                    ["Friction coefficient", ">= 0"]),
    "unknown model": (base.replace("set Model = linear elastic", "set Model = rubber"),
                      ["rubber", "linear elastic"]),
    "missing boundary id": (base.replace("set Contact boundary ids = 2", "set Contact boundary ids = 7"),
                            ["Contact boundary ids", "7", "0, 1, 2, 3"]),
    "wrong variable names": (base.replace("x,y,t", "x,t"), ["Variable names", "x,y,t"]),
    "bad r_n": (base.replace("set r_n                  = automatic", "set r_n                  = 0"),
                ["r_n", "> 0"]),
    "softening hardening curve": (
        base.replace("set Model = linear elastic", "set Model = J2 plasticity\n"
                     "  subsection J2 plasticity\n    set Hardening curve = 0:194, 0.1:150\n  end"),
        ["Hardening curve", "150"]),
}
for name, (text, expected) in cases.items():
    out = f"{workdir}/{name.replace(' ', '_')}"
    code, log = sltest.run(executable, text, out, expect_success=False)
    first = log.strip().splitlines()[0] if log.strip() else ""
    check(code != 0, f"{name}: exit code {code}")
    check(all(e in log for e in expected), f"{name}: message names {expected}: {first[:150]}")
    check("Segmentation" not in log and "core dumped" not in log and len(log) < 2000,
          f"{name}: one short message ({len(log)} characters), no crash")

# a step that cannot converge: it is cut and retried, then the run stops
# cleanly with exit code 2, keeping what the converged steps wrote
text = base.replace("set Maximum step cuts    = 5", "set Maximum step cuts    = 2")
text += """
subsection Nonlinear solver
  subsection Newton
    # every Newton loop of the patin needs more (a fixed-point loop that
    # runs out of iterations is folded into Newton instead of failing)
    set Maximum iterations = 1
  end
end
"""
out = f"{workdir}/non_convergence"
code, log = sltest.run(executable, text, out, expect_success=False)
check(code == 2, f"non-convergence: exit code {code}")
check(log.count("cutting the step") == 2 and "did not converge after 2 step cuts" in log,
      "non-convergence: the step is halved twice, then a clear message")
check("cutting the step to 0.025" in log and "with the step 0.025" in log,
      "non-convergence: the log gives the step sizes in full (0.025, not 0.03)")
check(os.path.isfile(f"{out}/output/statistics.csv") and os.path.isfile(f"{out}/output/solution.pvd"),
      "non-convergence: statistics.csv and solution.pvd are kept")

# a material point leaves its admissible range (neo-Hookean block pressed by
# more than its height): the step is cut, then the run stops cleanly, naming J
text = base.replace("set Model = linear elastic", "set Model = neo-Hookean").replace(
    "u0=0.5", "u0=60").replace("set Maximum step cuts    = 5", "set Maximum step cuts    = 1")
text += "\nsubsection Load stepping\n  set Number of load steps = 1\nend\n"
out = f"{workdir}/inadmissible"
code, log = sltest.run(executable, text, out, expect_success=False)
check(code == 2 and "J = det F" in log and "admissible range" in log,
      f"inadmissible state: exit code {code}, the log names J and the admissible range")

# a missing parameter file
result = subprocess.run([executable, f"{workdir}/does-not-exist.prm"], capture_output=True, text=True)
check(result.returncode != 0 and "does-not-exist.prm" in result.stderr,
      f"missing file: exit code {result.returncode}, message: {result.stderr.strip()[:120]}")

# output directories: a shorter run into the directory of a longer one leaves
# none of its files behind; a bad expression stops the run before anything is
# written; a file name taken by a directory, or a directory that cannot be
# created, is named with the entry
short = base.replace("set Global refinements = 4", "set Global refinements = 2")
out = f"{workdir}/reused_directory"
shutil.rmtree(out, ignore_errors=True)  # a rerun starts from an empty directory
sltest.run(executable, short, out)
sltest.run(executable, short.replace("set Number of load steps = 10", "set Number of load steps = 4"),
           out)
names = sorted(os.listdir(f"{out}/output"))
check("profile-00004.csv" in names and "profile-00005.csv" not in names and
      "solution_00005.pvtu" not in names and len(sltest.read_csv(f"{out}/output/statistics.csv")) == 4,
      f"a 4-step run into a 10-step run's directory leaves only its own files ({len(names)} files)")
kept = open(f"{out}/output/parameters.prm").read()
code, log = sltest.run(executable, short.replace("-u0*min", "-uu*min"), out, expect_success=False)
check(code == 1 and "Boundary conditions/Dirichlet 1/Displacement" in log and "uu" in log and
      open(f"{out}/output/parameters.prm").read() == kept and
      sorted(os.listdir(f"{out}/output")) == names,
      f"an undefined name in an expression: exit code {code}, the entry named, nothing written")
os.remove(f"{out}/output/statistics.csv")
os.mkdir(f"{out}/output/statistics.csv")
code, log = sltest.run(executable, short, out, expect_success=False)
check(code == 1 and "Output/Output directory" in log and "statistics.csv is a directory" in log,
      f"statistics.csv taken by a directory: exit code {code}, the entry and the path named")
code, log = sltest.run(executable, short.replace("set Output directory = output",
                                                 f"set Output directory = {out}/input.prm/sub"),
                       out, expect_success=False)
check(code == 1 and "Output/Output directory" in log and "cannot be created" in log,
      f"an output directory under a file: exit code {code}, the entry named")

# the command line: each mistake is named and exits with 1
for arguments, expected in ((["--print-parameters", "7"], "2 or 3"),
                            (["--print-parameters", "x"], "2 or 3"),
                            (["--print-parameters", "2", "3"], "2 or 3"),
                            (["--frobnicate"], "unknown option '--frobnicate'"),
                            (["a.prm", "b.prm"], "one parameter file at most"),
                            (["--threads", "0", "a.prm"], "--threads N"),
                            (["--threads"], "--threads N"),
                            (["--resume"], "--resume needs the parameter file"),
                            (["--inf-sup", "x", "a.prm"], "--inf-sup N"),
                            # empty, negative, non-numeric and overflowing numbers: the option
                            # and its range named, no raw "stoi"
                            (["--threads", "", "a.prm"], "--threads N: N must be an integer from 1 to 256"),
                            (["--threads", "abc", "a.prm"], "--threads N: N must be an integer from 1 to 256"),
                            (["--threads", "-1", "a.prm"], "--threads N: N must be an integer from 1 to 256"),
                            (["--threads", "9" * 25, "a.prm"], "--threads N: N must be an integer from 1 to 256"),
                            (["--inf-sup", "", "a.prm"], "--inf-sup N: N must be an integer from 1 to 10"),
                            (["--inf-sup", "-1", "a.prm"], "--inf-sup N: N must be an integer from 1 to 10"),
                            (["--inf-sup", "9" * 25, "a.prm"], "--inf-sup N: N must be an integer from 1 to 10"),
                            (["--inf-sup", "0", "a.prm"], "--inf-sup N: N must be an integer from 1 to 10"),
                            (["--print-parameters", ""], "2 or 3")):
    result = subprocess.run([executable] + arguments, capture_output=True, text=True)
    check(result.returncode == 1 and expected in result.stderr and "stoi" not in result.stderr,
          f"command line {' '.join(arguments)}: exit code {result.returncode}, "
          f"message names '{expected}'")

# --threads 256 under an address-space limit of 8 GB: the buffers OpenBLAS gives each thread did
# not fit and its allocator retried them for ever; the threads are capped to the processors a
# rank has and to the address space left, with a note (a limit too tight for one buffer is
# refused with a message)
# (not under AddressSanitizer, whose shadow memory needs more address space than any such limit)
out = f"{workdir}/threads_256"
os.makedirs(out, exist_ok=True)
with open(f"{out}/input.prm", "w") as f:
    f.write(short)
if sltest.address_sanitized(executable):
    print("SKIP --threads 256 under ulimit -v 8000000: AddressSanitizer cannot start under it")
else:
    try:
        result = subprocess.run(
            ["bash", "-c", f"ulimit -v 8000000; exec {executable} --threads 256 input.prm"],
            cwd=out, capture_output=True, text=True, timeout=120)
        code, log = result.returncode, result.stdout + result.stderr
    except subprocess.TimeoutExpired:
        code, log = None, ""
    check(code == 0 and "BLAS/OpenMP thread(s) per rank are used" in log,
          f"--threads 256 under ulimit -v 8000000: exit code {code} (None: still running after 120 s), "
          f"the threads capped with a note: {log.strip().splitlines()[0][:150] if log.strip() else ''}")

# a run out of memory (a 2D block refined 11 times under an address-space limit of 3 GB) says
# so in words and what the program was doing, not std::bad_alloc; where its size estimate
# (~80 GB) exceeds the machine's memory it is refused before the mesh is refined, naming the
# entry (Geometry::SizeCheck)
out = f"{workdir}/out_of_memory"
os.makedirs(out, exist_ok=True)
with open(f"{out}/input.prm", "w") as f:
    f.write("subsection Geometry\n  set Model = block\n  subsection block\n"
            "    set Global refinements = 11\n  end\nend\n" + sltest.QUIET_OUTPUT)
if sltest.address_sanitized(executable):
    print("SKIP out of memory under ulimit -v 3000000: AddressSanitizer cannot start under it")
else:
    result = subprocess.run(["bash", "-c", f"ulimit -v 3000000; exec {executable} input.prm"],
                            cwd=out, capture_output=True, text=True, timeout=300)
    check(result.returncode == 1 and ("Error: out of memory while running the load steps" in result.stderr
                                      or "Geometry/block/Global refinements = 11: the refined mesh would "
                                         "need" in result.stderr)
          and "bad_alloc" not in result.stderr,
          f"out of memory: exit code {result.returncode}, {result.stderr.strip()[:150]}")

# no NaN in any CSV written (the .vtu files are compressed; the ParaView test
# reads them and checks their arrays for NaN)
nan_files = []
for root, _, files in os.walk(workdir):
    for name in files:
        if name.endswith(".csv"):
            with open(os.path.join(root, name), errors="replace") as f:
                if "nan" in f.read().lower():
                    nan_files.append(name)
check(not nan_files, f"no NaN in any output file {nan_files}")
# input that runs but cannot be what the user meant: a warning in the log
# (exit 0), and none for the scene as shipped
for name, text, expect in (
        ("obstacle normal into the body", short.replace("set Normal = 0, 1", "set Normal = 0, -1"),
         "lie behind the obstacle's surface"),
        ("contact surface on a side face", short.replace("set Contact boundary ids = 2",
                                                         "set Contact boundary ids = 0"),
         "contact points was in contact in any load step"),
        ("the scene as shipped", short, None)):
    code, log = sltest.run(executable, text, f"{workdir}/warning", expect_success=False)
    warned = "WARNING" in log and (expect is None or expect in log)
    check(code == 0 and (warned if expect else "WARNING" not in log),
          f"{name}: exit code {code}, " + ("warned" if "WARNING" in log else "no warning"))

check.finish()
