#!/usr/bin/env pvpython
"""Render load steps of a stabilized_lagrangian run to PNG images.

Usage (rendering needs a display; pvpython comes with the python3-paraview package):
  xvfb-run -a pvpython contrib/render_pvd.py OUTPUT_DIR [--step N|all|last ...] [--output FOLDER|FILE.png]
      [--field NAME] [--view body|contact] [--scale FACTOR|auto] [--range MIN MAX] [--mesh]

What an image shows:
- the body in its deformed configuration, light grey, with the true
  displacement (--scale magnifies it: then the image says so, and the obstacle
  stays where it is, so the magnified body seems to cross it);
- its contact surface coloured by --field (default contact_pressure; colours
  unshaded, as in the bar; where the field is 0, no contact, in grey): the
  surface is the one of the run's profile-NNNNN.csv, so the field is not
  smeared over the cells next to it (without profiles the whole body is
  coloured, and the image says so); contact_status is drawn at the nodes;
- the outline of the undeformed body (not in the 3D contact view);
- the rigid obstacle of the run's parameters.prm (Obstacle/Model plane or
  ball), dark grey; none when the master is a second body of the mesh
  (Contact/Master boundary ids), which is drawn as the body is;
- a colour bar with the field's unit, and in the upper left corner the run,
  the load step and its time, the field's largest value, the normal force
  (statistics.csv: N, in plane strain N/mm per unit thickness), the
  displacement scale and the obstacle.

The contact surface is the slave's (the nodes whose contact_status is not -1):
where two bodies touch, the master's nodes at the same place are not on it.
Files of the output schema 1 (CHANGELOG.md: VTU fields without their units)
are read too.

Views (--view): in 2D the whole body (default) or the contact zone and a few
cells around it; in 3D the contact zone (default): the camera is on the
obstacle's side, drawn as a wireframe to look through, 50 degrees off its
normal, aimed at the centre of the pressed zone (weighted by the pressure) and
framing it with a few cells around; or the whole body, from the body's side.
Orthographic projection.

--step: numbers of solution.pvd's steps (the load steps; 0 is the initial
state), 'all' or 'last' (default). One image per step, FOLDER/NAME-NNNNN.png
(NAME the field), into --output (default: OUTPUT_DIR); --output FILE.png names
the image of a single step. With several steps the colour range is the same in
all (the largest over them), unless --range.

Exits with 2 and a message for an argument the run cannot satisfy (no
solution.pvd, a step it does not have, an unknown field)."""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_output  # noqa: E402

# name: (title, unit, kind, what 0 means): kind 'scalar', 'magnitude' (of a vector) or
# 'status' (categories); a field >= 0 whose 0 means something (no contact, ...) draws 0 in the
# body's grey
FIELDS = {"contact_pressure": ("contact pressure", "MPa", "scalar", "no contact"),
          "tangential_traction": ("tangential traction (magnitude)", "MPa", "magnitude", "no friction force"),
          "gap": ("gap", "mm", "scalar", None),
          "slip_increment": ("slip increment (magnitude)", "mm", "magnitude", "no slip"),
          "cumulative_slip": ("cumulative slip (magnitude)", "mm", "magnitude", "no slip"),
          "slip_path": ("slip path", "mm", "scalar", "no slip"),
          "contact_status": ("contact status", None, "status", None)}


def array_name(field):
    """The VTU array of a field: its name with its unit (contact_pressure_MPa)."""
    unit = "mm" if field == "displacement" else FIELDS[field][1]
    return field + ("_" + unit if unit else "")
WIDTH, HEIGHT = 1600, 900
BODY_GREY = [0.82, 0.82, 0.82]
OBSTACLE_GREY = [0.55, 0.55, 0.6]

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("output_dir", metavar="OUTPUT_DIR", help="the run's output directory (holding solution.pvd)")
parser.add_argument("--step", nargs="+", metavar="N", default=["last"],
                    help="steps of solution.pvd: numbers, 'all' or 'last' (default)")
parser.add_argument("--output", metavar="FOLDER", help="folder of the images, or FILE.png for one step "
                    "(default: OUTPUT_DIR)")
