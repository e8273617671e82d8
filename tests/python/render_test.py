"""shellmarch.render of files and of Meshes against `shellmarch render`'s PNG, bit for bit."""

import os
import threading
import time
import unittest

import numpy as np

import shellmarch
import support

SIZE = (64, 48)
# Keyword arguments, and the command line a user would type for them (written out, not derived,
# so that the translation is checked too).
DEFAULT = ({"field": "f", "size": SIZE}, ["--field", "f", "--size", "64x48"])
DETAILED = ({"field": "f", "size": SIZE, "eye": (-1.5, -2.0, 1.8), "at": (0.5, 0.5, 0.4),
             "up": (0, 0, 1), "fovy": 35.0, "colormap": "inferno", "range": (0.5, 5.5),
             "opacity": [(1.0, 0.0), (3.0, 0.9), (6.0, 0.9)], "integration": "sampled",
             "clip": ["x>0.2", (0.5, 0.5, 0.5, 0, 0, -1)], "legend": True,
             "background": (0.2, 0.3, 0.4)},
            ["--field", "f", "--size", "64x48", "--eye", "-1.5,-2,1.8", "--at", "0.5,0.5,0.4",
             "--up", "0,0,1", "--fovy", "35", "--colormap", "inferno", "--range", "0.5,5.5",
             "--opacity", "1:0,3:0.9,6:0.9", "--integration", "sampled", "--clip", "x>0.2",
             "--clip", "0.5,0.5,0.5,0,0,-1", "--legend", "--background", "0.2,0.3,0.4"])


def cli(path, out, args):
    import subprocess
    subprocess.run([support.CLI, "render", path, *args, "--out", out], check=True)
    return support.read_png(out)


class RenderMatchesCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = support.out_dir("render")
        cls.tets = support.tet_box(4)
        cls.tet_file = os.path.join(cls.dir, "tets.vtu")
        support.write_vtu(cls.tets, cls.tet_file)
        cls.mixed = support.mixed_box(4)
        cls.mixed_file = os.path.join(cls.dir, "mixed.vtu")
        support.write_vtu(cls.mixed, cls.mixed_file)

    def check(self, image, expected, background):
        self.assertIsInstance(image, np.ndarray)
        self.assertEqual(image.dtype, np.uint8)
        self.assertEqual(image.shape, (SIZE[1], SIZE[0], 4))
        # Something was drawn: not every pixel is the background.
        bg = np.round(np.array(background) * 255)
        self.assertGreater(np.count_nonzero(np.any(image[:, :, :3] != bg, axis=2)), 100)
        diff = np.abs(image.astype(int) - expected.astype(int))
        self.assertEqual(int(diff.max()), 0,
                         f"{np.count_nonzero(diff.max(axis=2))} pixels differ, by up to {diff.max()}")

    def test_file_default(self):
        kw, args = DEFAULT
        expected = cli(self.tet_file, os.path.join(self.dir, "default.png"), args)
        self.check(shellmarch.render(self.tet_file, **kw), expected, (0.1, 0.1, 0.12))

    def test_file_detailed(self):
        kw, args = DETAILED
        expected = cli(self.tet_file, os.path.join(self.dir, "detailed.png"), args)
        self.check(shellmarch.render(self.tet_file, **kw), expected, (0.2, 0.3, 0.4))

    def test_mesh_default(self):
        kw, args = DEFAULT
        expected = cli(self.tet_file, os.path.join(self.dir, "mesh_default.png"), args)
        self.check(shellmarch.render(self.tets, **kw), expected, (0.1, 0.1, 0.12))

    def test_mesh_detailed(self):
        kw, args = DETAILED
        expected = cli(self.tet_file, os.path.join(self.dir, "mesh_detailed.png"), args)
        self.check(shellmarch.render(self.tets, **kw), expected, (0.2, 0.3, 0.4))

    def test_mixed_elements_point_field(self):
        args = ["--field", "g", "--size", "64x48", "--view", "+y", "--colormap", "turbo"]
        expected = cli(self.mixed_file, os.path.join(self.dir, "mixed_g.png"), args)
        kw = {"field": "g", "size": SIZE, "view": "+y", "colormap": "turbo"}
        self.check(shellmarch.render(self.mixed_file, **kw), expected, (0.1, 0.1, 0.12))
        self.check(shellmarch.render(self.mixed, **kw), expected, (0.1, 0.1, 0.12))

    def test_mixed_elements_cell_field(self):
        # Cell data averaged onto the points, by the file reader and by the in-situ renderer.
        args = ["--field", "c", "--size", "64x48", "--fovy", "40"]
        expected = cli(self.mixed_file, os.path.join(self.dir, "mixed_c.png"), args)
        kw = {"field": "c", "size": SIZE, "fovy": 40}
        self.check(shellmarch.render(self.mixed_file, **kw), expected, (0.1, 0.1, 0.12))
        self.check(shellmarch.render(self.mixed, **kw), expected, (0.1, 0.1, 0.12))
        try:
            import meshio  # python3-meshio: the test dependencies have it
        except ImportError:
            return
        from_meshio = shellmarch.Mesh.from_meshio(meshio.read(self.mixed_file))
        self.check(shellmarch.render(from_meshio, **kw), expected, (0.1, 0.1, 0.12))

    def test_transparent_background(self):
        # The RGBA PNG's bytes: colour un-premultiplied, the frame's own alpha.
        args = ["--field", "f", "--size", "64x48", "--background", "transparent"]
        expected = cli(self.tet_file, os.path.join(self.dir, "transparent.png"), args)
        self.assertTrue(np.any((expected[:, :, 3] > 0) & (expected[:, :, 3] < 255)))
        for source in (self.tet_file, self.tets):
            got = shellmarch.render(source, field="f", size=SIZE, background="transparent")
            np.testing.assert_array_equal(got, expected)

    def test_renderer_steps(self):
        # Topology once, a field per step: each step's image is the file render of that step.
        r = shellmarch.Renderer(self.tets)
        for step, scale in enumerate([1.0, -2.0]):
            values = self.tets.point_data["f"] * scale
            r.set_field("f", values)
            mesh = shellmarch.Mesh(self.tets.points, self.tets.cells, point_data={"f": values})
            path = os.path.join(self.dir, f"step{step}.vtu")
            support.write_vtu(mesh, path)
            expected = cli(path, os.path.join(self.dir, f"step{step}.png"), DEFAULT[1])
            self.check(r.render(**DEFAULT[0]), expected, (0.1, 0.1, 0.12))
        self.assertEqual(r.stats()["geometry_builds"], 1)

    def test_png_of_the_image(self):
        img = shellmarch.render(self.tets, **DEFAULT[0])
        path = os.path.join(self.dir, "saved.png")
        img.save_png(path)
        np.testing.assert_array_equal(support.read_png(path), img)
        self.assertTrue(img._repr_png_().startswith(b"\x89PNG"))

    def test_gil_released_while_rendering(self):
        ticks = []
        worker = threading.Thread(target=shellmarch.render, args=(self.tet_file,),
                                  kwargs=DEFAULT[0])
        worker.start()
        while worker.is_alive():
            ticks.append(time.monotonic())
            time.sleep(0.002)
        worker.join()
        # A render on lavapipe takes well over 20 ms; a held GIL would stop this loop meanwhile.
        self.assertGreater(len(ticks), 10)


class Info(unittest.TestCase):
    def test_info_is_the_json_info_prints(self):
        import json
        d = support.out_dir("info")
        path = os.path.join(d, "mixed.vtu")
        support.write_vtu(support.mixed_box(2), path)
        got = shellmarch.info(path)
        self.assertEqual(got, json.loads(support.cli_info(path)))
        self.assertEqual(got["wedges"], 2 * 2 * 2)
        self.assertEqual(got["pyramids"], 6 * 2)  # two cubes at i = 1 with j + k even
        self.assertEqual([f["name"] for f in got["fields"]], ["g"])


if __name__ == "__main__":
    unittest.main()
