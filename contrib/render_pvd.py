#!/usr/bin/env pvpython
"""Render one step of a stabilized_lagrangian ParaView time series to a PNG.

The deformed body (warped by `displacement`) is coloured by `contact_pressure`,
over the outline of the undeformed body.

Usage (rendering needs a display; pvpython comes with the python3-paraview package):
  xvfb-run -a pvpython contrib/render_pvd.py OUTPUT_DIR [--step N] [--output out.png] [--scale FACTOR]

--step N is the N-th entry of solution.pvd (default: the last one); as the program
writes every load step, starting with step 0, it is the step number of solution_N.pvtu.
"""
import argparse
import math
import os
import sys

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output_dir", help="directory holding solution.pvd")
parser.add_argument("--step", type=int, help="index of the step in solution.pvd (default: last)")
parser.add_argument("--output", help="PNG file (default: OUTPUT_DIR/contact_pressure.png)")
parser.add_argument("--scale", type=float,
                    help="displacement magnification (default: 0.1 x model size / max |displacement|)")
args = parser.parse_args()

pvd = os.path.join(args.output_dir, "solution.pvd")
if not os.path.isfile(pvd):
    sys.exit(f"error: {pvd} not found (is {args.output_dir} an output directory?)")
png = os.path.abspath(args.output or os.path.join(args.output_dir, "contact_pressure.png"))

# imported only after the argument checks: loading ParaView takes about a second
from paraview.simple import (CleantoGrid, ColorBy, CreateView, ExtractSurface, FeatureEdges,
                             GetColorTransferFunction, GetScalarBar, PVDReader, Render, SaveScreenshot,
                             SetActiveView, Show, WarpByVector)

reader = PVDReader(FileName=pvd)
times = reader.TimestepValues
times = [times] if isinstance(times, float) else list(times)  # a single step comes as a bare float
step = len(times) - 1 if args.step is None else args.step
if not 0 <= step < len(times):
    sys.exit(f"error: --step {step} out of range, {pvd} has steps 0..{len(times) - 1}")
time = times[step]
reader.UpdatePipeline(time)

point_arrays = reader.PointData.keys()
for name in ("displacement", "contact_pressure"):
    if name not in point_arrays:
        sys.exit(f"error: no point array '{name}' in {pvd} (found: {', '.join(point_arrays)})")

bounds = reader.GetDataInformation().GetBounds()
size = math.sqrt(sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)))
is_2d = bounds[5] - bounds[4] <= 1e-12 * size
max_u = reader.PointData["displacement"].GetRange(-1)[1]  # component -1: magnitude
scale = args.scale if args.scale is not None else (0.1 * size / max_u if max_u > 0 else 1.0)

view = CreateView("RenderView")
SetActiveView(view)
view.ViewSize = [1600, 900]
view.ViewTime = time
view.Background = [1, 1, 1]
view.UseColorPaletteForBackground = 0  # otherwise the palette overrides Background (ParaView >= 5.10)
view.OrientationAxesVisibility = 0

warp = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=scale)
body = Show(warp, view)
ColorBy(body, ("POINTS", "contact_pressure"))
lut = GetColorTransferFunction("contact_pressure")
lut.AutomaticRescaleRangeMode = "Never"
p_max = reader.PointData["contact_pressure"].GetRange()[1]
lut.RescaleTransferFunction(0.0, p_max if p_max > 0 else 1.0)  # [0, 0] at step 0 gives a bar of round-off
lut.ApplyPreset("Rainbow Uniform", True)
bar = GetScalarBar(lut, view)
bar.Title = "contact pressure (MPa)"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
bar.TitleFontSize = bar.LabelFontSize = 20
bar.ScalarBarLength = 0.5
bar.Visibility = 1

# deal.II writes every cell with its own copy of the vertices: merge them, or every
# cell edge would count as a boundary edge of the outline
outline = FeatureEdges(Input=ExtractSurface(Input=CleantoGrid(Input=reader)))
outline.BoundaryEdges = 1
outline.FeatureEdges = 0 if is_2d else 1
outline.NonManifoldEdges = 0
outline.ManifoldEdges = 0
edges = Show(outline, view)
edges.SetRepresentationType("Wireframe")
edges.ColorArrayName = [None, ""]
edges.AmbientColor = edges.DiffuseColor = [0, 0, 0]
edges.LineWidth = 2

Render(view)  # the first Render() of a view resets its camera: have it before setting the camera
focal = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
if is_2d:
    view.InteractionMode = "2D"
    direction, view.CameraViewUp = (0, 0, 1), (0, 1, 0)
else:  # isometric; the program's 3D block has z as the vertical axis
    direction, view.CameraViewUp = (1, -1, 1), (0, 0, 1)
view.CameraFocalPoint = focal
view.CameraPosition = [f + size * d for f, d in zip(focal, direction)]
view.ResetCamera(False)
if is_2d:  # ResetCamera fits the bounding circle: fit the deformed and undeformed box instead
    warp.UpdatePipeline(time)
    b = [f(x, y) for x, y, f in zip(bounds, warp.GetDataInformation().GetBounds(), [min, max] * 3)]
    view.CameraFocalPoint = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, focal[2]]
    view.CameraPosition = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, focal[2] + size]
    # 0.55: 10 % margin; the width gets an extra 25 % for the colour bar
    view.CameraParallelScale = 0.55 * max(b[3] - b[2], 1.25 * (b[1] - b[0]) * 900 / 1600)

os.makedirs(os.path.dirname(png), exist_ok=True)
SaveScreenshot(png, view, ImageResolution=[1600, 900])
print(png)
print(f"step {step}, t = {time:g}, displacement x {scale:.3g}", file=sys.stderr)
