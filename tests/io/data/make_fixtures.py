#!/usr/bin/python3
# Regenerates the small VTK fixtures in this folder. Run with Debian's python (it has vtk 9):
#   /usr/bin/python3 tests/io/data/make_fixtures.py
#
# Every fixture holds the same 13-point mesh (see mesh()) so that one test can check all
# encodings against the same expectations (tests/io/fixture_mesh.h):
#   cell 0  hexahedron  0..7 (unit cube)                      cluster 0
#   cell 1  pyramid     1 2 6 5 | 8 on the cube's +x face     cluster 1
#   cell 2  wedge       3 7 9 | 2 6 10 on the cube's +y face  cluster 1
#   cell 3  tetra       0 4 3 11 (positive)                   cluster 2
#   cell 4  tetra       0 4 1 12 (inverted on purpose)        cluster 2
#   cell 5  triangle    0 1 2 (a 2D cell: skipped)            cluster 0
#   cell 6  quadratic tetra, corners 0 1 3 4 (reduced)        cluster 3
#   cell 7  vertex      12 (a 0D cell: skipped)               cluster 0
# Point arrays: pressure (Float32) = 1 + i/2; velocity (Float64 x3) = (i, 2i, -i);
# temp@t0..temp@t2 (Float32) = i + 100 t; count (Int32) = 3i. Cell arrays: cluster (Int32),
# quality (Float64). Field data: TimeValues = 0, 0.25, 1.
import base64
import os
import struct
import zlib

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk

HERE = os.path.dirname(os.path.abspath(__file__))

POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1),
          (1.5, 0.5, 0.5), (0, 1.5, 0.5), (1, 1.5, 0.5), (-0.5, 0.5, 0.5), (0.5, -0.5, 0.5)]
CELLS = [(12, [0, 1, 2, 3, 4, 5, 6, 7]), (14, [1, 2, 6, 5, 8]), (13, [3, 7, 9, 2, 6, 10]),
         (10, [0, 4, 3, 11]), (10, [0, 4, 1, 12]), (5, [0, 1, 2]),
         (24, [0, 1, 3, 4, 5, 6, 7, 8, 9, 10]), (1, [12])]
CLUSTER = [0, 1, 1, 2, 2, 0, 3, 0]


def array(values, name, dtype, components=1):
    a = numpy_to_vtk(np.ascontiguousarray(np.asarray(values, dtype=dtype)), deep=1)
    a.SetName(name)
    a.SetNumberOfComponents(components)
    return a


def mesh(points_dtype=np.float64):
    g = vtk.vtkUnstructuredGrid()
    pts = vtk.vtkPoints()
    pts.SetData(array(np.asarray(POINTS, dtype=points_dtype).reshape(-1, 3), "Points",
                      points_dtype, 3))
    g.SetPoints(pts)
    for t, ids in CELLS:
        g.InsertNextCell(t, len(ids), ids)
    n = len(POINTS)
    i = np.arange(n)
    pd = g.GetPointData()
    pd.AddArray(array(1 + i / 2, "pressure", np.float32))
    pd.AddArray(array(np.stack([i, 2 * i, -i], axis=1), "velocity", np.float64, 3))
    for t in range(3):
        pd.AddArray(array(i + 100 * t, "temp@t%d" % t, np.float32))
    pd.AddArray(array(3 * i, "count", np.int32))
    # Active attributes make the legacy writer use SCALARS / LOOKUP_TABLE and VECTORS.
    pd.SetActiveScalars("pressure")
    pd.SetActiveVectors("velocity")
    cd = g.GetCellData()
    cd.AddArray(array(CLUSTER, "cluster", np.int32))
    cd.AddArray(array(np.linspace(0, 1, len(CELLS)), "quality", np.float64))
    cd.SetActiveScalars("cluster")
    g.GetFieldData().AddArray(array([0.0, 0.25, 1.0], "TimeValues", np.float64))
    return g


def write_vtu(name, grid, mode, compressor="none", header=64, id_type=64, big_endian=False,
              encode=True, block_size=128):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(os.path.join(HERE, name))
    w.SetInputData(grid)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(encode)
    {"none": w.SetCompressorTypeToNone, "zlib": w.SetCompressorTypeToZLib,
     "lz4": w.SetCompressorTypeToLZ4, "lzma": w.SetCompressorTypeToLZMA}[compressor]()
    w.SetBlockSize(block_size)  # small blocks: compressed arrays span several blocks
    w.SetHeaderTypeToUInt32() if header == 32 else w.SetHeaderTypeToUInt64()
    w.SetIdTypeToInt32() if id_type == 32 else w.SetIdTypeToInt64()
    w.SetByteOrderToBigEndian() if big_endian else w.SetByteOrderToLittleEndian()
    assert w.Write() == 1, name


def write_legacy(name, grid, binary, version):
    w = vtk.vtkUnstructuredGridWriter()
    w.SetFileName(os.path.join(HERE, name))
    w.SetInputData(grid)
    w.SetFileTypeToBinary() if binary else w.SetFileTypeToASCII()
    w.SetFileVersion(version)
    assert w.Write() == 1, name


