#!/usr/bin/env python3
"""Seed corpora for the fuzz targets, from the test fixtures (ci/fuzz.sh runs this).

    make_seeds.py OUT_DIR REPO_ROOT SHARED_DATA_DIR

Writes OUT_DIR/<target>/ for vtu, pvtu, legacy_vtk, ugrid and colormap. The cache seeds come from
fuzz_make_cache_seed (the real cache writer), which ci/fuzz.sh runs next. Input layouts are the
ones tests/fuzz/fuzz_inputs.h defines: .pvtu bundles, and .ugrid with a leading variant byte.
"""
import json
import os
import shutil
import struct
import sys

PIECE_SEPARATOR = b"\n===piece===\n"
# Index = the variant byte of fuzz_inputs.cpp's ugridVariants().
UGRID_VARIANTS = ["", "b8", "lb8", "b8l", "lb8l", "b4", "lb4", "r8", "lr8", "r4", "lr4"]


def copy_matching(src_dir, suffix, dst_dir):
    if not os.path.isdir(src_dir):
        return
    for name in sorted(os.listdir(src_dir)):
        if name.endswith(suffix):
            shutil.copyfile(os.path.join(src_dir, name), os.path.join(dst_dir, name))


def pvtu_bundles(data_dir, dst_dir):
    """weld.pvtu with its pieces, whole and as a one-piece index."""
    with open(os.path.join(data_dir, "weld.pvtu"), "rb") as f:
        index = f.read()
    pieces = []
    for k in range(3):
        with open(os.path.join(data_dir, "weld", "weld_%d.vtu" % k), "rb") as f:
            pieces.append(f.read())
    with open(os.path.join(dst_dir, "weld3"), "wb") as f:
        f.write(PIECE_SEPARATOR.join([index] + pieces))
    one = index.split(b"<Piece")
    one_index = one[0] + b"<Piece" + one[1].split(b"/>")[0] + b"/>\n  </PUnstructuredGrid>\n</VTKFile>\n"
    with open(os.path.join(dst_dir, "weld1"), "wb") as f:
        f.write(PIECE_SEPARATOR.join([one_index, pieces[0]]))


# One element of each kind plus a boundary triangle and quad, in UGRID node order (the grid of
# tests/io/ugrid_reader_test.cpp).
XYZ = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1,
       2, 0, 0, 3, 0, 0, 2, 1, 0, 2, 0, 1, 3, 0, 1, 2, 1, 1,
       5, 0, 0, 6, 0, 0, 5, 1, 0, 5, 0, 1,
       8, 0, 0, 9, 0, 0, 9, 1, 0, 8, 1, 0, 8, 0, 1, 9, 0, 1, 9, 1, 1, 8, 1, 1]
TRIS, QUADS, TAGS = [1, 2, 5], [1, 2, 3, 4], [7, 8]
TETS, PYRS, PRISMS = [12, 13, 14, 15], [1, 4, 5, 2, 3], [6, 7, 8, 9, 10, 11]
HEXES = [16, 17, 18, 19, 20, 21, 22, 23]
COUNTS = [len(XYZ) // 3, 1, 1, 1, 1, 1, 1]
INTS = TRIS + QUADS + TAGS + TETS + PYRS + PRISMS + HEXES


def ugrid_bytes(variant):
    if variant == "":
        lines = [" ".join(map(str, COUNTS))]
        lines += [" ".join(map(str, XYZ[i:i + 3])) for i in range(0, len(XYZ), 3)]
        lines += [str(i) for i in INTS]
        return ("\n".join(lines) + "\n").encode()
    fortran = variant.lstrip("l").startswith("r")
    end = "<" if variant.startswith("l") else ">"
    isz = 8 if variant.endswith("8l") else 4
    rsz = 8 if "8" in variant else 4
    ifmt, rfmt = end + ("q" if isz == 8 else "i"), end + ("d" if rsz == 8 else "f")
    head = b"".join(struct.pack(ifmt, c) for c in COUNTS)
    body = b"".join(struct.pack(rfmt, x) for x in XYZ) + b"".join(struct.pack(ifmt, i) for i in INTS)
    out = b""
    for record in (head, body):
        marker = struct.pack(end + "i", len(record)) if fortran else b""
        out += marker + record + marker
    return out


COLORMAPS = {
    "cool_to_warm.json": [{
        "Name": "Cool to Warm", "ColorSpace": "Diverging", "NanColor": [1, 1, 0],
        "RGBPoints": [0, 0.23, 0.299, 0.754, 0.5, 0.865, 0.865, 0.865, 1, 0.706, 0.016, 0.15],
        "Points": [0, 0, 0.5, 0, 1, 1, 0.5, 0]}],
    "lab.json": {"ColorSpace": "Lab", "RGBPoints": [-3, 0, 0, 0, 7, 1, 1, 1]},
    "hsv.json": {"ColorSpace": "HSV", "RGBPoints": [0, 1, 0, 0, 0.3, 0, 1, 0, 1, 0, 0, 1],
                 "Points": [0, 0.2, 0.5, 0]},
    "rgb.json": {"ColorSpace": "RGB", "RGBPoints": [0, 0, 0, 1, 1, 1, 0, 0],
                 "Points": [0, 0, 0.5, 0, 0.4, 0.8, 0.5, 0, 1, 0.1, 0.5, 0]},
    "step.json": {"ColorSpace": "Step", "RGBPoints": [0, 1, 0, 0, 0.5, 0, 1, 0, 1, 0, 0, 1],
                  "Points": [0, 0, 0.3, 0.7, 1, 1, 0.5, 1]},
    "prolab.json": {"ColorSpace": "Prolab", "HSVWrap": 1,
                    "RGBPoints": [0, 1, 0, 0, 0.5, 0.2, 0.9, 0.1, 1, 0, 0, 1]},
}


def main():
    out, root, shared = sys.argv[1], sys.argv[2], sys.argv[3]
    fixtures = os.path.join(root, "tests", "io", "data")
    for target in ("vtu", "pvtu", "legacy_vtk", "ugrid", "colormap", "cache"):
        os.makedirs(os.path.join(out, target), exist_ok=True)
    copy_matching(fixtures, ".vtu", os.path.join(out, "vtu"))
    copy_matching(shared, ".vtu", os.path.join(out, "vtu"))
    copy_matching(fixtures, ".vtk", os.path.join(out, "legacy_vtk"))
    copy_matching(shared, ".vtk", os.path.join(out, "legacy_vtk"))
    pvtu_bundles(fixtures, os.path.join(out, "pvtu"))
    for k, v in enumerate(UGRID_VARIANTS):
        with open(os.path.join(out, "ugrid", "grid_%s" % (v or "ascii")), "wb") as f:
            f.write(bytes([k]) + ugrid_bytes(v))
    for name, value in COLORMAPS.items():
        with open(os.path.join(out, "colormap", name), "w") as f:
            json.dump(value, f)


if __name__ == "__main__":
    main()
