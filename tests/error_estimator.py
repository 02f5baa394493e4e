#!/usr/bin/python3
"""The residual error estimate (doc/formulation.md, "Error estimate").

Checks:
- exact discrete solutions have a zero estimate: a block pressed by a uniform
  pressure onto a rigid plane (the displacement is linear, in every pair's
  space), 2D with hanging nodes on the contact face and 3D, Q1/P1 and Q2/P1:
  the estimate is below 1e-6 of the solution's energy norm (round-off; a
  discretisation error would be of order 1e-2 on these meshes);
- on Hertz (a half disc on a rigid plane, refined uniformly three times) the
  estimate decreases at each refinement, and its effectivity index against
  the last cycle (`Errors against the last cycle`, cycles at least two
  refinements from it) lies between 1 and 20 and varies by less than a factor
  3;
- `Criterion = estimator` refines where the estimate is largest: the estimate
  falls below that of uniform refinement with fewer DoFs; with `Marking =
  bulk` the pressure error falls below that of fixed-number marking with
  fewer DoFs;
- the pressure estimate is zero for the uniform pressure, and within a
  factor 2 of the true error against Hertz on the uniform and the graded
  meshes;
- on 2 MPI ranks a J2 plastic body (history carried to the ghost cells) has
  the 1-rank estimates (energy and pressure) to 1e-8;
- the VTU carries the cell field error_indicator_sqrtNmm, finite and not all
  zero; statistics.csv and run_summary.csv carry the estimate.
"""
import math
import os
import sys
import sltest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
from hertz_errors import hertz_errors  # noqa: E402

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()

# --- exact discrete solutions ---------------------------------------------
for dim, pair, local in ((2, "Q1/P1", 2), (2, "Q2/P1", 1), (3, "Q1/P1", 0)):
    variables = "x,y,t" if dim == 2 else "x,y,z,t"
    text = sltest.scene(
        "pressed_block", DIM=dim, MU=0, SLIDE=0, NU=0.3, QUADRATURE="Gauss-Lobatto",
        SUBDIVISIONS="2, 1" if dim == 2 else "2, 1, 1", REFINEMENTS=2 if dim == 2 else 1,
        TANGENTIAL_ID=0, COMPONENTS="x", SLIDE_EXPRESSION="0; 0" if dim == 2 else "0; 0; 0",
        VARIABLES=variables, PRESSURE=100, PAIR=pair, LOCAL=local,
        CENTER="0, 0" if dim == 2 else "0, 0, 0", RADIUS=30,
        TRACTION_EXPRESSION="0; -p*t" if dim == 2 else "0; 0; -p*t", STEPS=1, VTU="false")
    name = f"uniform pressure {dim}D {pair}" + (f", {local} local refinements" if local else "")
    out = os.path.join(workdir, name.replace(" ", "_").replace("/", "").replace(",", ""))
    if sltest.run_checked(executable, text, out, check, name):
        row = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]
        check(row["energy_norm_sqrtNmm"] > 0 and row["estimated_relative_error"] < 1e-6,
              f"{name}: estimate {row['estimated_relative_error']:.1e} of the energy norm "
              f"{row['energy_norm_sqrtNmm']:.3f} sqrt(N mm) (exact solution)")
        check(row["estimated_pressure_error"] < 1e-6,
              f"{name}: pressure estimate {row['estimated_pressure_error']:.1e} (the recovered "
              "stress is exact for a uniform one)")

# --- Hertz: decrease and effectivity ---------------------------------------
hertz = sltest.coarse_hertz()


def hertz_cycles(name, criterion, cycles, fraction=0.3, marking="fixed number"):
    text = hertz + f"""
subsection Adaptive refinement
  set Cycles = {cycles}
  set Criterion = {criterion}
  set Refined fraction = {fraction}
  set Marking = {marking}
  set Errors against the last cycle = true
end
"""
    out = os.path.join(workdir, name)
    if not sltest.run_checked(executable, text, out, check, name):
        return None, None
    output = os.path.join(out, "output")
    return (sltest.read_csv(os.path.join(output, "refinement_cycles.csv")),
            sltest.read_csv(os.path.join(output, "cycle_errors.csv")))


