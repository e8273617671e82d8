#!/usr/bin/env bash
# cmake --install of the python and insitu components into a fresh prefix, then Debian's python3
# imports the package from there (not from the build tree) and renders a tiny Mesh.
#   install_check.sh CMAKE BUILD_DIR PREFIX PYTHON
set -euo pipefail
cmake=$1 build=$2 prefix=$3 python=$4
rm -rf "$prefix"
for component in insitu python; do
  "$cmake" --install "$build" --component "$component" --prefix "$prefix" >/dev/null
done
cd "$prefix"
env -u PYTHONPATH PYTHONPATH="$prefix/lib/python3/dist-packages" "$python" - <<'PY'
import numpy as np
import shellmarch
assert shellmarch.__file__.startswith(__import__("os").getcwd()), shellmarch.__file__
points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
mesh = shellmarch.Mesh(points, {"tetra": np.array([[0, 1, 2, 3]])}, point_data={"f": points[:, 0]})
img = shellmarch.render(mesh, size=(16, 12))
assert img.shape == (12, 16, 4) and (img[:, :, :3] != [26, 26, 31]).any(), img.shape
print("installed module renders", shellmarch.__file__)
PY