parser.add_argument("--field", choices=list(FIELDS), default="contact_pressure",
                    help="the field on the contact surface (default: contact_pressure)")
parser.add_argument("--view", choices=["body", "contact"],
                    help="what the camera frames (default: 2D body, 3D contact)")
parser.add_argument("--scale", default="1",
                    help="displacement magnification: a number, or 'auto' (a tenth of the model's size for "
                         "the largest displacement); default 1, the true deformation")
parser.add_argument("--range", nargs=2, type=float, metavar=("MIN", "MAX"), help="colour range of the field")
parser.add_argument("--mesh", action="store_true", help="draw the cell edges of the deformed body")
args = parser.parse_args()

if not os.path.isdir(args.output_dir):
    parser.error(f"argument OUTPUT_DIR: '{args.output_dir}' does not exist or is not a directory")
try:
    available = run_output.solution_steps(args.output_dir)
    steps = run_output.select_steps(args.step, [s for s, _, _ in available],
                                    os.path.join(args.output_dir, "solution.pvd"))
    parameters = run_output.run_parameters(args.output_dir)
    obstacle = run_output.rigid_obstacle(parameters)
except run_output.OutputError as error:
    parser.error(str(error))
if args.scale != "auto":
    try:
        scale_factor = float(args.scale)
    except ValueError:
        parser.error(f"argument --scale: '{args.scale}' is not a number or 'auto'")
    if not scale_factor > 0:
        parser.error(f"argument --scale: {args.scale} is not > 0")
if args.range and not args.range[0] < args.range[1]:
    parser.error("argument --range: MIN must be below MAX")
single_file = args.output is not None and args.output.endswith(".png")
if single_file and len(steps) > 1:
    parser.error(f"argument --output: one file for {len(steps)} steps; name a folder")
folder = os.path.dirname(os.path.abspath(args.output)) if single_file else os.path.abspath(
    args.output or args.output_dir)
if os.path.exists(folder) and not os.path.isdir(folder):
    parser.error(f"argument --output: '{folder}' exists and is not a directory")

# imported only after the argument checks: loading ParaView takes about a second
import numpy as np  # noqa: E402
from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, GetScalarBar,  # noqa: E402
                             Render, SaveScreenshot, SetActiveView, Show, Text, TrivialProducer)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonCore import VTK_ID_TYPE  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData, vtkUnstructuredGrid  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkFeatureEdges, vtkPolyDataNormals  # noqa: E402
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkRegularPolygonSource, vtkSphereSource  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader  # noqa: E402


# ------------------------------------------------------------------------------------------ the data

def merged_grid(grid):
    """The grid with deal.II's per-cell copies of the vertices merged (else every cell edge
    would be a boundary edge): copies with the same position and the same continuous fields.
    Position alone would also merge the coincident nodes of two bodies in contact, whose
    displacement or contact fields differ."""
    point_data = grid.GetPointData()
    continuous = [array_name(n) for n in ("displacement", "contact_pressure", "tangential_traction", "gap",
                                          "slip_increment", "contact_status")]
    continuous = [n for n in continuous if point_data.GetArray(n) is not None]
    key = [vtk_to_numpy(grid.GetPoints().GetData()).astype(float)]
    key += [vtk_to_numpy(point_data.GetArray(n)).astype(float).reshape(grid.GetNumberOfPoints(), -1)
            for n in continuous]
    _, first, inverse = np.unique(np.hstack(key), axis=0, return_index=True, return_inverse=True)
    merged = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(vtk_to_numpy(grid.GetPoints().GetData())[first].astype(float), deep=True))
    merged.SetPoints(points)
    connectivity = inverse.ravel()[vtk_to_numpy(grid.GetCells().GetConnectivityArray())]
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtk(vtk_to_numpy(grid.GetCells().GetOffsetsArray()).astype(np.int64), deep=True,
                               array_type=VTK_ID_TYPE),
                  numpy_to_vtk(connectivity.astype(np.int64), deep=True, array_type=VTK_ID_TYPE))
    merged.SetCells(grid.GetCellTypesArray(), cells)
    for i in range(point_data.GetNumberOfArrays()):
        values = vtk_to_numpy(point_data.GetArray(i))[first]
        array = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        array.SetName(point_data.GetArrayName(i))
        merged.GetPointData().AddArray(array)
    return merged


