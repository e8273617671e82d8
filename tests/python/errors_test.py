"""Bad input raises ValueError (or OSError for files), never crashes: Mesh arrays, options,
files, communicators. Nothing here needs a device but the Renderer cases."""

import os
import unittest

import numpy as np

import shellmarch
import support


def cube():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    return points, np.array([[0, 1, 2, 3]], dtype=np.int32)


class MeshArrays(unittest.TestCase):
    def test_kept_without_a_copy(self):
        points, tets = cube()
        m = shellmarch.Mesh(points, {"tetra": tets})
        self.assertTrue(np.shares_memory(m.points, points))
        self.assertTrue(np.shares_memory(m.cells["tetra"], tets))

    def test_converted_when_they_must_be(self):
        points, tets = cube()
        fortran = np.asfortranarray(points)
        m = shellmarch.Mesh(fortran.astype(np.float32), {"tetra": tets.astype(np.int16)[:, ::-1]})
        self.assertTrue(m.points.flags.c_contiguous)
        self.assertEqual(m.points.dtype, np.float64)
        self.assertEqual(m.cells["tetra"].dtype, np.int64)
        np.testing.assert_array_equal(m.cells["tetra"], [[3, 2, 1, 0]])

    def assertRaisesNaming(self, text, f, *args, **kw):
        with self.assertRaises(ValueError) as c:
            f(*args, **kw)
        self.assertIn(text, str(c.exception))

    def test_wrong_shapes(self):
        points, tets = cube()
        self.assertRaisesNaming("points", shellmarch.Mesh, points[:, :2], {"tetra": tets})
        self.assertRaisesNaming("points", shellmarch.Mesh, points.reshape(-1), {"tetra": tets})
        self.assertRaisesNaming("tetra", shellmarch.Mesh, points, {"tetra": tets[:, :3]})
        self.assertRaisesNaming("hexahedron", shellmarch.Mesh, points, {"hexahedron": tets})
        self.assertRaisesNaming("triangle", shellmarch.Mesh, points, {"triangle": tets[:, :3]})
        self.assertRaisesNaming("point_data['f']", shellmarch.Mesh, points, {"tetra": tets},
                                point_data={"f": np.zeros(5)})
        self.assertRaisesNaming("cell_data['c']", shellmarch.Mesh, points, {"tetra": tets},
                                cell_data={"c": np.zeros(2)})

    def test_wrong_dtypes(self):
        points, tets = cube()
        self.assertRaisesNaming("tetra", shellmarch.Mesh, points, {"tetra": tets.astype(float)})
        self.assertRaisesNaming("points", shellmarch.Mesh, points.astype(complex), {"tetra": tets})
        self.assertRaisesNaming("points", shellmarch.Mesh, points.astype(object), {"tetra": tets})

    def test_indices_out_of_range(self):
        points, tets = cube()
        self.assertRaisesNaming("refers to vertex 4", shellmarch.Mesh, points,
                                {"tetra": np.array([[0, 1, 2, 4]])})
        self.assertRaisesNaming("refers to vertex -1", shellmarch.Mesh, points,
                                {"tetra": np.array([[0, -1, 2, 3]])})
        self.assertRaisesNaming("refers to vertex", shellmarch.Mesh, points,
                                {"tetra": np.array([[0, 1, 2, 2**63 + 5]], dtype=np.uint64)})

    def test_nan_points(self):
        points, tets = cube()
        points[2, 1] = np.nan
        self.assertRaisesNaming("point 2", shellmarch.Mesh, points, {"tetra": tets})
        points[2, 1] = np.inf
        self.assertRaisesNaming("point 2", shellmarch.Mesh, points, {"tetra": tets})


class FromMeshio(unittest.TestCase):
    """meshio's layout (meshio itself is not a dependency): blocks with .type and .data, cell
    data as one array per block."""

    def test_volume_blocks_joined_and_others_left_out(self):
        from types import SimpleNamespace as Block
        points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float)
        m = Block(points=points,
                  cells=[Block(type="tetra", data=np.array([[0, 1, 2, 3]])),
                         Block(type="triangle", data=np.array([[0, 1, 2]])),
                         Block(type="tetra", data=np.array([[1, 2, 3, 4]]))],
                  point_data={"f": points[:, 0]},
                  cell_data={"c": [np.array([1.0]), np.array([9.0]), np.array([2.0])]})
        mesh = shellmarch.Mesh.from_meshio(m)
        np.testing.assert_array_equal(mesh.cells["tetra"], [[0, 1, 2, 3], [1, 2, 3, 4]])
        self.assertEqual(list(mesh.cells), ["tetra"])
        np.testing.assert_array_equal(mesh.cell_data["c"], [1.0, 2.0])
        self.assertEqual(mesh.field_names(), ["f", "c"])