cycles, errors = hertz_cycles("hertz_uniform", "uniform", 3)
if cycles:
    estimates = [row["estimated_error_sqrtNmm"] for row in cycles]
    check(all(b < 0.75 * a for a, b in zip(estimates, estimates[1:])),
          "Hertz, uniform refinement: the estimate decreases at each refinement: "
          + " > ".join(f"{e:.1f}" for e in estimates))
    indices = [row["effectivity_index"] for row in errors if row["cycle"] <= len(cycles) - 3]
    check(len(indices) >= 2 and min(indices) > 1 and max(indices) < 20 and max(indices) < 3 * min(indices),
          "Hertz: effectivity index against the last cycle " + ", ".join(f"{i:.2f}" for i in indices))
    rows = sltest.read_csv(os.path.join(workdir, "hertz_uniform", "output", "run_summary.csv"))
    check(abs(rows[0]["estimated_error_sqrtNmm"] - estimates[-1]) <= 1e-6 * estimates[-1]
          and rows[0]["peak_memory_MiB"] > 0,
          "run_summary.csv: the last cycle's estimate and the peak memory")

adaptive, _ = hertz_cycles("hertz_estimator", "estimator", 3, fraction=0.2)


def true_pressure_errors(name, rows):
    """Each cycle's true pressure error against Hertz (with the run's force)."""
    return sltest.cycle_pressure_errors(os.path.join(workdir, name, "output"), rows, "surface_l2_error")


def pressure_effectivity(name, rows):
    """Each cycle's pressure estimate against its true error."""
    return [row["estimated_pressure_error"] / e for row, e in zip(rows, true_pressure_errors(name, rows))]


bulk, _ = hertz_cycles("hertz_bulk", "estimator", 6, fraction=0.5, marking="bulk")
if adaptive and bulk:
    # bulk marking refines only where the estimate concentrates (the contact
    # zone's edge and the stress below it): less error per DoF than refining
    # a fixed fraction of the cells
    fixed_errors = true_pressure_errors("hertz_estimator", adaptive)
    bulk_errors = true_pressure_errors("hertz_bulk", bulk)
    last = len(bulk) - 1
    check(bulk[last]["displacement_dofs"] < adaptive[-1]["displacement_dofs"]
          and bulk_errors[last] < fixed_errors[-1],
          f"Marking = bulk: pressure error {bulk_errors[last]:.4f} with {bulk[last]['displacement_dofs']:.0f} DoFs, "
          f"below fixed number's {fixed_errors[-1]:.4f} with {adaptive[-1]['displacement_dofs']:.0f}")

# the recovered pressure is one order more accurate than lambda_n, so the
# estimate tends to the error (measured 0.85-1.6 over 14 graded meshes,
# doc/error_estimator.md); the one-sided traction it replaced gave 3-6 here
for name, rows in (("hertz_uniform", cycles), ("hertz_estimator", adaptive)):
    if rows:
        ratios = pressure_effectivity(name, rows)
        check(all(0.5 < r < 2 for r in ratios),
              f"{name}: the pressure estimate against the true error within a factor 2: "
              + ", ".join(f"{r:.2f}" for r in ratios))
if cycles and adaptive:
    # the uniform curve interpolated at the adaptive mesh's DoFs (log-log)
    last = adaptive[-1]
    dofs = [row["displacement_dofs"] for row in cycles]
    k = max(i for i in range(len(dofs) - 1) if dofs[i] <= last["displacement_dofs"])
    slope = (math.log(cycles[k + 1]["estimated_error_sqrtNmm"] / cycles[k]["estimated_error_sqrtNmm"])
             / math.log(dofs[k + 1] / dofs[k]))
    uniform = cycles[k]["estimated_error_sqrtNmm"] * (last["displacement_dofs"] / dofs[k]) ** slope
    check(last["estimated_error_sqrtNmm"] < uniform,
          f"Criterion = estimator: estimate {last['estimated_error_sqrtNmm']:.1f} with "
          f"{last['displacement_dofs']:.0f} DoFs, below uniform refinement's {uniform:.1f} at as many DoFs")

# --- an accuracy target on the contact pressure -----------------------------

