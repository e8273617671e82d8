# Helpers the command-line test scripts source: Open MPI as root (CI runs as root), `mpi N CMD...`
# on N ranks (oversubscribed: ranks may outnumber cores), `fail MESSAGE`,
# `refused WANT OUT CMD...` (a one-line error, exit status 1, nothing written), and
# `json FILE EXPRESSION`, which fails unless the Python expression on the file's JSON (as j) holds.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi() { local n=$1; shift; mpiexec -n "$n" --oversubscribe "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
# `refused WANT OUT CMD...`: CMD must fail with one line of error containing WANT, and leave no
# file OUT (bad input writes nothing).
refused() {
  local want=$1 out=$2; shift 2
  local rc=0
  "$@" >refused.log 2>&1 || rc=$?
  # 1 exactly: a crash or a sanitizer's abort after the right message is a failure too.
  [ $rc -eq 1 ] || { cat refused.log; fail "'$*' exit $rc, wanted 1"; }
  grep -qF -- "$want" refused.log || { cat refused.log; fail "'$*': no message with '$want'"; }
  [ "$(grep -c error refused.log)" -eq 1 ] || { cat refused.log; fail "'$*': not one line of error"; }
  [ ! -e "$out" ] || fail "'$*' wrote $out"
}
json() {
  python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1" ||
    fail "$1: $2"
}
