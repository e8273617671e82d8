#!/usr/bin/python3
"""shellmarch's colour and opacity maps against VTK's own (python3-vtk9), run by ctest as
    vtk_peers_test.py TF_PROBE

1. Random colour nodes (midpoints and sharpnesses included) in RGB, Lab, HSV (with and without
   HSVWrap), Diverging and Step, against vtkColorTransferFunction::GetTable.
2. Random opacity nodes against vtkPiecewiseFunction::GetTable.
3. Every ParaView preset shellmarch ships, as `--colormap NAME` builds it, against the same
   control points given to vtkColorTransferFunction (duplicate points allowed, as ParaView allows
   them), and a ParaView .json map with "Points" against vtkPiecewiseFunction.
Prolab is not in VTK 9.1; tests/scene/control_points_test.cpp checks it against values of VTK's
own test instead.
"""
import json
import os
import random
import subprocess
import sys
import tempfile

import vtk

PROBE = sys.argv[1]
N = 301  # samples: not a multiple of the nodes' spacing, so most fall between nodes
failures = []


def probe(args, stdin=""):
    r = subprocess.run([PROBE] + args, input=stdin, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"tf_probe {' '.join(args)} failed: {r.stderr}")
    return [[float(v) for v in line.split()] for line in r.stdout.splitlines()]


def compare(what, ours, theirs, tolerance):
    worst = max(abs(a - b) for ra, rb in zip(ours, theirs) for a, b in zip(ra, rb))
    if len(ours) != len(theirs) or worst > tolerance:
        failures.append(f"{what}: differs from VTK by {worst:.3g} (tolerance {tolerance:g})")
    return worst


def vtk_colors(ctf, n):
    table = [0.0] * (3 * n)
    ctf.GetTable(0.0, 1.0, n, table)
    return [table[3 * i:3 * i + 3] for i in range(n)]


def random_shape(rng):
    sharp = rng.choice([0.0, 0.0, 0.005, 0.2, 0.5, 0.8, 0.995, 1.0, rng.random()])
    mid = rng.choice([0.5, 0.0, 1.0, rng.random(), rng.random()])
    return mid, sharp


def random_xs(rng, count):
    inner = sorted(rng.random() for _ in range(count - 2))
    return [0.0] + inner + [1.0]


SPACES = {"RGB": "SetColorSpaceToRGB", "Lab": "SetColorSpaceToLab", "HSV": "SetColorSpaceToHSV",
          "Diverging": "SetColorSpaceToDiverging", "Step": "SetColorSpaceToStep"}


def color_cases(rng):
    worst = 0.0
    for case in range(240):
        space = list(SPACES)[case % len(SPACES)]
        wrap = case % 2 if space == "HSV" else 0
        nodes = []
        for x in random_xs(rng, rng.randint(2, 6)):
            mid, sharp = random_shape(rng)
            nodes.append((x, rng.random(), rng.random(), rng.random(), mid, sharp))
        ctf = vtk.vtkColorTransferFunction()
        getattr(ctf, SPACES[space])()
        ctf.SetHSVWrap(wrap)
        for node in nodes:
            ctf.AddRGBPoint(*node)
        text = "".join(" ".join(repr(v) for v in node) + "\n" for node in nodes)
        ours = probe(["color", space, str(wrap), str(N)], text)
        worst = max(worst, compare(f"colour case {case} ({space}, wrap {wrap}, nodes {nodes})",
                                   ours, vtk_colors(ctf, N), 1e-9))
    print(f"colour nodes: 240 random maps, largest difference {worst:.3g}")


def opacity_cases(rng):
    worst = 0.0
    for case in range(120):
        nodes = []
        for x in random_xs(rng, rng.randint(2, 6)):
            mid, sharp = random_shape(rng)
            nodes.append((x, rng.random(), mid, sharp))
        pwf = vtk.vtkPiecewiseFunction()
        for node in nodes:
            pwf.AddPoint(*node)
        table = [0.0] * N
        pwf.GetTable(0.0, 1.0, N, table)
        text = "".join(" ".join(repr(v) for v in node) + "\n" for node in nodes)
        ours = probe(["opacity", str(N)], text)
        worst = max(worst, compare(f"opacity case {case} (nodes {nodes})", ours,
                                   [[v] for v in table], 1e-12))
    print(f"opacity nodes: 120 random functions, largest difference {worst:.3g}")


def vtk_map(preset):
    """A vtkColorTransferFunction of a ParaView map, its points rescaled to [0, 1]."""
    pts = preset["RGBPoints"]
    xs = pts[0::4]
    x0, x1 = min(xs), max(xs)
    ctf = vtk.vtkColorTransferFunction()
    ctf.AllowDuplicateScalarsOn()
    space = {"CIELAB": "Lab", "Lab": "Lab"}.get(preset.get("ColorSpace", "RGB"),
                                               preset.get("ColorSpace", "RGB"))
    getattr(ctf, SPACES[space])()
    ctf.SetHSVWrap(0)
    for i in range(0, len(pts), 4):
        ctf.AddRGBPoint((pts[i] - x0) / (x1 - x0), *pts[i + 1:i + 4])
    return ctf


def preset_cases():
    texts = subprocess.run([PROBE, "presets"], capture_output=True, text=True,
                           check=True).stdout.splitlines()
    worst = 0.0
    for text in texts:
        preset = json.loads(text)
        name = preset["Name"]
        ours = [row[:3] for row in probe(["table", name, "256"])]
        # The table is single precision.
        worst = max(worst, compare(f"preset '{name}'", ours, vtk_colors(vtk_map(preset), 256),
                                   2e-6))
    print(f"presets: {len(texts)} maps, largest difference {worst:.3g}")
    if len(texts) < 30:
        failures.append(f"only {len(texts)} presets")


def json_opacity_case(rng, folder):
    points = []
    for x in random_xs(rng, 5):
        mid, sharp = random_shape(rng)
        points += [-2 + 5 * x, rng.random(), mid, sharp]
    m = {"Name": "probe", "ColorSpace": "RGB", "RGBPoints": [-2, 0, 0, 0, 3, 1, 1, 1],
         "Points": points}
    path = os.path.join(folder, "probe.json")
    with open(path, "w") as f:
        json.dump(m, f)
    pwf = vtk.vtkPiecewiseFunction()
    for i in range(0, len(points), 4):
        pwf.AddPoint((points[i] + 2) / 5, *points[i + 1:i + 4])
    table = [0.0] * 256
    pwf.GetTable(0.0, 1.0, 256, table)
    ours = [row[3:] for row in probe(["table", path, "256"])]
    worst = compare(f"'Points' of {m}", ours, [[v] for v in table], 1e-6)
    print(f"ParaView .json opacity points: largest difference {worst:.3g}")


def main():
    rng = random.Random(43)
    color_cases(rng)
    opacity_cases(rng)
    preset_cases()
    with tempfile.TemporaryDirectory() as folder:
        json_opacity_case(rng, folder)
    for f in failures[:20]:
        print("FAIL:", f)
    print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
