"""Shared by the Python module's tests: small analytic meshes, a .vtu writer, a PNG reader and
the command line, so that the module's images can be checked against `shellmarch render`'s."""

import base64
import os
import struct
import subprocess
import tempfile
import zlib

import numpy as np

import shellmarch

CLI = os.environ.get("SHELLMARCH_CLI", "shellmarch")
VTK_TYPES = {"tetra": 10, "pyramid": 14, "wedge": 13, "hexahedron": 12}


def out_dir(name):
    """A fresh folder for a test's files (under SHELLMARCH_TEST_OUT when ctest runs it)."""
    base = os.environ.get("SHELLMARCH_TEST_OUT")
    if base:
        os.makedirs(base, exist_ok=True)
    return tempfile.mkdtemp(prefix=f"python-{name}-", dir=base)


def _grid(n):
    """(n+1)^3 grid points on [0, 1]^3 and the index of grid point (i, j, k)."""
    r = np.arange(n + 1) / n
    x, y, z = np.meshgrid(r, r, r, indexing="ij")
    points = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    return points, lambda i, j, k: (i * (n + 1) + j) * (n + 1) + k


CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]


def tet_box(n=4):
    """A unit cube of n^3 cubes, each split into 6 tetrahedra along its main diagonal (Kuhn's
    split: conforming between cubes), with the point field f = x + 2y + 3z."""
    points, at = _grid(n)
    tets = []
    for i in range(n):
        for j in range(n):
            for k in range(n):
                for p in [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]:
                    v = [0, 0, 0]
                    ids = [at(i, j, k)]
                    for axis in p:
                        v[axis] = 1
                        ids.append(at(i + v[0], j + v[1], k + v[2]))
                    if p in [(0, 2, 1), (1, 0, 2), (2, 1, 0)]:  # odd: positive volume
                        ids[1], ids[2] = ids[2], ids[1]
                    tets.append(ids)
    f = points @ np.array([1.0, 2.0, 3.0])
    return shellmarch.Mesh(points, {"tetra": np.array(tets, dtype=np.int64)},
                           point_data={"f": f.astype(np.float32)})


def mixed_box(n=4):
    """A unit cube of n^3 cubes: the column i = 0 as wedges (two per cube, their triangles at z
    faces only), cubes with i = 1 and j + k even as six pyramids about the cube's centre, the rest
    hexahedra: every face between elements is one both sides share. Point field g = x*y + z; cell
    field c = 10 * the element's first vertex's x + its block's number."""
    points, at = _grid(n)
    points = list(points)
    blocks = {"wedge": [], "pyramid": [], "hexahedron": []}
    for i in range(n):
        for j in range(n):
            for k in range(n):
                c = [at(i + a, j + b, k + d) for a, b, d in CORNERS]
                if i == 0:
                    blocks["wedge"] += [[c[0], c[1], c[2], c[4], c[5], c[6]],
                                        [c[0], c[2], c[3], c[4], c[6], c[7]]]
                elif i == 1 and (j + k) % 2 == 0:
                    centre = len(points)
                    points.append((np.array([i, j, k]) + 0.5) / n)
                    for face in [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5),
                                 (2, 3, 7, 6), (3, 0, 4, 7)]:
                        blocks["pyramid"].append([c[v] for v in face] + [centre])
                else:
                    blocks["hexahedron"].append(c)
    points = np.array(points)
    cells = {b: np.array(ids, dtype=np.int32) for b, ids in blocks.items()}
    g = (points[:, 0] * points[:, 1] + points[:, 2]).astype(np.float32)
    cell_c = [(10 * points[ids[:, 0], 0] + b).astype(np.float32) for b, ids in enumerate(cells.values())]
    return shellmarch.Mesh(points, cells, point_data={"g": g}, cell_data={"c": cell_c})


def _binary(array):
    raw = np.ascontiguousarray(array).tobytes()
    return base64.b64encode(struct.pack("<I", len(raw)) + raw).decode()


def _data_array(name, array, vtk_type, components=1):
    return (f'<DataArray type="{vtk_type}" Name="{name}" NumberOfComponents="{components}" '
            f'format="binary">{_binary(array)}</DataArray>\n')


def write_vtu(mesh, path):
    """The Mesh as a VTK XML .vtu (binary inline, exact values: Float64 points, Float32 fields)."""
    order = [b for b in ("tetra", "pyramid", "wedge", "hexahedron") if b in mesh.cells]
    conn = np.concatenate([mesh.cells[b].reshape(-1).astype(np.int64) for b in order])
    sizes = np.concatenate([np.full(len(mesh.cells[b]), mesh.cells[b].shape[1]) for b in order])
    types = np.concatenate([np.full(len(mesh.cells[b]), VTK_TYPES[b], np.uint8) for b in order])
    point_data = "".join(_data_array(k, np.asarray(v, np.float32), "Float32")
                         for k, v in mesh.point_data.items())
    cell_data = "".join(_data_array(k, np.asarray(v, np.float32), "Float32")
                        for k, v in mesh.cell_data.items())  # already in the order written
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
                'byte_order="LittleEndian" header_type="UInt32">\n<UnstructuredGrid>\n'
                f'<Piece NumberOfPoints="{len(mesh.points)}" NumberOfCells="{len(types)}">\n'
                f"<PointData>\n{point_data}</PointData>\n<CellData>\n{cell_data}</CellData>\n"
                f"<Points>\n{_data_array('Points', mesh.points, 'Float64', 3)}</Points>\n"
                f"<Cells>\n{_data_array('connectivity', conn, 'Int64')}"
                f"{_data_array('offsets', np.cumsum(sizes).astype(np.int64), 'Int64')}"
                f"{_data_array('types', types, 'UInt8')}</Cells>\n"
                "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")


def read_png(path):
    """An 8-bit RGB or RGBA PNG (not interlaced) as an (h, w, 4) uint8 array, alpha 255 for RGB."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, (depth, colour, interlace)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    c = 4 if colour == 6 else 3
    raw = zlib.decompress(idat)
    stride = w * c
    out = np.zeros((h, stride), dtype=np.int32)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(h):
        kind = raw[y * (stride + 1)]
        line = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        row = np.zeros(stride, dtype=np.int32)
        for x in range(stride):
            a = row[x - c] if x >= c else 0
            b = prev[x]
            d = prev[x - c] if x >= c else 0
            if kind == 0:
                p = 0
            elif kind == 1:
                p = a
            elif kind == 2:
                p = b
            elif kind == 3:
                p = (a + b) // 2
            else:
                q = a + b - d
                pa, pb, pc = abs(q - a), abs(q - b), abs(q - d)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else d)
            row[x] = (line[x] + p) & 255
        out[y] = row
        prev = row
    img = out.reshape(h, w, c).astype(np.uint8)
    if c == 3:
        img = np.concatenate([img, np.full((h, w, 1), 255, np.uint8)], axis=2)
    return img


def cli_info(path):
    return subprocess.run([CLI, "info", "--json", path], check=True, capture_output=True,
                          text=True).stdout
