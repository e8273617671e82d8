"""render(), info() and Renderer: keyword arguments spelled as `shellmarch render`'s options and
parsed by the command's own parser (in the compiled core), so that values, checks and messages are
the command line's."""

import json
import os
import re

import numpy as np

from . import _shellmarch as _core
from ._image import as_image
from ._mesh import BLOCKS, Mesh

# Flags: True adds the option, False leaves it out.
_FLAGS = {"legend", "log_scale", "shading", "plain", "parallel"}
# What the in-situ renderer (Mesh and Renderer) does as the command does; the other options of
# files (shading, fragment lists, clusters, caches, ...) have no in-situ counterpart.
_MESH_OPTIONS = {"field", "size", "view", "eye", "at", "up", "fovy", "colormap", "range",
                 "opacity", "log_scale", "opacity_scale", "unit_distance", "step", "integration",
                 "early_termination", "background", "legend", "clip", "time"}


def _number(x, what):
    if isinstance(x, (bool, np.bool_)):
        raise ValueError(f"{what}: expected a number, not {x!r}")
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        return repr(float(x))  # the shortest text that reads back as the same double
    raise ValueError(f"{what}: expected a number, not {x!r}")


def _text(value, what):
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return ",".join(_number(x, what) for x in np.asarray(value, dtype=object).reshape(-1))
    return _number(value, what)


def _option_args(key, value):
    if not re.fullmatch(r"[a-z][a-z0-9_]*", key) or key == "help":
        raise ValueError(f"render: unknown option {key!r}")
    option = "--" + key.replace("_", "-")
    if key in _FLAGS:
        if not isinstance(value, (bool, np.bool_)):
            raise ValueError(f"{key}: expected True or False, not {value!r}")
        return [option] if value else []
    if key == "size":
        if isinstance(value, str):
            return [f"{option}={value}"]
        if len(value) != 2:
            raise ValueError(f"size: expected (width, height), not {value!r}")
        return [f"{option}={_number(value[0], key)}x{_number(value[1], key)}"]
    if key == "clip":
        # One plane: 'x>0.5' or (px, py, pz, nx, ny, nz); several: a list of them.
        single = isinstance(value, str) or all(
            isinstance(x, (int, float, np.integer, np.floating)) for x in value)
        planes = [value] if single else list(value)
        return [f"{option}={_text(p, key)}" for p in planes]
    if key == "opacity" and not isinstance(value, str):
        # [(value, opacity), ...] control points
        return [option + "=" + ",".join(f"{_number(v, key)}:{_number(a, key)}" for v, a in value)]
    # --option=VALUE: a value that starts with '-' (a field's name, a negative coordinate) is not
    # taken for an option.
    return [f"{option}={_text(value, key)}"]


def _args(options):
    args = []
    for key, value in options.items():
        if value is not None:
            args += _option_args(key, value)
    return args


def _stack(frames):
    return as_image(frames[0] if len(frames) == 1 else np.stack(frames))


def render(source, *, field=None, **options):
    """Renders a mesh file (a path) or a shellmarch.Mesh; returns the (h, w, 4) uint8 RGBA image
    `shellmarch render` writes with the same options (a time sequence: (frames, h, w, 4)).

    Options are `render`'s without the dashes, '_' for '-': size=(w, h), view='iso',
    eye=(x, y, z), at=..., up=..., fovy=30, colormap='viridis', range=(lo, hi),
    opacity=[(value, opacity), ...] or '2:0,3:0.8', integration='exact', time=0, clip='x>0.5' or
    a list of planes, legend=True, background=(r, g, b), log_scale=True, step=..., ...
    """
    if isinstance(source, Mesh):
        unknown = sorted(set(options) - _MESH_OPTIONS - {"device", "tracer"})
        if unknown:
            raise ValueError(f"render: {', '.join(unknown)}: not available for a shellmarch.Mesh "
                             "(the in-situ renderer has no such option); render a file for it")
        renderer = Renderer(source, device=options.pop("device", None) or "",
                            tracer=options.pop("tracer", None) or "auto")
        return renderer.render(field=field, **options)
    path = os.fspath(source)
    return _stack(_core.render_file(path, _args(dict(field=field, **options))))


def info(path):
    """What `shellmarch info --json PATH` prints, as a dict."""
    return json.loads(_core.info_json(os.fspath(path)))