class Options(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.path = os.path.join(support.out_dir("errors"), "tets.vtu")
        support.write_vtu(support.tet_box(2), cls.path)

    def test_cli_messages(self):
        # Settings are named by their keyword arguments, as the command line names its options.
        cases = [({"size": (0, 10)}, "size: '0x10'"), ({"colormap": "nope"}, "colormap: "),
                 ({"range": (2, 1)}, "range: "), ({"fovy": 200}, "fovy: 200"),
                 ({"view": "sideways"}, "view: unknown view 'sideways'"),
                 ({"no_such_option": 1}, "--no-such-option"),
                 ({"eye": (1, 2)}, "eye: '1"), ({"field": "missing"}, "missing"),
                 ({"legend": "yes"}, "legend"), ({"size": (64, "x")}, "size"),
                 ({"clip": "w>1"}, "clip: "), ({"opacity": [(1, 2)]}, "opacity: "),
                 ({"log_scale": True, "range": (0, 1)}, "log_scale: ")]
        for kw, text in cases:
            with self.subTest(**{k: str(v) for k, v in kw.items()}):
                with self.assertRaises(ValueError) as c:
                    shellmarch.render(self.path, **kw)
                self.assertIn(text, str(c.exception))
                self.assertNotIn("\n", str(c.exception))
                if text.endswith(": "):  # a setting's key, not the option's
                    self.assertNotIn("--" + text, str(c.exception))

    def test_missing_file_is_an_os_error(self):
        missing = os.path.join(os.path.dirname(self.path), "missing.vtu")
        for f in (shellmarch.render, shellmarch.info):
            with self.assertRaises(OSError) as c:
                f(missing)
            self.assertIn("missing.vtu", str(c.exception))

    def test_damaged_file_is_a_value_error(self):
        bad = os.path.join(os.path.dirname(self.path), "damaged.vtu")
        with open(bad, "w") as f:
            f.write("<VTKFile type='UnstructuredGrid'><UnstructuredGrid><Piece")
        with self.assertRaises(ValueError) as c:
            shellmarch.info(bad)
        self.assertIn("damaged.vtu", str(c.exception))

    def test_mesh_only_options(self):
        points, tets = cube()
        m = shellmarch.Mesh(points, {"tetra": tets}, point_data={"f": np.arange(4.0)})
        with self.assertRaises(ValueError) as c:
            shellmarch.render(m, shading=True)
        self.assertIn("shading", str(c.exception))
        with self.assertRaises(ValueError):
            shellmarch.render(m, field="nope")


class RendererInput(unittest.TestCase):
    """Needs a device: the renderer is made before its arrays are checked."""

    @classmethod
    def setUpClass(cls):
        cls.mesh = support.tet_box(2)
        cls.r = shellmarch.Renderer(cls.mesh)

    def test_field_arrays(self):
        n = len(self.mesh.points)
        for bad in (np.zeros(n - 1), np.zeros((n, 2)), np.array(["a"] * n), None):
            with self.assertRaises(ValueError):
                self.r.set_field("f", bad)
        self.r.set_field("f", np.arange(2 * n, dtype=np.float64)[::2])  # strided: copied
        with self.assertRaises(ValueError):
            self.r.set_cell_field("c", np.zeros(3))
        with self.assertRaises(ValueError) as c:
            self.r.render(field="f", size=(16, 16), shading=True)
        self.assertIn("shading", str(c.exception))
        self.assertEqual(self.r.render(field="f", size=(16, 16)).shape, (16, 16, 4))

    def test_core_refuses_what_python_would_convert(self):
        from shellmarch import _shellmarch
        core = _shellmarch.Renderer(None, "", "auto")
        points = np.asfortranarray(self.mesh.points)
        with self.assertRaises(ValueError) as c:
            core.set_mesh(points, tetra=self.mesh.cells["tetra"])
        self.assertIn("contiguous", str(c.exception))
        with self.assertRaises(ValueError):
            core.set_mesh(self.mesh.points, tetra=self.mesh.cells["tetra"].astype(np.float64))
        with self.assertRaises(ValueError):
            core.set_mesh(self.mesh.points.astype(np.float32), tetra=self.mesh.cells["tetra"])

    def test_communicator(self):
        with self.assertRaises(TypeError):
            shellmarch.Renderer(self.mesh, comm=object())
        with self.assertRaises(ValueError):
            shellmarch.Renderer("mesh.vtu")


if __name__ == "__main__":
    unittest.main()
