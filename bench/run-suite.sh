#!/bin/sh
# SPDX-License-Identifier: AGPL-3.0-or-later
# The benchmark suite in one command: builds, then runs dot-bench, which
# writes CSV files, PNG plots and report.md into $OUT (bench-results).
# Extra arguments go to dot-bench (--quick, --reps N, --only curves, ...).
# Takes about half an hour on a 2-core machine; --quick takes seconds.
set -eu
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
OUT="${OUT:-bench-results}"
BUILD_DIR="$BUILD_DIR" scripts/build.sh
# Transparent huge pages for large heap blocks: page faults otherwise cost
# this VM up to half of a large solve. Applies to every process measured
# (ours, CGAL's, the server) alike.
export GLIBC_TUNABLES="${GLIBC_TUNABLES:-glibc.malloc.hugetlb=1}"
exec "$BUILD_DIR/bench/dot-bench" --out "$OUT" "$@"
