"""Renderer over two MPI ranks through mpi4py: each rank holds half of the cells, and rank 0's
image equals one process's image of the whole mesh. Run as
    mpirun -np 2 python3 mpi_test.py"""

import sys

import numpy as np
from mpi4py import MPI

import shellmarch
import support

OPTIONS = {"size": (64, 48), "early_termination": 1.0, "colormap": "cool-to-warm"}


def half(mesh, rank, ranks):
    """The cells whose first vertex lies in this rank's slab in x (non-convex ownership is not
    needed here), with every point kept: unused points are allowed."""
    ids = mesh.cells["tetra"]
    centre_x = mesh.points[ids].mean(axis=1)[:, 0]
    mine = (np.floor(centre_x * ranks).clip(0, ranks - 1) == rank)
    return shellmarch.Mesh(mesh.points, {"tetra": ids[mine]}), mine


def main():
    comm = MPI.COMM_WORLD
    assert comm.size == 2, "run with mpirun -np 2"
    whole = support.tet_box(4)
    part, mine = half(whole, comm.rank, comm.size)
    r = shellmarch.Renderer(part, comm)
    assert (r.rank, r.ranks) == (comm.rank, 2)
    failures = 0
    for step, f in enumerate([whole.point_data["f"], np.sin(4 * whole.points[:, 0]) + whole.points[:, 2]]):
        r.set_field("f", f)  # local: each rank its own points' values
        img = r.render(field="f", **OPTIONS)
        # A cell field too: the mean over the cells at each point, across the ranks.
        cell = whole.points[whole.cells["tetra"]].mean(axis=1) @ np.array([1.0, -1.0, 2.0])
        r.set_cell_field("c", cell[mine])
        img_c = r.render(field="c", **OPTIONS)
        if comm.rank != 0:
            assert img is None and img_c is None
            continue
        one = shellmarch.Renderer(whole)  # one process, no communicator
        one.set_field("f", f)
        one.set_cell_field("c", cell)
        for name, got in (("f", img), ("c", img_c)):
            expected = one.render(field=name, **OPTIONS)
            diff = np.abs(got.astype(int) - expected.astype(int))
            drawn = np.count_nonzero(np.any(expected[:, :, :3] != [26, 26, 31], axis=2))
            print(f"step {step} field {name}: {np.count_nonzero(diff.max(axis=2))} pixels differ, "
                  f"max {diff.max()}, {drawn} pixels drawn", flush=True)
            if diff.max() != 0 or drawn < 100:
                failures += 1
    failures = comm.allreduce(failures)
    if comm.rank == 0:
        print("FAILED" if failures else "passed", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
