#!/usr/bin/env python3
"""VTK peer of `shellmarch bench prep`: read the same .pvtu, weld its pieces, extract the surface.

Times (median of --runs, each in this one process) reading the pieces with
vtkXMLPUnstructuredGridReader, welding their coincident points with vtkAppendFilter(MergePoints)
(see vtk_common.py), and surface extraction with vtkDataSetSurfaceFilter and vtkGeometryFilter.
Writes JSON to --json.
Exit status 3 when VTK cannot be imported.
"""
import argparse
import json
import resource
import statistics
import sys

from vtk_common import read_pieces, timed, weld


def rss_bytes(key):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(key):
                return int(line.split()[1]) * 1024
    return 0


def surface(vtk, grid, cls):
    f = cls()
    f.SetInputData(grid)
    f.Update()
    return f.GetOutput()


def one_run(vtk, path):
    pieces, t_read = timed(lambda: read_pieces(vtk, path))
    welded, t_weld = timed(lambda: weld(vtk, pieces))
    surf, t_surf = timed(lambda: surface(vtk, welded, vtk.vtkDataSetSurfaceFilter))
    geom, t_geom = timed(lambda: surface(vtk, welded, vtk.vtkGeometryFilter))
    counts = {
        "pieces": len(pieces),
        "cells": welded.GetNumberOfCells(),
        "points_read": sum(p.GetNumberOfPoints() for p in pieces),
        "points_welded": welded.GetNumberOfPoints(),
        "surface_polygons": surf.GetNumberOfCells(),
        "geometry_polygons": geom.GetNumberOfCells(),
    }
    return {"read": t_read, "weld": t_weld, "surface": t_surf, "geometry": t_geom}, counts


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--json", required=True)
    args = ap.parse_args()
    try:
        import vtkmodules.all as vtk
    except ImportError as e:
        print(f"cannot import VTK with {sys.executable}: {e}", file=sys.stderr)
        sys.exit(3)
    vtk.vtkSMPTools.Initialize(args.threads)
    start_rss = rss_bytes("VmRSS:")
    times = {"read": [], "weld": [], "surface": [], "geometry": []}
    counts = {}
    for _ in range(args.runs):
        t, counts = one_run(vtk, args.mesh)
        for k, v in t.items():
            times[k].append(v)
    med = {k: statistics.median(v) for k, v in times.items()}
    out = {
        "vtk_version": vtk.vtkVersion.GetVTKVersion(),
        "smp_backend": vtk.vtkSMPTools.GetBackend(),
        "threads": args.threads,
        "runs": args.runs,
        "read_seconds": med["read"],
        "weld_seconds": med["weld"],
        "surface_seconds": med["surface"],
        "geometry_seconds": med["geometry"],
        "total_seconds": med["read"] + med["weld"] + med["surface"],
        "seconds_all": times,
        "start_rss_bytes": start_rss,
        "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
    }
    out.update(counts)
    with open(args.json, "w") as f:
        json.dump(out, f, indent=2)


if __name__ == "__main__":
    main()
