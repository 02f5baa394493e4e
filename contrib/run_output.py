#!/usr/bin/python3
"""Reading a run's output directory (imported by the contrib/ tools that read a run's files).

The names of the output's CSV columns and VTU fields of the previous output schema
(CHANGELOG.md) are read under the current ones too: current_names(), current_vtu_names().

The parameters the run used (parameters.prm, in the directory or, for the
cycle-N/ directories of adaptive refinement, the one above), the rigid
obstacle and the friction law they define, the load steps of solution.pvd and
of the profile-NNNNN.csv files. Standard library only: render_pvd.py runs it
under ParaView's Python."""
import csv
import math
import os
import re
import sys


class OutputError(Exception):
    """The output directory does not hold what was asked for; the message says what it holds."""


def parameters_path(output_dir):
    """parameters.prm of the run that wrote output_dir, or None."""
    for directory in (output_dir, os.path.dirname(os.path.abspath(output_dir))):
        path = os.path.join(directory, "parameters.prm")
        if os.path.isfile(path):
            return path
    return None


def read_parameters(path):
    """{'Section/Sub/Entry': value} of a parameter file in deal.II's format."""
    values, sections, pending = {}, [], ""
    with open(path) as f:
        for raw in f:
            # '#' starts a comment unless escaped; a trailing backslash continues the line
            line = pending + re.sub(r"(?<!\\)#.*", "", raw.rstrip("\n")).replace("\\#", "#")
            if line.rstrip().endswith("\\"):
                pending = line.rstrip()[:-1] + " "
                continue
            pending = ""
            words = line.strip()
            if words.startswith("subsection "):
                sections.append(words[len("subsection "):].strip())
            elif words == "end":
                if sections:
                    sections.pop()
            elif words.startswith("set "):
                name, _, value = words[len("set "):].partition("=")
                values["/".join(sections + [name.strip()])] = value.strip()
    return values


def run_parameters(output_dir):
    """The parameters of the run that wrote output_dir ({} if it has no parameters.prm)."""
    path = parameters_path(output_dir)
    return read_parameters(path) if path else {}


def _vector(text, dim, entry):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != dim:
        raise OutputError(f"{entry} = '{text}' is not {dim} comma-separated numbers")
    return values + [0.0] * (3 - dim)


def rigid_obstacle(parameters):
    """The rigid obstacle as a dict: model 'plane' with point and unit normal, or 'ball' with
    center and radius (3-vectors, z = 0 in 2D); None when the master is a second deformable
    body (Contact/Master boundary ids) or the run's parameters are unknown."""
    if not parameters or parameters.get("Contact/Master boundary ids", "").strip():
        return None
    dim = int(parameters.get("Dimension", "2"))
    model = parameters.get("Obstacle/Model", "plane")
    if model == "plane":
        normal = _vector(parameters["Obstacle/plane/Normal"], dim, "Obstacle/plane/Normal")
        length = math.sqrt(sum(n * n for n in normal))
        return {"model": "plane", "point": _vector(parameters["Obstacle/plane/Point"], dim, "Obstacle/plane/Point"),
                "normal": [n / length for n in normal]}
    if model == "ball":
        return {"model": "ball", "center": _vector(parameters["Obstacle/ball/Center"], dim, "Obstacle/ball/Center"),
                "radius": float(parameters["Obstacle/ball/Radius"])}
    raise OutputError(f"Obstacle/Model = {model}: not an obstacle this tool knows how to draw (plane, ball)")


def moved_obstacle(obstacle, output_dir, step):
    """The obstacle of rigid_obstacle() where the run's obstacle_NNNNN.vtu puts it at `step`
    (an obstacle moved by Obstacle/Motion): a ball's centre is the mean of its surface's
    vertices (the refined sphere's are symmetric about it), a plane passes through its written
    segment (2D) or rectangle (3D), with the normal on the side of the one at rest. The
    obstacle at rest when the file is missing (a run without vtu output)."""
    path = os.path.join(output_dir, f"obstacle_{step:05d}.vtu")
    if obstacle is None or not os.path.exists(path):
        return obstacle
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput().GetPoints()
    points = [data.GetPoint(i) for i in range(data.GetNumberOfPoints())]
    if not points:
        return obstacle
    if obstacle["model"] == "ball":
        return dict(obstacle, center=[sum(p[i] for p in points) / len(points) for i in range(3)])
    a, b = points[0], points[1]
    t = [b[i] - a[i] for i in range(3)]
    if len(points) == 2:
        normal = [-t[1], t[0], 0.0]
    else:
        c = points[2]
        s = [c[i] - a[i] for i in range(3)]
        normal = [t[1] * s[2] - t[2] * s[1], t[2] * s[0] - t[0] * s[2], t[0] * s[1] - t[1] * s[0]]
    length = math.sqrt(sum(n * n for n in normal))
    sign = 1.0 if sum(n * m for n, m in zip(normal, obstacle["normal"])) >= 0 else -1.0
    return dict(obstacle, point=list(a), normal=[sign * n / length for n in normal])