def read_step(path):
    """The step's mesh (merged_grid) and its boundary surface: in 3D the boundary faces, each
    ordered so that its normal points out of its cell (the lighting needs outward normals, and
    a surface with the hanging nodes of local refinement cannot be oriented as a whole); in 2D
    the cells."""
    reader = vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu") else vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = merged_grid(run_output.current_vtu_names(reader.GetOutput()))
    surface = vtkDataSetSurfaceFilter()
    surface.SetInputData(grid)
    surface.PassThroughCellIdsOn()
    surface.Update()
    data = surface.GetOutput()
    points = vtk_to_numpy(data.GetPoints().GetData()).astype(float)
    if np.ptp(points[:, 2]) == 0:
        return data
    connectivity = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
    grid_points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    cell_centres = np.add.reduceat(grid_points[connectivity], offsets[:-1], axis=0) / np.diff(offsets)[:, None]
    parents = vtk_to_numpy(data.GetCellData().GetArray("vtkOriginalCellIds"))
    polys = vtkCellArray()
    for c, cell in enumerate(cells_of(data)):
        corners = points[cell]
        normal = np.cross(corners - corners.mean(0), np.roll(corners, -1, axis=0) - corners.mean(0)).sum(0)
        if np.dot(normal, corners.mean(0) - cell_centres[parents[c]]) < 0:
            cell = cell[::-1]
        polys.InsertNextCell(len(cell), cell)
    data.SetPolys(polys)
    return data


def point_array(data, name):
    array = data.GetPointData().GetArray(name)
    if array is None:
        names = [data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())]
        sys.exit(f"error: no point array '{name}' in the step's file (found: {', '.join(names)})")
    return vtk_to_numpy(array).astype(float)


def field_values(data, name):
    values = point_array(data, array_name(name))
    return np.sqrt((values ** 2).sum(1)) if FIELDS[name][2] == "magnitude" else values


def contact_nodes(points, profile_path, size):
    """Which surface points are nodes of the contact surface (profile-NNNNN.csv, reference
    coordinates, as the points of the files are)."""
    if profile_path is None:
        return None
    nodes = np.array([[row.get("x_mm", 0.0), row.get("y_mm", 0.0), row.get("z_mm", 0.0)]
                      for row in run_output.read_csv(profile_path)])
    marked = np.zeros(len(points), dtype=bool)
    if not len(nodes):
        return marked
    tolerance = 1e-6 * size  # the files' points are single precision
    order = np.argsort(points[:, 0])
    xs = points[order, 0]
    for node in nodes:  # the candidates by x first: a few thousand nodes against 1e5 points
        lo, hi = np.searchsorted(xs, node[0] - tolerance), np.searchsorted(xs, node[0] + tolerance, "right")
        candidates = order[lo:hi]
        close = candidates[np.abs(points[candidates] - node).max(1) <= tolerance]
        marked[close] = True
    return marked


def polydata(points, cells, arrays=()):
    """A vtkPolyData of the points, the cells (lists of point indices: 1 point a vertex, 2 a
    line, more a polygon) and the point arrays {name: values}."""
    data = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    data.SetPoints(vtk_points)
    verts, lines, polys = vtkCellArray(), vtkCellArray(), vtkCellArray()
    for cell in cells:
        ({1: verts, 2: lines}.get(len(cell), polys)).InsertNextCell(len(cell), [int(i) for i in cell])
    data.SetVerts(verts)
    data.SetLines(lines)
    data.SetPolys(polys)
    for name, values in dict(arrays).items():
        array = numpy_to_vtk(np.ascontiguousarray(values, dtype=float), deep=True)
        array.SetName(name)
        data.GetPointData().AddArray(array)
    return data


