#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Hole filling at scan size: dot-bench's scan figure alone (see
# bench/suite/fig_scan.cc): bunny00 subdivided twice (1.2 M faces) with
# 10 / 100 / 1,000 holes of 200 triangles and three times (4.8 M faces)
# with 30 of 3,000, `dotctl fill-holes --local` and CGAL 5.5 side by side
# as whole processes, then the largest mesh through a dot-server.
# Usage: bench/scan_fill.sh [BUILD_DIR] [REPS] [OUT_DIR]
set -euo pipefail
build=${1:-build}
exec "$build/bench/dot-bench" --only scan --reps "${2:-3}" \
  --out "${3:-bench-results/scan}"
