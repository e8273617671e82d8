"""shellmarch: direct volume rendering of unstructured meshes (docs/PYTHON.md).

    import shellmarch
    img = shellmarch.render("case.vtu", field="density", size=(640, 480))   # (480, 640, 4) uint8
    shellmarch.info("case.vtu")["fields"]

render() takes a file path or a shellmarch.Mesh; Renderer renders a simulation's own arrays step
after step, over MPI through mpi4py. Errors raise ValueError (bad input, with the command line's
one-line message) or OSError (a file that cannot be opened).
"""

from ._image import Image, to_png
from ._mesh import Mesh
from ._render import Renderer, info, render

__all__ = ["Image", "Mesh", "Renderer", "info", "render", "to_png"]
