#!/usr/bin/python3
"""The same input gives the same loop counts and the same results whatever the
BLAS kernel (the CPU) and the thread count (doc/formulation.md, "Newton
stopping criterion").

The J2 patin (prm/patin_elastoplastic.prm on a coarser mesh) is the scene that
showed it: at the onset of sliding its Newton path is sensitive, and before the
fix its Newton iterations went from 114 to 125 with 0 to 2 step cuts between
kernels. It runs here
- with the program's own thread setting and conflicting environment variables
  (OPENBLAS_NUM_THREADS=2, OMP_NUM_THREADS=2), which the program must override;
- with `Linear solver/Threads per rank = 2` (a different blocking of the dense
  kernels);
- with OpenBLAS forced to the kernels of other CPU generations
  (OPENBLAS_CORETYPE), which is what a machine that did not write the
  references runs.
Every run must give the same iterations.csv counts as the first run (every
column but the residuals: exact, since each decision the loops take is now
away from round-off) and the same assemblies per step, and forces equal to
1e-10 relative (the runs end with scaled residuals near 1e-12)."""
import csv
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
with open(os.path.join(root, "prm", "patin_elastoplastic.prm")) as f:
    text = f.read().replace("set Global refinements = 4", "set Global refinements = 3")

variants = {
    "default": ({}, ""),
    "environment_threads": ({"OPENBLAS_NUM_THREADS": "2", "OMP_NUM_THREADS": "2"}, ""),
    "two_threads": ({}, sltest.nested_set("Linear solver/Threads per rank", 2)),
}

# The instruction sets each forced OpenBLAS kernel executes (OpenBLAS's
# cpuid tables): a kernel the processor cannot run dies with SIGILL, so it is
# skipped with a message, not counted as a failure.
kernels = {
    "Prescott": {"sse3"},
    "Sandybridge": {"avx"},
    "SkylakeX": {"avx512f", "avx512bw", "avx512dq", "avx512vl", "avx512cd"},
}
cpu_flags = sltest.cpu_flags()
for kernel, needs in kernels.items():
    missing = sorted(needs - cpu_flags)
    if missing:
        print(f"SKIP kernel_{kernel.lower()}: this processor lacks {', '.join(missing)}")
        continue
    variants["kernel_" + kernel.lower()] = ({"OPENBLAS_CORETYPE": kernel}, "")


def counts(out):
    with open(os.path.join(out, "iterations.csv")) as f:
        rows = list(csv.DictReader(f))
    return [tuple(v for k, v in r.items() if "residual" not in k) for r in rows]


results = {}
for name, (environment, extra) in variants.items():
    out = f"{workdir}/{name}"
    if sltest.run_checked(executable, text + extra, out, check, name, environment):
        results[name] = (counts(out + "/output"), sltest.read_csv(out + "/output/statistics.csv"))

reference_counts, reference_rows = results.get("default", (None, None))
for name, (loop_counts, rows) in results.items():
    if name == "default" or reference_rows is None:
        continue
    check(loop_counts == reference_counts,
          f"{name}: loop counts equal the default run's ({len(loop_counts)} inner loops)")
    check([r["assemblies"] for r in rows] == [r["assemblies"] for r in reference_rows],
          f"{name}: assemblies per step equal ({sum(r['assemblies'] for r in rows):.0f})")
    worst = 0.
    for a, b in zip(rows, reference_rows):
        scale = max(abs(b["normal_force_N"]), 1.)
        for key in ("normal_force_N", "tangential_force_N", "contact_force_x_N",
                    "contact_force_y_N"):
            worst = max(worst, abs(a[key] - b[key]) / scale)
    check(len(rows) == len(reference_rows) and worst <= 1e-10,
          f"{name}: forces equal to {worst:.1e} relative (<= 1e-10)")
check.finish()