def friction_law(parameters):
    """('Coulomb', mu), ('Tresca', threshold in MPa) or None (frictionless or unknown)."""
    model = parameters.get("Contact/Friction law/Model")
    if model == "Coulomb":
        mu = float(parameters.get("Contact/Friction law/Coulomb/Friction coefficient", "0"))
        return ("Coulomb", mu) if mu > 0 else None
    if model == "Tresca":
        return "Tresca", float(parameters.get("Contact/Friction law/Tresca/Threshold", "0"))
    return None


def solution_steps(output_dir):
    """[(step, time, file)] of solution.pvd in its order; the step is the number of the file name
    (solution_NNNNN.pvtu), which is the load step (0: the initial state)."""
    pvd = os.path.join(output_dir, "solution.pvd")
    if not os.path.isfile(pvd):
        raise OutputError(f"{pvd} not found (is {output_dir} an output directory of the program, "
                          "run with Output/Write vtu = true?)")
    with open(pvd) as f:
        text = f.read()
    steps = []
    for time, name in re.findall(r'<DataSet[^>]*timestep="([^"]*)"[^>]*file="([^"]*)"', text):
        match = re.search(r"_(\d+)\.p?vtu$", name)
        steps.append((int(match.group(1)) if match else len(steps), float(time), os.path.join(output_dir, name)))
    if not steps:
        raise OutputError(f"{pvd} lists no step")
    return steps


def profile_steps(output_dir):
    """{step: path} of the profile-NNNNN.csv files."""
    found = {}
    for name in os.listdir(output_dir):
        match = re.fullmatch(r"profile-(\d+)\.csv", name)
        if match:
            found[int(match.group(1))] = os.path.join(output_dir, name)
    return dict(sorted(found.items()))


# The output schema (CHANGELOG.md; run_summary.csv's `schema_version`, none before 2): the names
# schema 1 wrote that schema 2 renamed, old -> new. The tools read the old names too, for one
# release: VTU fields through vtu_array(), CSV columns through current_names().
SCHEMA_VERSION = 2
RENAMED_VTU_FIELDS = {"displacement": "displacement_mm", "stress": "stress_MPa",
                      "von_mises_stress": "von_mises_stress_MPa", "contact_pressure": "contact_pressure_MPa",
                      "tangential_traction": "tangential_traction_MPa", "gap": "gap_mm",
                      "slip_increment": "slip_increment_mm"}
# CSV columns: in plane strain every force column `<name>_N` became `<name>_N_per_mm`
OLD_FORCE_SUFFIX, FORCE_SUFFIX_PER_MM = "_N", "_N_per_mm"


def plane_strain(parameters):
    """Whether the run of these parameters (read_parameters()) is a plane strain one, whose forces
    are per unit thickness (N/mm): 2D and not axisymmetric; False when unknown ({})."""
    return (bool(parameters) and parameters.get("Dimension", "2").strip() == "2"
            and parameters.get("Geometry/Axisymmetric", "false").strip().lower() != "true")


def current_names(row, plane_strain_run=False):
    """A row of a run's CSV file, its columns also under the names of the current schema: the
    force columns of a plane strain run of schema 1 (`..._N`, in N per mm of thickness) also as
    `..._N_per_mm`. And each force column named per unit thickness also under its 3D name
    (`..._N`), so that one reader serves both dimensions."""
    if plane_strain_run and not any(key.endswith(FORCE_SUFFIX_PER_MM) for key in row):
        for key in list(row):
            if key.endswith(OLD_FORCE_SUFFIX):
                row.setdefault(key[:-len(OLD_FORCE_SUFFIX)] + FORCE_SUFFIX_PER_MM, row[key])
    for key in list(row):
        if key.endswith(FORCE_SUFFIX_PER_MM):
            row.setdefault(key[:-len(FORCE_SUFFIX_PER_MM)] + OLD_FORCE_SUFFIX, row[key])
    return row


def force_aliases(row):
    """current_names() of a row of a run whose dimension is not known."""
    return current_names(row)


