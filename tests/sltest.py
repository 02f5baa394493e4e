"""Helpers for the scene tests: run the program on a parameter file and read its CSV output."""
import csv
import math
import os
import random
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
import run_output  # noqa: E402

MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")


def run(executable, prm_text, workdir, ranks=1, expect_success=True, timeout=1200,
        environment=None):
    """Write prm_text to workdir/input.prm, run the program there (with the variables of
    `environment` added to its environment), return (exit code, stdout+stderr).
    Raises subprocess.TimeoutExpired after `timeout` seconds."""
    os.makedirs(workdir, exist_ok=True)
    prm = os.path.join(workdir, "input.prm")
    with open(prm, "w") as f:
        f.write(prm_text)
    command = [executable, "input.prm"]
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
    result = subprocess.run(command, cwd=workdir, env=dict(MPI_ENV, **(environment or {})),
                            capture_output=True, text=True,
                            timeout=timeout)
    output = result.stdout + result.stderr
    if expect_success and result.returncode != 0:
        print(output)
        raise SystemExit(f"FAIL: the program exited with {result.returncode} in {workdir}")
    return result.returncode, output


def address_sanitized(executable):
    """Whether the executable is built with AddressSanitizer (contrib/sanitize.sh links libasan
    into it). ASan reserves terabytes of address space at start-up, so a run under an
    address-space limit set before it starts (ulimit -v) cannot start."""
    try:
        with open(executable, "rb") as f:
            return b"libasan.so" in f.read()
    except OSError:
        return False


def seed_random(variable, what):
    """Seed `random` from the environment variable `variable`, or from the clock, and print the
    seed, so that a failing draw can be made again; `what` says what is drawn."""
    seed = int(os.environ.get(variable, time.time_ns() % 1000003))
    print(f"{what} drawn with {variable}={seed}")
    random.seed(seed)
    return seed


def cpu_flags():
    """The instruction-set flags of this processor (/proc/cpuinfo), an empty set where
    the file does not say."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def nested_set(path, value):
    """'Section/Sub/Entry', value -> the prm text setting it in nested subsections."""
    *sections, entry = path.split("/")
    return ("\n" + "".join(f"subsection {s}\n" for s in sections) + f"set {entry} = {value}\n" +
            "end\n" * len(sections))


# the geometry, friction and status loops all folded into the generalized Newton
GENERALIZED_NEWTON = "".join(nested_set(f"Nonlinear solver/{loop}/Method", "newton")
                             for loop in ("Geometry loop", "Friction loop", "Status loop"))

# the half ball's symmetry planes (Geometry/half ball/Symmetry planes = true) held in their
# normal direction, by dimension
SYMMETRY_PLANES = {2: """subsection Boundary conditions
  subsection Dirichlet symmetry x
    set Boundary id = 4
    set Components  = x
  end
end
""", 3: """subsection Boundary conditions
  subsection Dirichlet symmetry x
    set Boundary id = 4
    set Components  = x
  end
  subsection Dirichlet symmetry y
    set Boundary id = 5
    set Components  = y
  end
end
"""}

QUIET_OUTPUT = "\nsubsection Output\n  set Output directory = output\n  set Write vtu = false\nend\n"


def run_checked(executable, prm_text, workdir, check, name, environment=None, ranks=1):
    """Run prm_text in workdir (output in workdir/output, no vtu) on `ranks` ranks; check that
    it exits with 0, printing the end of its log if not; return whether it did."""
    code, log = run(executable, prm_text + QUIET_OUTPUT, workdir, ranks=ranks, expect_success=False,
                    environment=environment)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-3000:])
    return code == 0


def scene(name, **replacements):
    """The text of tests/scenes/<name>.prm with `@KEY@` placeholders replaced."""
    with open(os.path.join(os.path.dirname(__file__), "scenes", name + ".prm")) as f:
        text = f.read()
    defaults = {"PAIR": "Q1/P1", "LOCAL": 0, "RADIUS": 0, "CELL_SHAPE": "hypercube",
                "CENTER": "0, 0" if str(replacements.get("DIM", 2)) == "2" else "0, 0, 0"}
    for key, value in {**defaults, **replacements}.items():
        text = text.replace("@" + key + "@", str(value))
    return text


def coarse_hertz():
    """prm/hertz_cylinder.prm on a coarse mesh (2 global, 2 local refinements): the start of
    the refinement-cycle tests."""
    return read_prm(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                                 "hertz_cylinder.prm")) + """
