"""Render a field of a perifem Exodus II file to PNG with ParaView, off-screen.

    pvbatch scripts/render_fields.py RUN.e OUT.png [--field damage] [--time T | --step K]
            [--view iso|top|front|back|side] [--clip-y Y] [--range LO,HI] [--size W H] [--zoom Z]
            [--keep FIELD,LO,HI]

PD bodies (SPHERE blocks) are drawn as points, FE bodies (HEX8 blocks) as surfaces, on their
deformed positions (the reader applies the displacements), coloured by the field (a point
field such as damage, velocity_z, eqps, fragment; a vector field by its magnitude).
--time picks the last output at or before T seconds (default: the last output), --step the
K-th output (0 first; negative counts from the end). --clip-y Y keeps what lies at y <= Y
(whole cells), to look inside: --view back then faces the cut. --keep FIELD,LO,HI draws only
the cells whose points all lie in the range (damage,0,0.99: without the points that have lost
every bond, which stretch the FE cells they belong to across the picture). Needs pvbatch (Debian paraview, python3-paraview); run it
with a clean environment when a user Python is set up: env -i PATH=/usr/bin:/bin pvbatch ...
"""
import argparse
import sys

from paraview.simple import (Clip, ColorBy, ExodusIIReader, GetColorTransferFunction,
                             GetScalarBar, SaveScreenshot, CreateView, Show, Text, Threshold)

VIEWS = {  # camera direction (from the focal point towards the camera) and view-up
    "iso": ((1.0, -1.6, 1.2), (0, 0, 1)),
    "top": ((0, 0, 1), (0, 1, 0)),
    "front": ((0, -1, 0), (0, 0, 1)),
    "back": ((0, 1, 0), (0, 0, 1)),  # onto the cut face of --clip-y
    "side": ((1, 0, 0), (0, 0, 1)),
}


def main():
    ap = argparse.ArgumentParser(description="Render a perifem Exodus field to PNG")
    ap.add_argument("exodus")
    ap.add_argument("png")
    ap.add_argument("--field", default="damage")
    ap.add_argument("--time", type=float)
    ap.add_argument("--step", type=int)
    ap.add_argument("--view", choices=sorted(VIEWS), default="iso")
    ap.add_argument("--clip-y", type=float)
    ap.add_argument("--keep", help="FIELD,LO,HI: draw only cells whose points all have LO <= FIELD <= HI "
                    "(e.g. damage,0,0.99 hides the points that have lost every bond)")
    ap.add_argument("--range", help="LO,HI: the colour scale (default: the data's range)")
    ap.add_argument("--size", type=int, nargs=2, default=(1200, 800))
    ap.add_argument("--zoom", type=float, default=1.0, help="magnify the framed view by this")
    ap.add_argument("--title", default=None)
    a = ap.parse_args()

    reader = ExodusIIReader(FileName=[a.exodus])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) or [0.0]
    if a.step is not None:
        t = times[a.step]
    elif a.time is not None:
        earlier = [x for x in times if x <= a.time * (1 + 1e-9)]
        t = earlier[-1] if earlier else times[0]
    else:
        t = times[-1]
    fields = list(reader.PointData.keys())
    # ParaView joins displacement_x, _y, _z into the vector "displacement_"
    if a.field in fields:
        array, component = a.field, None
    elif a.field + "_" in fields:
        array, component = a.field + "_", "Magnitude"
    elif a.field[-2:] in ("_x", "_y", "_z") and a.field[:-1] in fields:
        array, component = a.field[:-1], a.field[-1].upper()
    else:
        print("render_fields: %s has no point field '%s' (it has: %s)" % (a.exodus, a.field, ", ".join(fields)),
              file=sys.stderr)
        sys.exit(2)

    source = reader
    if a.keep:
        name, lo, hi = a.keep.split(",")
        if name not in fields:
            print("render_fields: %s has no point field '%s' for --keep" % (a.exodus, name), file=sys.stderr)
            sys.exit(2)
        source = Threshold(Input=source, Scalars=["POINTS", name], LowerThreshold=float(lo),
                           UpperThreshold=float(hi), AllScalars=1)
    if a.clip_y is not None:
        source = Clip(Input=source, ClipType="Plane", Crinkleclip=1)
        source.ClipType.Origin = [0.0, a.clip_y, 0.0]
        source.ClipType.Normal = [0.0, 1.0, 0.0]
        source.Invert = 1

    view = CreateView("RenderView")
    view.ViewSize = list(a.size)
    view.ViewTime = t
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    try:  # ParaView >= 5.10: the palette's background would override the colour above
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    disp = Show(source, view)
    disp.Representation = "Surface"
    disp.PointSize = 4.0
    disp.RenderPointsAsSpheres = 1
    ColorBy(disp, ("POINTS", array) if component is None else ("POINTS", array, component))
    lut = GetColorTransferFunction(array)
    lut.ApplyPreset("Cool to Warm", True)
    if a.range:
        lo, hi = (float(x) for x in a.range.split(","))
        lut.RescaleTransferFunction(lo, hi)
    else:
        disp.RescaleTransferFunctionToDataRange(False, True)
    bar = GetScalarBar(lut, view)
    bar.Title = a.field
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    disp.SetScalarBarVisibility(view, True)
    label = Text(Text=a.title or "t = %.2f µs" % (t * 1e6))
    ldisp = Show(label, view)
    ldisp.Color = [0.1, 0.1, 0.1]
    ldisp.WindowLocation = "Upper Left Corner"

    view.ResetCamera()
    direction, up = VIEWS[a.view]
    cam = view.GetActiveCamera()
    fp = cam.GetFocalPoint()
    dist = cam.GetDistance()
    norm = sum(c * c for c in direction) ** 0.5
    cam.SetPosition(*[fp[i] + dist * direction[i] / norm for i in range(3)])
    cam.SetViewUp(*up)
    view.ResetCamera()
    cam.Zoom(a.zoom)
    SaveScreenshot(a.png, view, ImageResolution=list(a.size))
    print("%s: %s at t = %.4g s" % (a.png, a.field, t))


if __name__ == "__main__":
    main()