target = 0.05
out = os.path.join(workdir, "hertz_target")
text = hertz + f"""
subsection Adaptive refinement
  set Cycles = 20
  set Criterion = estimator
  set Target pressure error = {target}
end
"""
if sltest.run_checked(executable, text, out, check, "Hertz, Target pressure error"):
    output = os.path.join(out, "output")
    cycles = sltest.read_csv(os.path.join(output, "refinement_cycles.csv"))
    met = sltest.read_csv(os.path.join(output, "target_error.csv"))[0]
    # the estimate divided by its smallest effectivity, 0.8 (RefinementCycles::pressure_error_bound)
    estimates = [row["estimated_pressure_error"] / 0.8 for row in cycles]
    check(met["met"] == 1 and estimates[-1] <= target and all(e > target for e in estimates[:-1])
          and met["cycle"] == len(cycles) - 1,
          f"Target {target}: the cycles stop at the first bound (estimate / 0.8) below it: " +
          ", ".join(f"{e:.4f}" for e in estimates))
    last = len(cycles) - 1
    check(not os.path.exists(os.path.join(output, f"cycle-{last}"))
          and all(os.path.isdir(os.path.join(output, f"cycle-{k}")) for k in range(last))
          and os.path.exists(os.path.join(output, "statistics.csv")),
          "Target: the output directory holds the last cycle, the earlier ones are in cycle-N/")
    force = sltest.read_csv(os.path.join(output, "statistics.csv"))[-1]["normal_force_N"]
    true_error = hertz_errors(2, force, sltest.last_profile(output))["l2_error"]
    check(target / 3 < true_error < 3 * target,
          f"Target {target}: the true pressure error against Hertz {true_error:.4f} is within a factor 3 of it")
code, log = sltest.run(executable, hertz + "\nsubsection Adaptive refinement\n  set Target error = 0.1\nend\n",
                       os.path.join(workdir, "target_without_cycles"), expect_success=False)
check(code == 1 and "Target error" in log and "Cycles" in log,
      f"a target without Cycles: exit {code}, the message names the entries")

# --- 1 and 2 ranks, a history-dependent material ---------------------------
plastic = hertz + """
subsection Material
  set Model = J2 plasticity
  subsection J2 plasticity
    set Young's modulus = 200000
    set Poisson's ratio = 0.3
    set Hardening curve = 0:400, 1:900
  end
end
subsection Output
  set Write vtu = true
end
"""
results = {}
for ranks in (1, 2):
    out = os.path.join(workdir, f"plastic-np{ranks}")
    code, log = sltest.run(executable, plastic.replace("output-hertz-cylinder", "output"), out, ranks=ranks,
                           expect_success=False)
    check(code == 0, f"J2 Hertz on {ranks} rank(s): exit code {code}")
    if code == 0:
        results[ranks] = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    else:
        print(log[-2000:])
if len(results) == 2:
    for column in ("estimated_error_sqrtNmm", "estimated_pressure_error"):
        worst = max(abs(a[column] - b[column]) / a[column] for a, b in zip(results[1], results[2]))
        check(worst < 1e-8, f"J2 Hertz: {column} on 2 ranks equals 1 rank's (largest difference {worst:.1e})")
    log_has_plasticity = max(r["estimated_error_sqrtNmm"] for r in results[1]) > 0
    check(log_has_plasticity, "J2 Hertz: a non-zero estimate")

# the cell field of the VTU
try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    output = os.path.join(workdir, "plastic-np1", "output")
    pieces = sorted(p for p in os.listdir(output) if p.endswith(".vtu"))
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(output, pieces[-1]))
    reader.Update()
    # DataOut writes cell data as point values of each cell's own patch
    array = reader.GetOutput().GetPointData().GetArray("error_indicator_sqrtNmm")
    values = vtk_to_numpy(array) if array is not None else []
    check(len(values) > 0 and all(math.isfinite(v) and v >= 0 for v in values) and max(values) > 0,
          f"VTU: error_indicator_sqrtNmm on {len(values)} points, finite, largest {max(values, default=0):.3g}")
except ImportError:
    check(False, "python3-vtk9 is needed to read the VTU")
check.finish()