subsection Geometry
  subsection half ball
    set Global refinements = 2
    set Local refinements = 2
  end
end
"""


def gmsh_mesh(dim, mesh_file, refinements=None):
    """The dimension and the Geometry subsection of the Gmsh mesh (or .geo) `mesh_file`,
    refined `refinements` times globally where given."""
    refined = "" if refinements is None else f"    set Global refinements = {refinements}\n"
    return f"""set Dimension = {dim}
subsection Geometry
  set Model = gmsh
  subsection gmsh
    set Mesh file = {mesh_file}
{refined}  end
end
"""


def linear_elastic(youngs_modulus, poissons_ratio, formulation=None):
    """The Material subsection of one linear elastic material, with the volumetric
    `formulation` (F-bar, ...) where given."""
    volumetric = "" if formulation is None else f"  set Volumetric formulation = {formulation}\n"
    return f"""subsection Material
  set Model = linear elastic
{volumetric}  subsection linear elastic
    set Young's modulus = {youngs_modulus}
    set Poisson's ratio = {poissons_ratio}
  end
end
"""


def coulomb_contact(entries, friction_coefficient):
    """The Contact subsection: `entries` (its own `set` lines, indented), then Coulomb friction
    with `friction_coefficient`."""
    return f"""subsection Contact
{entries}  subsection Friction law
    set Model = Coulomb
    subsection Coulomb
      set Friction coefficient = {friction_coefficient}
    end
  end
end
"""


def cylinder_on_block_geo(arc=13, top=18, side=6, h=3):
    """tests/scenes/cylinder_on_block.geo (a half cylinder, R = 10 mm, touching a block 30 x 10
    mm at one point, non-matching quadrilaterals) with `arc` nodes on each quarter arc, `top`
    along the block's top, `side` along its sides and cells at most `h` mm."""
    with open(os.path.join(os.path.dirname(__file__), "scenes", "cylinder_on_block.geo")) as f:
        geo = f.read()
    for key, value in (("ARC", arc), ("TOP", top), ("SIDE", side), ("H", h)):
        geo = geo.replace(f"@{key}@", str(value))
    return geo


def cylinder_on_block_prm(mesh_file, press, steps, contact=""):
    """The scene of cylinder_on_block_geo() in `mesh_file`: linear elastic (E = 20000 MPa,
    nu = 0.3), the cylinder's arc the slave, the block's top the master, Coulomb mu = 0.3,
    the block's bottom held; `press`: the condition subsection(s) on the cylinder's top
    (cyl_top); `contact`: further Contact entries; `steps` load steps."""
    entries = "  set Contact boundary ids = cyl_contact\n  set Master boundary ids  = blk_contact\n"
    return (gmsh_mesh(2, mesh_file) + linear_elastic(20000, 0.3) + coulomb_contact(entries + contact, 0.3) +
            f"""subsection Boundary conditions
  subsection Dirichlet base
    set Boundary id = blk_bottom
    set Components  = x, y
  end
{press}end
subsection Load stepping
  set Number of load steps = {steps}
end
""")


def two_blocks(dim, mesh, friction, refinements=None):
    """tests/scenes/<mesh> (two blocks): the geometry (refined once in 2D, not in 3D unless
    refinements says), E = 1000 MPa, nu = 0.3, and the contact between the blocks' surfaces
    upper_bottom (slave) and lower_top (master) with Coulomb friction."""
    scenes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes")
    if refinements is None:
        refinements = 1 if dim == 2 else 0
    return (gmsh_mesh(dim, f"{scenes}/{mesh}", refinements) + linear_elastic(1000, 0.3) +
            coulomb_contact("""  set Contact boundary ids = upper_bottom
  set Master boundary ids = lower_top
  set r_n = automatic
  set r_t = automatic
  set Contact quadrature = Gauss
""", friction))