def cells_of(data):
    """The cells of a vtkPolyData (polygons, or lines) as lists of point indices."""
    return [[data.GetCell(c).GetPointId(k) for k in range(data.GetCell(c).GetNumberOfPoints())]
            for c in range(data.GetNumberOfCells())]


def boundary_edges(data, feature_edges):
    """The boundary edges (and in 3D the feature edges) of a surface, as a vtkPolyData of lines."""
    edges = vtkFeatureEdges()
    edges.SetInputData(data)
    edges.BoundaryEdgesOn()
    edges.SetFeatureEdges(feature_edges)
    edges.NonManifoldEdgesOff()
    edges.ManifoldEdgesOff()
    edges.Update()
    return edges.GetOutput()


def without_hanging_edges(lines):
    """The boundary edges of a mesh with hanging nodes (local refinement) include, inside the
    body, the edge of a coarse cell and the finer edges that cover it: leave out every edge
    whose midpoint lies on another edge."""
    points = vtk_to_numpy(lines.GetPoints().GetData()).astype(float)
    edges = np.array([c for c in cells_of(lines) if len(c) == 2], dtype=int).reshape(-1, 2)
    if not len(edges):
        return lines
    a, b = points[edges[:, 0]], points[edges[:, 1]]
    d = b - a
    length2 = np.maximum((d ** 2).sum(1), 1e-300)
    middle = (a + b) / 2
    keep = []
    for i, m in enumerate(middle):
        t = np.clip(((m - a) * d).sum(1) / length2, 0.0, 1.0)
        distance2 = ((a + t[:, None] * d - m) ** 2).sum(1)
        same_ends = np.minimum(((a - a[i]) ** 2).sum(1) + ((b - b[i]) ** 2).sum(1),
                               ((a - b[i]) ** 2).sum(1) + ((b - a[i]) ** 2).sum(1)) <= 1e-12 * length2[i]
        distance2[same_ends] = np.inf
        # 5 %: refined cells of a curved boundary put their vertices on the curve, off the coarse edge
        keep.append(not (distance2 <= 0.05 ** 2 * length2[i]).any())
    return polydata(points, edges[np.array(keep)])


def smooth_normals(data):
    normals = vtkPolyDataNormals()
    normals.SetInputData(data)
    normals.SetFeatureAngle(30)
    normals.ConsistencyOff()  # the faces are ordered outwards already (read_step)
    normals.Update()
    return normals.GetOutput()


# ------------------------------------------------------------------------------------------ the obstacle

def tangent_basis(n):
    """Two unit vectors orthogonal to n and to each other, the first as close as possible to (1, -1, 0)."""
    for guess in ((1.0, -1.0, 0.0), (0.0, 1.0, 1.0)):
        t = np.array(guess) - np.dot(guess, n) * n
        if np.linalg.norm(t) > 1e-6:
            t /= np.linalg.norm(t)
            return t, np.cross(n, t)
    raise ValueError("no tangent")


def obstacle_normal(at):
    """The obstacle's unit normal (out of it, towards the body) at the point `at`."""
    if obstacle["model"] == "plane":
        return np.array(obstacle["normal"])
    d = at - np.array(obstacle["center"])
    return d / np.linalg.norm(d) if np.linalg.norm(d) > 0 else np.array([0.0, 0.0, 1.0] if is_3d else [0, 1.0, 0])


