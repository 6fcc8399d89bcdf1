#!/usr/bin/env bash
# The Python package's check (python/module.mk: its pytest against the
# `stray` of the same build, then the example notebook), as one job of the
# test pool in `make test` (tests/run-tests.sh), after the build is made.
# Usage: scripts/python-check.sh [BUILD_DIR]
set -euo pipefail
b=${1:-${STRAY_BUILD:-build}}
exec make --no-print-directory python-check B="$b"
