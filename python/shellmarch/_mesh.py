"""shellmarch.Mesh: a volume mesh as numpy arrays, in meshio's layout."""

import numpy as np

# meshio's block names, in the order the renderer numbers elements (setCellField's order), with
# their vertex counts (VTK vertex order).
BLOCKS = {"tetra": 4, "pyramid": 5, "wedge": 6, "hexahedron": 8}


def _points(points):
    a = np.asarray(points)
    if a.dtype.kind not in "fiu" or a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"points: needs an (n, 3) array of numbers, not {a.dtype} {a.shape}")
    # float64, C-contiguous: kept as given when it is so already (no copy).
    a = np.ascontiguousarray(a, dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(a).all(axis=1))
    if bad.size:
        raise ValueError(f"points: point {bad[0]} has a non-finite coordinate {tuple(a[bad[0]])}")
    return a


def _cells(name, ids, num_points):
    if name not in BLOCKS:
        raise ValueError(f"cells: block '{name}' is not one of {', '.join(BLOCKS)} "
                         "(meshio's names of the volume elements)")
    a = np.asarray(ids)
    k = BLOCKS[name]
    if a.dtype.kind not in "iu" or a.ndim != 2 or a.shape[1] != k:
        raise ValueError(f"cells['{name}']: needs an (m, {k}) integer array, not {a.dtype} {a.shape}")
    if a.dtype.itemsize not in (4, 8):
        a = a.astype(np.int64)  # 8- and 16-bit ids: widened (a copy)
    a = np.ascontiguousarray(a)  # 32- and 64-bit ids of either sign kept as given
    if a.size:
        flat = a.reshape(-1)
        bad = np.flatnonzero((flat < 0) | (flat >= num_points)) if flat.dtype.kind == "i" \
            else np.flatnonzero(flat >= num_points)
        if bad.size:
            i = bad[0]
            raise ValueError(f"cells['{name}']: element {i // k} (row {i // k}, column {i % k}) "
                             f"refers to vertex {flat[i]}, but points gives {num_points} "
                             "vertices (ids are 0-based)")
    return a


def _values(what, values, count):
    a = np.asarray(values)
    if a.dtype.kind not in "fiu" or a.ndim not in (1, 2) or a.shape[0] != count:
        raise ValueError(f"{what}: needs {count} values (an ({count},) array, or ({count}, k) for "
                         f"a vector), not {a.dtype} {a.shape}")
    return a


class Mesh:
    """A volume mesh: points, cells by meshio block name, and data on points or cells.

    points      (n, 3) array (float64 is kept without a copy; other numbers are converted)
    cells       {"tetra" | "pyramid" | "wedge" | "hexahedron": (m, k) integer array}, VTK order
    point_data  {name: (n,) array, or (n, k) whose components render as "name[j]"}
    cell_data   {name: one array per block of `cells` in its order, or one array of every
                 element in that order}; rendered averaged onto the points, as files' cell data
    """

    def __init__(self, points, cells, point_data=None, cell_data=None):
        self.points = _points(points)
        if not isinstance(cells, dict):
            raise ValueError("cells: needs a dict of meshio block names to arrays, e.g. "
                             "{'tetra': ids}")
        n = len(self.points)
        self.cells = {name: _cells(name, ids, n) for name, ids in cells.items()}
        self.point_data = {str(name): _values(f"point_data['{name}']", v, n)
                           for name, v in (point_data or {}).items()}
        self.cell_data = {str(name): self._cell_values(name, v)
                          for name, v in (cell_data or {}).items()}

    def _cell_values(self, name, values):
        if isinstance(values, (list, tuple)):
            if len(values) != len(self.cells):
                raise ValueError(f"cell_data['{name}']: {len(values)} arrays for "
                                 f"{len(self.cells)} cell blocks")
            parts = {b: _values(f"cell_data['{name}'] of '{b}'", v, len(ids))
                     for (b, ids), v in zip(self.cells.items(), values)}
        else:
            total = sum(len(ids) for ids in self.cells.values())
            a = _values(f"cell_data['{name}']", values, total)
            starts = np.cumsum([0] + [len(ids) for ids in self.cells.values()])
            parts = {b: a[starts[i]:starts[i + 1]] for i, b in enumerate(self.cells)}
        # The renderer's element order: tetrahedra, pyramids, wedges, hexahedra.
        ordered = [parts[b] for b in BLOCKS if b in parts]
        if not ordered:
            return np.zeros(0, dtype=np.float32)
        return np.concatenate(ordered) if len(ordered) > 1 else ordered[0]

    @classmethod
    def from_meshio(cls, m):
        """A Mesh of a meshio.Mesh's volume blocks (blocks of one type joined; 2D, line and vertex
        blocks left out, with their cell data) and its point and cell data."""
        keep = [i for i, block in enumerate(m.cells) if block.type in BLOCKS]
        cells = {}
        for i in keep:
            cells.setdefault(m.cells[i].type, []).append(np.asarray(m.cells[i].data))
        cells = {t: np.concatenate(parts) if len(parts) > 1 else parts[0] for t, parts in cells.items()}
        cell_data = {}
        for name, arrays in (m.cell_data or {}).items():
            per_type = {}
            for i in keep:
                per_type.setdefault(m.cells[i].type, []).append(np.asarray(arrays[i]))
            cell_data[name] = [np.concatenate(per_type[t]) for t in cells]
        return cls(m.points, cells, point_data=dict(m.point_data or {}), cell_data=cell_data)

    def field_names(self):
        """Point data first, then cell data: the order a render without field= picks from."""
        return list(self.point_data) + [n for n in self.cell_data if n not in self.point_data]

    def __repr__(self):
        blocks = ", ".join(f"{b}: {len(ids)}" for b, ids in self.cells.items())
        return (f"<shellmarch.Mesh {len(self.points)} points, {{{blocks}}}, "
                f"point_data {list(self.point_data)}, cell_data {list(self.cell_data)}>")
