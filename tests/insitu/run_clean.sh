#!/usr/bin/env bash
# Empties the output folder, then runs the command: stale frames of an earlier run must never
# stand in for this one's. Usage: run_clean.sh DIR COMMAND ARGS...
set -u
rm -rf "$1" || exit 1
shift
exec "$@"