def _field_values(mesh_data, name):
    """The array of field `name` ("v" or a component "v[2]") in a dict of arrays, or None."""
    if name in mesh_data:
        a = mesh_data[name]
        if a.ndim == 2:
            if a.shape[1] != 1:
                raise ValueError(f"field '{name}' has {a.shape[1]} components: name one, "
                                 f"'{name}[0]' .. '{name}[{a.shape[1] - 1}]'")
            a = a[:, 0]
        return a
    m = re.fullmatch(r"(.*)\[(\d+)\]", name)
    if m and m.group(1) in mesh_data and mesh_data[m.group(1)].ndim == 2:
        a, j = mesh_data[m.group(1)], int(m.group(2))
        if j >= a.shape[1]:
            raise ValueError(f"field '{name}': '{m.group(1)}' has {a.shape[1]} components")
        return a[:, j]
    return None


def _float32(name, values, count):
    a = np.asarray(values)
    if a.dtype.kind not in "fiu" or a.ndim != 1 or a.shape[0] != count:
        raise ValueError(f"field '{name}': needs {count} values (a one-dimensional array of "
                         f"numbers), not {a.dtype} {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)  # float32 contiguous: no copy


class Renderer:
    """Renders a simulation's mesh step after step: topology once, fields per step.

    Renderer(mesh, comm=None): `mesh` is this rank's part (a shellmarch.Mesh); `comm` an mpi4py
    communicator (every rank of it takes part in the constructor, set_cell_field and render), or
    None for one process without MPI. device and tracer choose the Vulkan device and tracer as
    `render --device/--tracer` do.
    """

    def __init__(self, mesh, comm=None, *, device="", tracer="auto"):
        if not isinstance(mesh, Mesh):
            raise ValueError(f"Renderer: needs a shellmarch.Mesh, not {type(mesh).__name__}")
        self._mesh = mesh
        self._core = _core.Renderer(comm, device, tracer)
        self._core.set_mesh(mesh.points, **{b: mesh.cells.get(b) for b in BLOCKS})
        self._fields = []  # set with set_field or set_cell_field, in order
        self._elements = sum(len(ids) for ids in mesh.cells.values())

    @property
    def rank(self):
        return self._core.rank

    @property
    def ranks(self):
        return self._core.ranks

    def set_field(self, name, values):
        """This rank's values of a point field (one per point). Local: no other rank takes part."""
        self._core.set_field(str(name), _float32(name, values, len(self._mesh.points)))
        self._remember(name)

    def set_cell_field(self, name, values):
        """This rank's values of a cell field (one per element: tetra, pyramid, wedge, hexahedron
        in that order), averaged onto the points across ranks. Collective."""
        self._core.set_cell_field(str(name), _float32(name, values, self._elements))
        self._remember(name)

    def _remember(self, name):
        if name not in self._fields:
            self._fields.append(str(name))

    def _ensure_field(self, field):
        """The field to render: `field`, or the first set, or the mesh's first (point data before
        cell data, as the command picks); one the mesh holds but not yet set is set from it."""
        if field is None:
            names = self._fields or self._mesh.field_names()
            if not names:
                raise ValueError("render: no field: set one with set_field, or give the Mesh "
                                 "point_data or cell_data")
            field = names[0]
        if field not in self._fields:
            values = _field_values(self._mesh.point_data, field)
            if values is not None:
                self.set_field(field, values)
            else:
                values = _field_values(self._mesh.cell_data, field)
                if values is None:
                    raise ValueError(f"render: field '{field}' is not set (set_field) and the mesh "
                                     f"has no such data (it has {self._mesh.field_names()})")
                self.set_cell_field(field, values)
        return field

    def render(self, *, field=None, **options):
        """Collective. The (h, w, 4) uint8 image on rank 0, None on the other ranks; options as
        render()'s for a Mesh."""
        unknown = sorted(set(options) - _MESH_OPTIONS)
        if unknown:
            raise ValueError(f"Renderer.render: {', '.join(unknown)}: not available in situ "
                             "(device and tracer go to Renderer())")
        time = options.pop("time", None)
        if time not in (None, 0, "0"):
            raise ValueError(f"time: {time!r}: a Mesh holds one step (set_field changes it)")
        field = self._ensure_field(field)
        img = self._core.render(_args(dict(field=field, **options)))
        return None if img is None else as_image(img)

    def stats(self):
        """This rank's statistics: device, tracer, elements, uploads, last frame's time."""
        return self._core.stats()