def obstacle_geometry(centre, half_size, offset):
    """The obstacle near `centre`, as vtkPolyData (surface, its edge or None): a plane as a band
    (2D) or a square (3D) of half width half_size, a ball as a disc (2D) or a sphere (3D); moved
    by `offset` (so that what touches the body is not drawn in the body's faces)."""
    if obstacle["model"] == "plane":
        n = np.array(obstacle["normal"])
        foot = centre - np.dot(centre - np.array(obstacle["point"]), n) * n + offset
        if not is_3d:
            t = np.array([n[1], -n[0], 0.0])
            depth = 0.15 * half_size  # the obstacle's side of the line, to tell it from the body
            corners = [foot - half_size * t, foot + half_size * t, foot + half_size * t - depth * n,
                       foot - half_size * t - depth * n]
            return polydata(corners, [[0, 1, 2, 3]]), polydata(corners[:2], [[0, 1]])
        t1, t2 = tangent_basis(n)
        source = vtkPlaneSource()
        source.SetOrigin(*(foot - half_size * (t1 + t2)))
        source.SetPoint1(*(foot + half_size * (t1 - t2)))
        source.SetPoint2(*(foot + half_size * (t2 - t1)))
        source.SetResolution(24, 24)  # the lines of the wireframe view
        source.Update()
        return source.GetOutput(), boundary_edges(source.GetOutput(), False)
    centre_ball, radius = np.array(obstacle["center"]) + offset, obstacle["radius"]
    if not is_3d:
        sources = []
        for polygon in (True, False):
            source = vtkRegularPolygonSource()
            source.SetNumberOfSides(720)
            source.SetRadius(radius)
            source.SetCenter(*centre_ball)
            source.SetGeneratePolygon(polygon)
            source.Update()
            sources.append(source.GetOutput())
        return tuple(sources)
    source = vtkSphereSource()
    source.SetCenter(*centre_ball)
    source.SetRadius(radius)
    source.SetThetaResolution(72)
    source.SetPhiResolution(36)
    source.Update()
    return source.GetOutput(), None


def describe_obstacle():
    if obstacle is None:
        if parameters.get("Contact/Master boundary ids", "").strip():
            return "master: a second body of the mesh (grey)"
        return "obstacle: unknown (no parameters.prm)"

    def vector(v):
        return "(" + ", ".join(f"{x:g}" for x in v[:3 if is_3d else 2]) + ")"
    if obstacle["model"] == "plane":
        return f"rigid plane through {vector(obstacle['point'])}, normal {vector(obstacle['normal'])}"
    kind = "ball" if is_3d else "disc"
    return f"rigid {kind}, centre {vector(obstacle['center'])}, radius {obstacle['radius']:g} mm"


# ------------------------------------------------------------------------------------------ the camera

def frame(view, points, direction, up, margin):
    """Aim an orthographic camera along -direction at the points, framing them with a margin."""
    direction = direction / np.linalg.norm(direction)
    up = up - np.dot(up, direction) * direction
    up /= np.linalg.norm(up)
    right = np.cross(up, direction)
    across, along = points @ right, points @ up
    centre_2d = [(across.min() + across.max()) / 2, (along.min() + along.max()) / 2]
    depth = points @ direction
    focal = centre_2d[0] * right + centre_2d[1] * up + depth.mean() * direction
    # room at the right for the colour bar
    half_height = max((along.max() - along.min()) / 2, (across.max() - across.min()) / 2 * HEIGHT / WIDTH / 0.8)
    distance = 10 * max(np.ptp(points, axis=0).max(), 1e-9)
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = list(focal + 0.08 * half_height * margin * right)
    view.CameraPosition = list(focal + 0.08 * half_height * margin * right + distance * direction)
    view.CameraViewUp = list(up)
    view.CameraParallelScale = max(half_height * margin, 1e-9)


# ------------------------------------------------------------------------------------------ one image

def field_range(values_per_step):
    if args.range:
        return args.range
    kind = FIELDS[args.field][2]
    if kind == "status":
        return 0.0, 2.0
    high = max((float(v.max()) for v in values_per_step if len(v)), default=0.0)
    low = min((float(v.min()) for v in values_per_step if len(v)), default=0.0)
    # a field >= 0 in theory (pressure, magnitudes) starts at 0 unless it is clearly negative:
    # -1e-9 MPa is round-off and would hide where 0 (no contact) is drawn grey
    low = 0.0 if FIELDS[args.field][3] is not None and low > -1e-6 * abs(high) else min(low, 0.0)
    return (low, high) if high > low else (low, low + 1.0)  # a zero field: a bar of 0 .. 1, not of round-off