# A hand-made appended raw file: integer types VTK's writer never picks for cells
# (UInt16 connectivity, Int8 types, UInt32 offsets), Int16 / UInt64 / Int8 point arrays, and
# no compressor; checks that every integer type is accepted.
def write_handmade_int_types(name):
    arrays = []  # (xml attributes, bytes)
    def add(attrs, data):
        arrays.append((attrs, np.ascontiguousarray(data).tobytes()))
    n = len(POINTS)
    i = np.arange(n)
    add('type="Int16" Name="pressure"', (10 * i).astype("<i2"))
    add('type="UInt64" Name="big" NumberOfComponents="2"', np.stack([i, i], 1).astype("<u8"))
    add('type="Int8" Name="small"', (-i).astype("<i1"))
    add('type="Float64" Name="Points" NumberOfComponents="3"', np.asarray(POINTS, "<f8"))
    conn = [v for _, ids in CELLS for v in ids]
    offs = np.cumsum([len(ids) for _, ids in CELLS])
    add('type="UInt16" Name="connectivity"', np.asarray(conn, "<u2"))
    add('type="UInt32" Name="offsets"', offs.astype("<u4"))
    add('type="Int8" Name="types"', np.asarray([t for t, _ in CELLS], "<i1"))
    add('type="UInt8" Name="part"', np.asarray(CLUSTER, "<u1"))
    blob = b""
    tags = []
    for attrs, data in arrays:
        tags.append('<DataArray %s format="appended" offset="%d"/>' % (attrs, len(blob)))
        blob += struct.pack("<I", len(data)) + data
    xml = ('<?xml version="1.0"?>\n'
           '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
           'header_type="UInt32">\n<UnstructuredGrid>\n'
           '<Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
           '<PointData>%s</PointData>\n<Points>%s</Points>\n<Cells>%s</Cells>\n'
           '<CellData>%s</CellData>\n</Piece>\n</UnstructuredGrid>\n'
           '<AppendedData encoding="raw">\n_' % (n, len(CELLS), "".join(tags[0:3]), tags[3],
                                                 "".join(tags[4:7]), tags[7]))
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(xml.encode() + blob + b"\n</AppendedData>\n</VTKFile>\n")


# Three pieces of the fixture mesh, each with its own copy of the points it uses, and a .pvtu
# naming them: piece 0 the hexahedron, piece 1 the pyramid and wedge, piece 2 the first tetra.
# Faces between pieces use bitwise-equal coordinates, so reading them together welds them.
def write_weld_pvtu():
    os.makedirs(os.path.join(HERE, "weld"), exist_ok=True)
    pieces = [[0], [1, 2], [3]]
    for k, cells in enumerate(pieces):
        used = sorted({v for c in cells for v in CELLS[c][1]})
        local = {v: j for j, v in enumerate(used)}
        g = vtk.vtkUnstructuredGrid()
        pts = vtk.vtkPoints()
        pts.SetData(array(np.asarray([POINTS[v] for v in used], np.float64), "Points",
                          np.float64, 3))
        g.SetPoints(pts)
        for c in cells:
            t, ids = CELLS[c]
            g.InsertNextCell(t, len(ids), [local[v] for v in ids])
        g.GetPointData().AddArray(array([1 + v / 2 for v in used], "pressure", np.float32))
        write_vtu(os.path.join("weld", "weld_%d.vtu" % k), g, "appended", "zlib",
                  encode=False)
    with open(os.path.join(HERE, "weld.pvtu"), "w") as f:
        f.write('<?xml version="1.0"?>\n'
                '<VTKFile type="PUnstructuredGrid" version="1.0" byte_order="LittleEndian">\n'
                '<PUnstructuredGrid GhostLevel="0">\n'
                '<PPointData><PDataArray type="Float32" Name="pressure"/></PPointData>\n'
                '<PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>\n')
        for k in range(len(pieces)):
            f.write('<Piece Source="weld/weld_%d.vtu"/>\n' % k)
        f.write('</PUnstructuredGrid>\n</VTKFile>\n')


def main():
    g = mesh()
    write_vtu("mesh_ascii.vtu", g, "ascii")
    for header in (32, 64):
        for comp in ("none", "zlib"):
            write_vtu("mesh_binary_%s_h%d.vtu" % (comp, header), g, "binary", comp, header)
            write_vtu("mesh_appended_raw_%s_h%d.vtu" % (comp, header), g, "appended", comp,
                      header, encode=False)
            write_vtu("mesh_appended_b64_%s_h%d.vtu" % (comp, header), g, "appended", comp,
                      header, encode=True)
    write_vtu("mesh_binary_zlib_id32.vtu", g, "binary", "zlib", 32, id_type=32)
    write_vtu("mesh_appended_raw_none_id32.vtu", g, "appended", "none", 64, id_type=32,
              encode=False)
    write_vtu("mesh_appended_raw_none_bigendian.vtu", g, "appended", "none", 64,
              big_endian=True, encode=False)
    write_vtu("mesh_binary_zlib_bigendian.vtu", g, "binary", "zlib", 32, big_endian=True)
    write_vtu("mesh_appended_raw_zlib_float32.vtu", mesh(np.float32), "appended", "zlib", 64,
              encode=False)
    write_vtu("mesh_lz4.vtu", g, "appended", "lz4", 64, encode=False)
    write_vtu("mesh_lzma.vtu", g, "binary", "lzma", 64)
    write_legacy("mesh_v42_ascii.vtk", g, False, 42)
    write_legacy("mesh_v42_binary.vtk", g, True, 42)
    write_legacy("mesh_v51_ascii.vtk", g, False, 51)
    write_legacy("mesh_v51_binary.vtk", g, True, 51)
    write_handmade_int_types("mesh_int_types.vtu")
    write_weld_pvtu()
    # The hand-made files must be valid for VTK too.
    for name in ("mesh_int_types.vtu", "weld.pvtu"):
        r = (vtk.vtkXMLPUnstructuredGridReader() if name.endswith(".pvtu")
             else vtk.vtkXMLUnstructuredGridReader())
        r.SetFileName(os.path.join(HERE, name))
        r.Update()
        assert r.GetOutput().GetNumberOfCells() > 0, name


if __name__ == "__main__":
    main()
