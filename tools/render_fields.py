"""Renders one time of an emcontact field output (fields.xdmf) to a PNG with ParaView.

Usage (ParaView's Python: Debian packages python3-paraview and paraview):

    pvpython tools/render_fields.py DIR/fields.xdmf OUT.png [--at-impact | --time T]
        [--field von_mises] [--scale 1] [--size 1200x900] [--ground-z 0 | --no-ground]
        [--clip] [--title TEXT]

Without a display (CI, ssh) Debian's ParaView needs an X server: run it under
`xvfb-run -a -s "-screen 0 1280x1024x24" pvpython ...` (Debian packages xvfb and xauth);
`--force-offscreen-rendering` does not help there, it still needs an X server.

The time shown is the output time with the most nodes in contact (`contact_status` > 0; ties go
to the larger total `normal_force`), which is the default (`--at-impact`), or the output time
nearest to `--time T`. The bodies are warped by `displacement` (times `--scale`, default 1: the
true deformed shape) and coloured by `--field` (point or cell data, default the von Mises
stress per tet) with a colour bar. The field output holds only the deformable bodies, so the
rigid ground is drawn as a grey slab whose top is z = `--ground-z` (default 0, the ball's
ground). The camera looks horizontally along +y (the ball moves to the right); `--clip` cuts the
bodies at their mid y plane and shows the far half, so the stress inside a shell is seen.

Exit codes: 0 on success, 2 for a bad argument, a missing file, an unknown field or an output
without the needed arrays (with a one-line message on stderr).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

PROG = "render_fields.py"
# colour bar titles of the fields emcontact writes (others: the name; vectors: the magnitude)
LABELS = {"von_mises": "von Mises stress [Pa]", "normal_force": "normal force [N]",
          "displacement": "|displacement| [m]", "velocity": "|velocity| [m/s]",
          "contact_status": "contact status"}


def fail(message):
    sys.stderr.write(f"{PROG}: error: {message}\n")
    sys.stderr.flush()
    # os._exit: pvpython's own sys.exit handling may print a traceback or keep the exit code 0.
    os._exit(2)


def parse_args(argv):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    p.add_argument("xdmf", help="the run's fields.xdmf")
    p.add_argument("png", help="the PNG to write")
    when = p.add_mutually_exclusive_group()
    when.add_argument("--at-impact", action="store_true",
                      help="the output time with the most nodes in contact (default)")
    when.add_argument("--time", type=float, help="the output time nearest to T [s]")
    p.add_argument("--field", default="von_mises", help="point or cell array to colour by")
    p.add_argument("--scale", type=float, default=1.0, help="displacement scale (1 = true shape)")
    p.add_argument("--size", default="1200x900", help="image size WIDTHxHEIGHT in pixels")
    ground = p.add_mutually_exclusive_group()
    ground.add_argument("--ground-z", type=float, default=0.0, help="height of the rigid plane")
    ground.add_argument("--no-ground", action="store_true", help="draw no ground plane")
    p.add_argument("--clip", action="store_true", help="cut the bodies at their mid y plane")
    p.add_argument("--title", default=None, help="first title line (default: the run directory)")

    try:
        args = p.parse_args(argv)
    except SystemExit as e:  # argparse printed the message; keep its code (0 for --help)
        os._exit(e.code if isinstance(e.code, int) else 2)
    try:
        w, h = (int(v) for v in args.size.lower().split("x"))
        if w < 16 or h < 16:
            raise ValueError
    except ValueError:
        fail(f"--size {args.size!r}: expected WIDTHxHEIGHT, e.g. 1200x900")
    args.width, args.height = w, h
    return args


def scan_xdmf(xdmf):
    """{time: step number} from the Grid names `step_N` our writer uses (empty if none).

    Also checks that every HDF5 file the XDMF names exists: the XDMF library aborts on a missing
    one, without a message that names it."""
    try:
        root = ET.parse(xdmf).getroot()
    except ET.ParseError as e:
        fail(f"{xdmf}: not an XDMF file ({e})")
    if root.tag != "Xdmf":
        fail(f"{xdmf}: not an XDMF file (root element <{root.tag}>)")
    base = os.path.dirname(xdmf)
    for item in root.iter("DataItem"):
        if item.get("Format", "XML").upper() == "HDF" and item.text:
            h5 = item.text.strip().split(":", 1)[0]
            if not os.path.isfile(os.path.join(base, h5)):
                fail(f"{xdmf}: the HDF5 file {h5} it names does not exist")
    steps = {}
    for grid in root.iter("Grid"):
        name = grid.get("Name", "")
        time = grid.find("Time")
        if name.startswith("step_") and time is not None:
            try:
                steps[float(time.get("Value"))] = int(name[len("step_"):])
            except (TypeError, ValueError):
                pass
    return steps


def main(argv):
    args = parse_args(argv)
    xdmf = os.path.abspath(args.xdmf)
    if not os.path.isfile(xdmf):
        fail(f"no such file: {args.xdmf}")
    out_dir = os.path.dirname(os.path.abspath(args.png))
    if not os.path.isdir(out_dir):
        fail(f"the directory of {args.png} does not exist")
    steps = scan_xdmf(xdmf)

    # Imported here so that argument and file errors are reported without starting ParaView.
    from paraview import servermanager
    from paraview.simple import (ColorBy, Clip, CreateRenderView, GetColorTransferFunction,
                                 GetScalarBar, MergeBlocks, Box, SaveScreenshot, Show, Text,
                                 WarpByVector, Xdmf3ReaderS)
    from vtkmodules.numpy_interface import dataset_adapter as dsa

    reader = Xdmf3ReaderS(FileName=[xdmf])
    reader.UpdatePipelineInformation()
    point_arrays = list(reader.PointArrays)  # what the XDMF declares (all read by default)
    cell_arrays = list(reader.CellArrays)
    if not point_arrays and not cell_arrays:
        fail(f"{args.xdmf}: no arrays read (missing or unreadable HDF5 files next to it?)")
    if args.field in cell_arrays:
        association = "CELLS"
    elif args.field in point_arrays:
        association = "POINTS"
    else:
        fail(f"{args.xdmf}: no field {args.field!r}; point data: {', '.join(point_arrays)}; "
             f"cell data: {', '.join(cell_arrays)}")
    if "displacement" not in point_arrays:
        fail(f"{args.xdmf}: no point field 'displacement' to warp by")
    times = reader.TimestepValues  # a list, a single float, or empty without time steps
    times = [float(times)] if isinstance(times, (int, float)) else (list(times) or [0.0])
    merged = MergeBlocks(Input=reader)  # one unstructured grid whatever the XDMF's grid layout

    def fetch(t):
        merged.UpdatePipeline(t)
        return dsa.WrapDataObject(servermanager.Fetch(merged))

    if args.time is not None:
        t = min(times, key=lambda v: abs(v - args.time))
        data = fetch(t)
    else:
        if "contact_status" not in point_arrays:
            fail(f"{args.xdmf}: no point field 'contact_status' to find the impact "
                 "(use --time T)")
        best = None
        for v in times:
            d = fetch(v)
            status = d.PointData["contact_status"]
            n = int((status > 0).sum())
            force = float(d.PointData["normal_force"].sum()) if "normal_force" in point_arrays \
                else 0.0
            if best is None or (n, force) > best[:2]:
                best = (n, force, v)
        if best[0] == 0:
            sys.stderr.write(f"{PROG}: warning: no node is in contact at any output time; "
                             "showing the last one\n")
            t = times[-1]
        else:
            t = best[2]
        data = fetch(t)
    step = next((s for v, s in steps.items() if abs(v - t) <= 1e-9 * max(1.0, abs(t))), None)
    n_contact = int((data.PointData["contact_status"] > 0).sum()) \
        if "contact_status" in point_arrays else None
    values = data.CellData[args.field] if association == "CELLS" else data.PointData[args.field]
    if len(values.shape) > 1:  # a vector: colour by its magnitude
        import numpy as np
        values = np.linalg.norm(values, axis=1)
    lo, hi = float(values.min()), float(values.max())
    if hi <= lo:
        hi = lo + 1.0
    points = data.Points + args.scale * data.PointData["displacement"]
    pmin, pmax = points.min(axis=0), points.max(axis=0)
    center = (pmin + pmax) / 2
    extent = float(max(pmax - pmin))
    # The frame: the bodies and, if drawn, the ground slab's top (a slab 0.08 extent thick).
    slab = 0.08 * extent
    zlo = float(pmin[2]) if args.no_ground else min(float(pmin[2]), args.ground_z - slab)
    zhi = max(float(pmax[2]), zlo + slab)
    aspect = args.width / args.height
    # half the view's height: the scene fills 80% of the height (the title above it) and
    # leaves room for the colour bar on the right
    view_half = 1.25 * max(0.5 * (zhi - zlo), 0.5 * float(pmax[0] - pmin[0]) * 1.3 / aspect)

    view = CreateRenderView()
    view.ViewSize = [args.width, args.height]
    view.ViewTime = t
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "BackgroundColorMode"):
        view.BackgroundColorMode = "Single Color"

    warp = WarpByVector(Input=merged, Vectors=["POINTS", "displacement"],
                        ScaleFactor=args.scale)
    shown = warp
    if args.clip:
        # keep y > mid: the camera looks along +y, so the cut face is towards it
        shown = Clip(Input=warp, ClipType="Plane")
        shown.ClipType.Origin = [float(center[0]), float(center[1]), float(center[2])]
        shown.ClipType.Normal = [0.0, 1.0, 0.0]
        if hasattr(shown, "Invert"):
            shown.Invert = 0
    body = Show(shown, view)
    body.Representation = "Surface With Edges"
    body.EdgeColor = [0.15, 0.15, 0.15]
    if hasattr(body, "EdgeOpacity"):
        body.EdgeOpacity = 0.35
    ColorBy(body, (association, args.field))
    lut = GetColorTransferFunction(args.field)
    lut.ApplyPreset("Turbo", True)
    lut.RescaleTransferFunction(lo, hi)
    if hasattr(lut, "AutomaticRescaleRangeMode"):
        lut.AutomaticRescaleRangeMode = "Never"
    body.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = LABELS.get(args.field, args.field.replace("_", " "))
    bar.ComponentTitle = ""
    bar.TitleColor = [0.0, 0.0, 0.0]
    bar.LabelColor = [0.0, 0.0, 0.0]
    font = args.height / 900.0  # font sizes are in pixels: scale them with the image
    bar.TitleFontSize = max(8, round(20 * font))
    bar.LabelFontSize = max(8, round(18 * font))
    bar.TitleBold = 1
    bar.ScalarBarLength = 0.55
    bar.ScalarBarThickness = max(8, round(20 * font))
    bar.WindowLocation = "Any Location"
    bar.Position = [0.86, 0.3]  # above the ground band
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = "%-#.3g"
    bar.RangeLabelFormat = "%-#.3g"
    bar.AddRangeLabels = 1

    if not args.no_ground:
        # a slab under z = ground: seen edge-on, its front face is a band below the bodies
        ground = Box(XLength=4.0 * view_half * aspect, YLength=2.0 * extent, ZLength=slab,
                     Center=[float(center[0]), float(center[1]), args.ground_z - slab / 2])
        g = Show(ground, view)
        g.ColorArrayName = ["POINTS", ""]
        g.AmbientColor = g.DiffuseColor = [0.72, 0.72, 0.70]
        g.Representation = "Surface"

    title = Text(Text=(args.title or os.path.basename(os.path.dirname(xdmf)) or "emcontact")
                 + "\n" + f"t = {t:.4g} s"
                 + (f", step {step}" if step is not None else "")
                 + (f", {n_contact} nodes in contact" if n_contact is not None else "")
                 + "\n" + f"deformed shape (displacement x {args.scale:g})"
                 + (", cut at the mid y plane" if args.clip else ""))
    td = Show(title, view)
    td.WindowLocation = "Upper Center"
    td.FontSize = max(8, round(26 * font))
    td.Color = [0.0, 0.0, 0.0]
    td.Justification = "Center"

    # Horizontal view along +y at the deformed bodies: the ground is seen edge-on, so the
    # flattened contact is a straight line on its top edge. The scene's centre is at 45% of
    # the height: 5% margin below it, 15% above it for the title.
    focal = [float(center[0]), float(center[1]), 0.5 * (zlo + zhi) + 0.1 * view_half]
    view.CameraFocalPoint = focal
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraPosition = [focal[0], focal[1] - 4.6 * extent, focal[2]]
    view.CameraParallelProjection = 1  # orthographic: the ground's top face stays edge-on
    view.CameraParallelScale = view_half
    view.StillRender()
    SaveScreenshot(args.png, view, ImageResolution=[args.width, args.height],
                   TransparentBackground=0)
    if not os.path.isfile(args.png):
        fail(f"ParaView wrote no {args.png}")
    print(f"{args.png}: t = {t:.6g} s"
          + (f" (step {step})" if step is not None else "")
          + (f", {n_contact} nodes in contact" if n_contact is not None else "")
          + f", {args.field} {lo:.4g} .. {hi:.4g}")
    sys.stdout.flush()


if __name__ == "__main__":
    main(sys.argv[1:])
