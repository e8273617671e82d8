"""What the VTK peers of `shellmarch bench` share: reading a .pvtu piece by piece and welding the
pieces, as shellmarch's reader does.

vtkXMLPUnstructuredGridReader appends a .pvtu's pieces without merging their shared points, and
vtkAppendFilter merges points only between separate inputs, so the pieces are read one by one and
appended with MergePoints: without that, every face between two pieces would count as surface.
"""
import time


def timed(fn):
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def select_arrays(reader, path, arrays):
    """Load only these point arrays (None: all of them)."""
    if arrays is None:
        return
    sel = reader.GetPointDataArraySelection()
    for a in arrays:
        if not sel.ArrayExists(a):
            names = [sel.GetArrayName(i) for i in range(sel.GetNumberOfArrays())]
            raise SystemExit(f"{path} has no point array '{a}' (it has: {', '.join(names)})")
    sel.DisableAllArrays()
    for a in arrays:
        sel.EnableArray(a)


def read_pieces(vtk, path, arrays=None):
    """A .pvtu's pieces as separate grids (a .vtu is one piece)."""
    parallel = path.endswith(".pvtu")
    reader = vtk.vtkXMLPUnstructuredGridReader() if parallel else vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.UpdateInformation()
    select_arrays(reader, path, arrays)
    n = reader.GetNumberOfPieces() if parallel else 1
    pieces = []
    for i in range(n):
        reader.UpdatePiece(i, n, 0)
        piece = vtk.vtkUnstructuredGrid()
        piece.ShallowCopy(reader.GetOutput())
        pieces.append(piece)
    return pieces


def weld(vtk, pieces):
    """One grid with the pieces' coincident points merged (exactly: tolerance 0)."""
    append = vtk.vtkAppendFilter()
    append.MergePointsOn()
    append.SetTolerance(0.0)
    for p in pieces:
        append.AddInputData(p)
    append.Update()
    return append.GetOutput()