def show_polydata(view, data, colour=None, opacity=1.0, line_width=None, edges=False):
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(data)
    producer.UpdatePipeline()
    display = Show(producer, view)
    display.SetRepresentationType("Surface With Edges" if edges else "Surface")
    if colour is not None:
        display.ColorArrayName = ["POINTS", ""]
        display.AmbientColor = display.DiffuseColor = colour
    display.Opacity = opacity
    if line_width:
        display.LineWidth = line_width
    if edges:
        display.EdgeColor = [0.35, 0.35, 0.35]
    return producer, display


def render(step, time, data, marked, values, colour_range, scale, png):
    points = vtk_to_numpy(data.GetPoints().GetData()).astype(float)
    displacement = point_array(data, array_name("displacement"))
    deformed = points + scale * displacement
    cells = cells_of(data)
    producers = []

    view = CreateView("RenderView")
    SetActiveView(view)
    view.ViewSize = [WIDTH, HEIGHT]
    view.Background = [1, 1, 1]
    view.UseColorPaletteForBackground = 0  # otherwise the palette overrides Background (ParaView >= 5.10)
    view.OrientationAxesVisibility = 0 if not is_3d else 1
    view.OrientationAxesLabelColor = [0, 0, 0]
    # the key light along the view: the default comes from above the camera, which leaves a
    # contact face seen from below in the dark
    view.KeyLightElevation, view.KeyLightAzimuth = 0, 0

    # the contact surface: in 3D the boundary faces with every node on it, in 2D the boundary
    # edges with both ends on it; a status (a category, not a value to interpolate) is drawn at
    # the nodes
    kind = FIELDS[args.field][2]
    if marked is not None:
        if kind == "status":
            contact_cells = [[i] for i in np.nonzero(marked)[0]]
        else:
            contact_cells = run_output.contact_strip(cells, marked, is_3d)
        body_cells = [c for c in cells if not marked[c].all()] if is_3d and kind != "status" else cells
    else:
        contact_cells, body_cells = [], cells

    body = polydata(deformed, body_cells)
    lifted = deformed + ([0, 0, 0] if is_3d else [0, 0, 1e-3 * size])  # in front of the body's plane
    name = args.field if FIELDS[args.field][2] != "magnitude" else args.field + "_magnitude"
    coloured = polydata(lifted, contact_cells, {name: values}) if contact_cells else None
    if marked is None:  # no contact surface known: the field over the whole body
        body = polydata(deformed, body_cells, {name: values})
    body = smooth_normals(body) if is_3d else body
    producer, body_display = show_polydata(view, body, None if marked is None else BODY_GREY, edges=args.mesh)
    producers.append(producer)
    field_display = body_display if marked is None else None
    if coloured is not None and kind == "status":
        producer, field_display = show_polydata(view, coloured)
        field_display.SetRepresentationType("Points")
        field_display.PointSize = 14
        field_display.RenderPointsAsSpheres = 1
        producers.append(producer)
    elif coloured is not None:
        producer, field_display = show_polydata(view, smooth_normals(coloured) if is_3d else coloured,
                                                line_width=None if is_3d else 8, edges=args.mesh and is_3d)
        producers.append(producer)


    # the camera: the contact zone's centre and extent (deformed), the pressed part of it first
    pressure = point_array(data, array_name("contact_pressure"))
    on_surface = marked if marked is not None and marked.any() else np.ones(len(points), dtype=bool)
    pressed = on_surface & (pressure > 0)
    zone = pressed if pressed.any() else on_surface
    weights = pressure[zone] if pressed.any() else np.ones(zone.sum())
    centre = (deformed[zone] * weights[:, None]).sum(0) / weights.sum()
    view_kind = args.view or ("contact" if is_3d else "body")
    normal = obstacle_normal(centre) if obstacle else np.array([0, 0, 1.0] if is_3d else [0, 1.0, 0])
    if view_kind == "contact":
        zone_radius = np.sqrt(((deformed[zone] - centre) ** 2).sum(1)).max()
        # the zone and a few cells around it, so that a zone of one or two cells is seen in its mesh
        spacing = run_output.node_spacing(deformed[on_surface])
        radius = max(1.6 * zone_radius, zone_radius + 4 * spacing, 0.04 * size)
        if is_3d:  # the body's surface around the zone
            framed = deformed[np.sqrt(((deformed - centre) ** 2).sum(1)) <= radius]
        else:  # a square on the zone: the body above it, the obstacle below
            framed = centre + radius * np.array([[1.0, 0, 0], [-1.0, 0, 0], [0, 1.0, 0], [0, -1.0, 0]])
    else:
        framed = np.vstack([deformed, points])
    if is_3d:
        t1, _ = tangent_basis(normal)
        # contact: from the obstacle's side, 50 degrees off the normal; body: from the body's side
        tilt = np.radians(50)
        direction = (-np.cos(tilt) * normal + np.sin(tilt) * t1) if view_kind == "contact" else (0.8 * normal + t1)
        up = normal
    else:
        direction, up = np.array([0, 0, 1.0]), np.array([0, 1.0, 0])

    if not (is_3d and view_kind == "contact"):  # there it would only hide the contact zone
        outline = without_hanging_edges(boundary_edges(polydata(points, cells), is_3d))
        producer, display = show_polydata(view, outline, [0.3, 0.3, 0.3], line_width=1.5)
        producers.append(producer)

    if obstacle:
        extent = np.ptp(framed, axis=0).max()
        half = 1.5 * extent if view_kind == "contact" else 0.75 * np.ptp(points, axis=0).max()
        # 2D: behind the body's plane; 3D: a hair away from the body, off the contact faces
        offset = [0, 0, -1e-3 * size] if not is_3d else -1e-3 * size * normal
        surface, edge = obstacle_geometry(centre, max(half, 1e-6 * size), offset)
        producer, display = show_polydata(view, surface, OBSTACLE_GREY)
        if is_3d and view_kind == "contact":  # seen through: a wireframe hides nothing of the contact zone
            display.SetRepresentationType("Wireframe")
            display.Opacity = 0.6
        producers.append(producer)
        if edge is not None:
            producer, _ = show_polydata(view, edge, [0.2, 0.2, 0.25], line_width=3 if not is_3d else 1.5)
            producers.append(producer)

    title, unit, _, zero_meaning = FIELDS[args.field]
    zero_is_grey = zero_meaning is not None and colour_range[0] == 0
    if field_display is not None:
        # the colours of the bar, unshaded: a shaded colour would read as another value
        field_display.Ambient, field_display.Diffuse = 1.0, 0.0
        ColorBy(field_display, ("POINTS", name))
        lut = GetColorTransferFunction(name)
        lut.AutomaticRescaleRangeMode = "Never"
        if kind == "status":
            lut.InterpretValuesAsCategories = 1
            lut.Annotations = ["0", "open", "1", "stick", "2", "slip"]
            lut.IndexedColors = [0.6, 0.6, 0.6, 0.12, 0.47, 0.71, 1.0, 0.5, 0.05]
        else:
            lut.InterpretValuesAsCategories = 0
            lut.ApplyPreset("Rainbow Uniform", True)
            lut.RescaleTransferFunction(*colour_range)
            if zero_is_grey:
                # 0 in grey, anything above it in the map's colours: the map starts a hair above 0
                rgb = list(lut.RGBPoints)
                rgb[0] = 1e-6 * colour_range[1]
                lut.RGBPoints = [0.0] + BODY_GREY + rgb
        bar = GetScalarBar(lut, view)
        bar.Title = title + (f" ({unit})" if unit else "")
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        bar.TitleFontSize = bar.LabelFontSize = 20
        bar.ScalarBarLength = 0.5
        bar.WindowLocation = "Any Location"
        bar.Position = [0.89, 0.25]
        bar.Visibility = 1
        field_display.SetScalarBarVisibility(view, True)

    lines = [f"{run_name}: load step {step} of {last_step}, t = {time:g}"]
    if values is not None and len(values) and kind != "status":
        shown = values[marked] if marked is not None and marked.any() else values
        lines.append(f"largest {title}: {shown.max():.4g} {unit}"
                     + (f" (colour range {colour_range[0]:.4g} .. {colour_range[1]:.4g})"
                        if args.range or len(steps) > 1 else ""))
    if step in statistics_rows:
        lines.append(run_output.force_label(statistics_rows[step]))
    lines.append("displacement: true scale" if scale == 1 else
                 f"displacement magnified x {scale:.3g}" + (" (the obstacle is at its true place)" if obstacle else ""))
    lines.append(describe_obstacle() + ("; seen through it (wireframe), 50 degrees off its normal"
                                        if obstacle and is_3d and view_kind == "contact" else ""))
    if field_display is not None and zero_is_grey:
        lines.append(f"grey on the contact surface: {title} 0 ({zero_meaning})")
    if is_3d and view_kind == "body":
        lines.append("the contact surface faces away from this view: --view contact shows it")
    if marked is None:
        lines.append("no profile-NNNNN.csv: the field is drawn over the whole body")
    elif not contact_cells:
        lines.append("no face of the mesh matched the profile's nodes: the contact surface is not drawn")
    label = Text(Text="\n".join(lines))
    label_display = Show(label, view)
    label_display.WindowLocation = "Upper Left Corner"
    label_display.Justification = "Left"
    label_display.ShowBorder = "Always"  # a white box: the text stays readable over the mesh
    label_display.BackgroundColor = [1, 1, 1, 0.8]
    label_display.BorderColor = [1, 1, 1]
    label_display.FontSize = 18
    label_display.Color = [0, 0, 0]
    producers.append(label)

    Render(view)  # the first Render() of a view resets its camera: have it before setting the camera
    frame(view, framed, direction, up, 1.1)
    SaveScreenshot(png, view, ImageResolution=[WIDTH, HEIGHT])
    for producer in producers:
        Delete(producer)
    Delete(view)