def force(row, name):
    """(value, unit) of the force column `name` (normal_force, contact_force_x, ...) of a row of
    current_names(): N/mm in plane strain (per unit thickness), else N (3D, axisymmetric)."""
    if name + FORCE_SUFFIX_PER_MM in row:
        return row[name + FORCE_SUFFIX_PER_MM], "N/mm"
    return row[name + OLD_FORCE_SUFFIX], "N"


def read_rows(path, value=float):
    """The rows of a run's CSV file as dicts of value(text), under current_names() (the run's
    parameters.prm, beside the file or above it, tells a plane strain run)."""
    plane = plane_strain(run_parameters(os.path.dirname(os.path.abspath(path))))
    with open(path, newline="") as f:
        return [current_names({k: value(v) for k, v in row.items()}, plane) for row in csv.DictReader(f)]


def read_csv(path):
    """The rows of a CSV file of numbers, as dicts of floats (read_rows())."""
    return read_rows(path)


def current_vtu_names(grid):
    """A VTU's data set as VTK read it, each point or cell array of a schema 1 name renamed to
    its current one (displacement -> displacement_mm)."""
    for data in (grid.GetPointData(), grid.GetCellData()):
        for old, new in RENAMED_VTU_FIELDS.items():
            array = data.GetArray(old)
            if array is not None and data.GetArray(new) is None:
                array.SetName(new)
    return grid


def force_label(row):
    """The normal contact force of a row of statistics.csv (current_names()) with its unit."""
    value, unit = force(row, "normal_force")
    return f"normal contact force: {value:.4g} {unit}"


def on_contact_surface(marked, status):
    """Which points of a VTU are nodes of the contact surface Γc: those at a node of the profile
    (marked) whose contact_status is not -1 (-1 is off Γc: where two bodies touch, the master's
    points at the place of the slave's nodes)."""
    return [bool(m) and s != -1 for m, s in zip(marked, status)]


def contact_strip(cells, on_surface, is_3d):
    """What a picture draws of the contact surface: the faces (3D) or the boundary edges (2D) of
    the cells (lists of point indices, a 2D cell's in order around it) whose points are all on
    it (on_contact_surface()); edges as pairs of point indices, so that points at one place stay
    apart."""
    if is_3d:
        return [c for c in cells if all(on_surface[i] for i in c)]
    count = {}
    for cell in cells:
        for edge in zip(cell, cell[1:] + cell[:1]):
            count[frozenset(edge)] = count.get(frozenset(edge), 0) + 1
    return [sorted(edge) for edge, n in count.items() if n == 1 and all(on_surface[i] for i in edge)]


def step_times(output_dir):
    """{step: time} from statistics.csv ({} without it)."""
    path = os.path.join(output_dir, "statistics.csv")
    if not os.path.isfile(path):
        return {}
    return {int(row["step"]): row["time"] for row in read_csv(path)}


def node_spacing(points):
    """The median distance of a point (rows of a numpy array) to its nearest neighbour, over
    at most 2000 of them, each against all, in blocks (memory stays small for 1e5 points)."""
    import numpy as np  # here: the rest of the module needs only the standard library
    points = np.asarray(points, dtype=float)
    if len(points) < 2:
        return 0.0
    sample = np.arange(0, len(points), max(1, len(points) // 2000))
    nearest = []
    for block in np.array_split(sample, max(1, len(sample) // 100)):
        distances = np.sqrt(((points[block, None, :] - points[None, :, :]) ** 2).sum(-1))
        distances[np.arange(len(block)), block] = np.inf
        nearest.append(distances.min(1))
    return float(np.median(np.concatenate(nearest)))


def describe_steps(steps):
    """A list of step numbers in words ('steps 1 to 10')."""
    steps = sorted(steps)
    if not steps:
        return "no step"
    if len(steps) == 1:
        return f"step {steps[0]} only"
    if steps == list(range(steps[0], steps[-1] + 1)):
        return f"steps {steps[0]} to {steps[-1]}"
    return "steps " + ", ".join(map(str, steps))


def select_steps(requested, available, where):
    """The steps asked for (numbers, 'all' or 'last'; default the last) among `available`;
    OutputError naming the available ones if one is not there."""
    available = sorted(available)
    if not available:
        raise OutputError(f"{where} has no step")
    chosen = []
    for word in requested or ["last"]:
        if word == "all":
            chosen += available
        elif word == "last":
            chosen.append(available[-1])
        else:
            try:
                step = int(word)
            except ValueError:
                raise OutputError(f"step '{word}' is not a number, 'all' or 'last'") from None
            if step not in available:
                raise OutputError(f"step {step} not in {where}: it has {describe_steps(available)}")
            chosen.append(step)
    return sorted(set(chosen))


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import tool_cli
    tool_cli.module_help(__doc__)
