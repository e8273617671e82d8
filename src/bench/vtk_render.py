#!/usr/bin/env python3
"""VTK peer of `shellmarch bench render`: the same mesh, view, image size and transfer function
rendered by vtkUnstructuredGridVolumeRayCastMapper (Bunyk ray casting, multithreaded on the CPU,
its image shown through OpenGL, which is Mesa llvmpipe here).

The job file (--job, written by shellmarch) gives the mesh, the point array, the camera per image
size, the transfer function as shellmarch's table, the ray integrators and the run count. For each
size and integrator: one cold frame (VTK builds its face structures and integration tables), then
--runs warm frames, and the last frame read back as an RGBA PNG over a black, transparent
background, i.e. premultiplied colour and opacity like shellmarch's images. Writes JSON to --json.
Exit status 3 when VTK cannot be imported.
"""
import argparse
import json
import os
import resource
import statistics
import sys
import time

from vtk_common import read_pieces, timed, weld


def cpu_seconds():
    """Processor time of this process (VTK's ray casting threads and llvmpipe's included)."""
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime


def timed_frame(window):
    """Wall and processor seconds of one frame."""
    c, t = cpu_seconds(), time.perf_counter()
    window.Render()
    return time.perf_counter() - t, cpu_seconds() - c

INTEGRATORS = {
    "linear": "vtkUnstructuredGridLinearRayIntegrator",
    "partial": "vtkUnstructuredGridPartialPreIntegration",
    "preintegration": "vtkUnstructuredGridPreIntegration",
    "homogeneous": "vtkUnstructuredGridHomogeneousRayIntegrator",
}


def load(vtk, path, array):
    """Read, weld the pieces (vtk_common.py) and split every cell into tetrahedra (the Bunyk ray
    caster walks tetrahedra only)."""
    pieces, t_read = timed(lambda: read_pieces(vtk, path, [array]))
    welded, t_weld = timed(lambda: weld(vtk, pieces))
    tets = vtk.vtkDataSetTriangleFilter()
    tets.TetrahedraOnlyOn()
    tets.SetInputData(welded)
    _, t_tet = timed(tets.Update)
    out = tets.GetOutput()
    out.GetPointData().SetActiveScalars(array)
    setup = {"read_seconds": t_read, "weld_seconds": t_weld, "tetrahedralize_seconds": t_tet,
             "cells": welded.GetNumberOfCells(), "points_welded": welded.GetNumberOfPoints(),
             "tetrahedra": out.GetNumberOfCells()}
    return out, setup


def volume_property(vtk, tf):
    """shellmarch's table as piecewise-linear functions with one control point per entry, so both
    interpolate the same values; opacity per unit distance as shellmarch's extinction."""
    lo, hi, table = tf["lo"], tf["hi"], tf["table"]
    color = vtk.vtkColorTransferFunction()
    color.SetColorSpaceToRGB()
    color.ClampingOn()
    opacity = vtk.vtkPiecewiseFunction()
    opacity.ClampingOn()
    n = len(table)
    for i, (r, g, b, a) in enumerate(table):
        s = lo + (hi - lo) * i / (n - 1)
        color.AddRGBPoint(s, r, g, b)
        opacity.AddPoint(s, a * tf["opacity_scale"])
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(tf["unit_distance"])
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    prop.IndependentComponentsOn()
    return prop


def set_camera(vtk, renderer, view, width, height):
    cam = renderer.GetActiveCamera()
    cam.SetPosition(*view["eye"])
    cam.SetFocalPoint(*view["at"])
    cam.SetViewUp(*view["up"])
    cam.SetViewAngle(view["fovy_deg"])
    # The Bunyk caster sends pixel (x, y)'s ray (y from the bottom) through the image-plane point
    # (x, y), a pixel corner; shellmarch through the centre (x + 0.5, y + 0.5). Moving VTK's window
    # centre by half a pixel (1/W, 1/H in normalised coordinates) makes them the same rays.
    cam.SetWindowCenter(1.0 / width, 1.0 / height)
    renderer.ResetCameraClippingRange()


def save_rgba(vtk, window, path):
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGBA()
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def render_size(vtk, window, renderer, mapper, size, job):
    set_camera(vtk, renderer, size["view"], size["width"], size["height"])
    window.SetSize(size["width"], size["height"])
    results = []
    for name in job["integrators"]:
        mapper.SetRayIntegrator(getattr(vtk, INTEGRATORS[name])())
        cold, _ = timed_frame(window)
        frames = [timed_frame(window) for _ in range(job["runs"])]
        warm, warm_cpu = [f[0] for f in frames], [f[1] for f in frames]
        image = os.path.join(job["out_dir"], f"vtk_{name}_{size['width']}x{size['height']}.png")
        save_rgba(vtk, window, image)
        results.append({"integrator": name, "class": INTEGRATORS[name],
                        "cold_first_frame_ms": cold * 1e3,
                        # runs 0: the first image alone (bench render's first-image block)
                        "warm_ms": statistics.median(warm) * 1e3 if warm else None,
                        "warm_cpu_ms": statistics.median(warm_cpu) * 1e3 if warm else None,
                        "warm_ms_all": [w * 1e3 for w in warm], "image": image})
    return {"width": size["width"], "height": size["height"], "integrators": results}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--job", required=True)
    ap.add_argument("--json", required=True)
    args = ap.parse_args()
    with open(args.job) as f:
        job = json.load(f)
    for name in job["integrators"]:
        if name not in INTEGRATORS:
            raise SystemExit(f"unknown integrator '{name}' (use {', '.join(INTEGRATORS)})")
    try:
        import vtkmodules.all as vtk
    except ImportError as e:
        print(f"cannot import VTK with {sys.executable}: {e}", file=sys.stderr)
        sys.exit(3)
    grid, setup = load(vtk, job["mesh"], job["array"])
    mapper = vtk.vtkUnstructuredGridVolumeRayCastMapper()
    mapper.SetInputData(grid)
    mapper.AutoAdjustSampleDistancesOff()
    mapper.SetImageSampleDistance(1.0)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(volume_property(vtk, job["tf"]))
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(0, 0, 0)
    renderer.SetBackgroundAlpha(0.0)
    renderer.AddVolume(volume)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetAlphaBitPlanes(1)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    sizes = [render_size(vtk, window, renderer, mapper, s, job) for s in job["sizes"]]
    caps = window.ReportCapabilities() or ""
    gl = next((l.split(":", 1)[1].strip() for l in caps.splitlines() if "OpenGL renderer" in l), "")
    out = {"vtk_version": vtk.vtkVersion.GetVTKVersion(), "mapper": "vtkUnstructuredGridVolumeRayCastMapper",
           "ray_cast_function": mapper.GetRayCastFunction().GetClassName(),
           "threads": mapper.GetNumberOfThreads(), "gl_renderer": gl, "setup": setup, "sizes": sizes}
    with open(args.json, "w") as f:
        json.dump(out, f, indent=2)


if __name__ == "__main__":
    main()