# ------------------------------------------------------------------------------------------ the steps

files = {s: (t, f) for s, t, f in available}
last_step = max(files)
run_name = os.path.basename(os.path.normpath(os.path.abspath(args.output_dir)))
is_3d = int(parameters.get("Dimension", "0")) == 3
profiles = run_output.profile_steps(args.output_dir)
statistics = os.path.join(args.output_dir, "statistics.csv")
statistics_rows = ({int(r["step"]): r for r in run_output.read_csv(statistics)}
                   if os.path.isfile(statistics) else {})
os.makedirs(folder, exist_ok=True)

loaded = {}
for step in steps:
    data = read_step(files[step][1])
    points = vtk_to_numpy(data.GetPoints().GetData()).astype(float)
    if "Dimension" not in parameters:  # no parameters.prm: flat in z means 2D
        is_3d = np.ptp(points[:, 2]) > 1e-12 * max(np.ptp(points, axis=0).max(), 1e-300)
    size = float(np.sqrt((np.ptp(points, axis=0) ** 2).sum()))
    # the nodes of the contact surface: any profile will do (reference coordinates, one mesh per
    # directory), the step's own if there is one; step 0 has none
    profile = profiles.get(step) or (profiles[min(profiles, key=lambda s: abs(s - step))] if profiles else None)
    marked = contact_nodes(points, profile, size)
    if marked is not None:  # the slave's nodes only (two bodies: the master's at the same place)
        marked = np.array(run_output.on_contact_surface(marked, point_array(data, "contact_status")), dtype=bool)
    values = field_values(data, args.field)
    loaded[step] = (data, marked, values, size)
colour_range = field_range([v[m] if m is not None and m.any() else v for _, m, v, _ in loaded.values()])

obstacle_at_rest = obstacle
for step in steps:
    data, marked, values, size = loaded[step]
    # a moving obstacle where the run wrote it at this step
    obstacle = run_output.moved_obstacle(obstacle_at_rest, args.output_dir, step)
    displacement = point_array(data, array_name("displacement"))
    max_u = float(np.sqrt((displacement ** 2).sum(1)).max())
    scale = scale_factor if args.scale != "auto" else (0.1 * size / max_u if max_u > 0 else 1.0)
    png = os.path.abspath(args.output) if single_file else os.path.join(folder, f"{args.field}-{step:05d}.png")
    render(step, files[step][0], data, marked, values, colour_range, scale, png)
    print(png)
