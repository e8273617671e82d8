#!/usr/bin/env python3
"""Writes the polyhedron fixtures (polyhedra.vtu, polyhedra_v42_binary.vtk, polyhedra_v51_binary.vtk)
with VTK's own writers (python3-vtk9 9.1): two unit cubes side by side and a hexagonal prism,
each a VTK_POLYHEDRON; point field s = x + 2y + 3z, cell array q = 1, 2, 3. Run in tests/io/data."""
import math, vtk
pts = vtk.vtkPoints()
coords = [(0,0,0),(1,0,0),(1,1,0),(0,1,0),(0,0,1),(1,0,1),(1,1,1),(0,1,1),(2,0,0),(2,1,0),(2,0,1),(2,1,1)]
for k in range(6):
    coords.append((4 + math.cos(k*math.pi/3), math.sin(k*math.pi/3), 0))
for k in range(6):
    coords.append((4 + math.cos(k*math.pi/3), math.sin(k*math.pi/3), 1))
for c in coords: pts.InsertNextPoint(c)
ug = vtk.vtkUnstructuredGrid(); ug.SetPoints(pts)
def poly(faces):
    ids = vtk.vtkIdList(); ids.InsertNextId(len(faces))
    for f in faces:
        ids.InsertNextId(len(f))
        for i in f: ids.InsertNextId(i)
    ug.InsertNextCell(vtk.VTK_POLYHEDRON, ids)
poly([[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]])
poly([[1,2,9,8],[5,10,11,6],[1,8,10,5],[8,9,11,10],[9,2,6,11],[2,1,5,6]])
hexa = [[17,16,15,14,13,12],[18,19,20,21,22,23]] + [[12+k,12+(k+1)%6,18+(k+1)%6,18+k] for k in range(6)]
poly(hexa)
s = vtk.vtkFloatArray(); s.SetName("s")
for c in coords: s.InsertNextValue(c[0] + 2*c[1] + 3*c[2])
ug.GetPointData().AddArray(s)
q = vtk.vtkFloatArray(); q.SetName("q")
for v in (1, 2, 3): q.InsertNextValue(v)
ug.GetCellData().AddArray(q)
w = vtk.vtkXMLUnstructuredGridWriter(); w.SetFileName("polyhedra.vtu"); w.SetInputData(ug); w.Write()
w = vtk.vtkUnstructuredGridWriter(); w.SetFileName("polyhedra_v51_binary.vtk"); w.SetFileTypeToBinary(); w.SetInputData(ug); w.Write()
w = vtk.vtkUnstructuredGridWriter(); w.SetFileName("polyhedra_v42_binary.vtk"); w.SetFileVersion(42); w.SetFileTypeToBinary(); w.SetInputData(ug); w.Write()
