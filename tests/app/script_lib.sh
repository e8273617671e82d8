# Helpers the command-line test scripts source: Open MPI as root (CI runs as root), `mpi N CMD...`
# on N ranks (oversubscribed: ranks may outnumber cores), `fail MESSAGE`, and
# `json FILE EXPRESSION`, which fails unless the Python expression on the file's JSON (as j) holds.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi() { local n=$1; shift; mpiexec -n "$n" --oversubscribe "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
json() {
  python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1" ||
    fail "$1: $2"
}