def blocks_pressed_and_slid(press, onset, steps):
    """For two_blocks(3, ...): the lower block's bottom held, the upper's top pressed down by
    `press` mm until t = onset, then slid 1 mm along x until t = 1, in `steps` load steps."""
    return f"""subsection Boundary conditions
  subsection Dirichlet 1
    set Boundary id = lower_bottom
    set Components = x, y, z
  end
  subsection Dirichlet 2
    set Boundary id = upper_top
    set Components = x, y, z
    subsection Displacement
      set Function expression = if(t < {onset}, 0, 1*(t - {onset})/{1 - onset}); 0; -{press}*min(t/{onset}, 1)
      set Variable names = x,y,z,t
    end
  end
end
subsection Load stepping
  set End time = 1
  set Number of load steps = {steps}
  set Maximum step cuts = 5
end
"""


def read_prm(path):
    """The text of a parameter file, with the relative mesh files it names made absolute (the
    tests run it from another directory)."""
    with open(path) as f:
        text = f.read()
    directory = os.path.dirname(os.path.abspath(path))
    return re.sub(r"(set Mesh file\s*=\s*)(\S+)",
                  lambda m: m.group(1) + (m.group(2) if os.path.isabs(m.group(2))
                                          else os.path.join(directory, m.group(2))), text)


def read_csv(path):
    """The rows of a CSV file of numbers, as dicts of floats. A plane strain run names its force
    columns per unit thickness (`..._N_per_mm`); each is also given under its 3D name
    (`..._N`, contrib/run_output.py's force_aliases()), so that a check reads both dimensions
    alike (tests/column_units.py checks the names themselves)."""
    with open(path) as f:
        return [run_output.force_aliases({k: float(v) for k, v in row.items()}) for row in csv.DictReader(f)]


def read_vtu(path):
    """The vtkUnstructuredGrid of a .vtu file (python3-vtk9; ImportError without it)."""
    import vtk
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def last_profile(outdir):
    profiles = sorted(p for p in os.listdir(outdir) if p.startswith("profile-"))
    return read_csv(os.path.join(outdir, profiles[-1]))


def cycle_pressure_errors(output, rows, measure="l2_error"):
    """Each refinement cycle's (rows of refinement_cycles.csv in output) error of the last
    load step's contact pressure against Hertz with the run's force (contrib/hertz_errors.py)."""
    from hertz_errors import hertz_errors
    errors = []
    for row in rows:
        where = os.path.join(output, f"cycle-{int(row['cycle'])}")
        where = where if os.path.isdir(where) else output
        force = read_csv(os.path.join(where, "statistics.csv"))[-1]["normal_force_N"]
        errors.append(hertz_errors(2, force, last_profile(where))[measure])
    return errors


class Checker:
    """Collects named checks, prints each, and exits non-zero if any failed."""

    def __init__(self):
        self.failures = 0

    def __call__(self, ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        self.failures += not ok

    def finish(self):
        print("FAILED" if self.failures else "PASSED")
        sys.exit(1 if self.failures else 0)


def check_hertz_sequence(check, runs, name, lowest_order):
    """Checks of Hertz runs on three nested meshes (contrib/hertz_errors.py's dicts, coarse to
    fine): the L2 and peak pressure errors fall, the L2 order over the two refinements lies in
    (lowest_order, 1.5) (about 1 asymptotically: the square-root edge of the pressure; level to
    level it varies with where the edge falls between two nodes), and the half-width, that of the
    last node in contact, is within one contact cell of Hertz's (h / a)."""
    for key, title in (("l2_error", "L2 error of the pressure"), ("peak_error", "peak pressure error")):
        values = [abs(r[key]) for r in runs]
        check(values[0] > values[1] > values[2], f"{name}: the {title} falls, "
              + ", ".join(f"{v:.2%}" for v in values))
    order = math.log(runs[0]["l2_error"] / runs[2]["l2_error"]) / math.log(runs[0]["h_mm"] / runs[2]["h_mm"])
    check(lowest_order < order < 1.5, f"{name}: L2 order {order:.2f} in h over two refinements")
    for r in runs:
        check(abs(r["half_width_error"]) <= r["h_mm"] / r["a_hertz_mm"],
              f"{name}, h = {r['h_mm']:.3f} mm: half-width error {abs(r['half_width_error']):.2%} "
              f"<= h / a = {r['h_mm'] / r['a_hertz_mm']:.2%}")
