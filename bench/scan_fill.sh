#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Hole filling at scan size: libcgal-demo's bunny00 subdivided twice
# (1.2 M faces), 10 / 100 / 1,000 holes of 200 triangles cut by
# `dotctl generate holes`, then `dotctl fill-holes --local` on each and,
# side by side in the same run, CGAL 5.5 (bench/peer/cgal_fill_file: every
# border cycle through triangulate_refine_and_fair_hole), both whole
# processes as a user pays (read the OFF, fill at the fair stage, write a
# PLY). Prints the generator's time, the median of REPS runs of each with
# its peak memory, and dot's time over CGAL's.
# Usage: bench/scan_fill.sh [BUILD_DIR] [REPS] [HOLE_COUNTS]
#   (data in a temp dir; HOLE_COUNTS default "10 100 1000"; CGAL=0 skips it)
set -euo pipefail
build=${1:-build}
reps=${2:-3}
counts=${3:-10 100 1000}
dotctl=$build/client/dotctl
cgal=$build/bench/cgal_fill_file
mesh=$build/data/meshes/bunny00.off
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$(dirname "$0")/subdivide.py" "$mesh" 2 "$work/bunny2.off" \
  >/dev/null
# Median seconds and peak MiB of REPS runs of a command.
measure() {
  local times=() peak=0 t m
  for _ in $(seq "$reps"); do
    /usr/bin/time -f "%e %M" -o "$work/time" "$@" >/dev/null 2>&1
    read -r t m <"$work/time"
    times+=("$t")
    ((m > peak)) && peak=$m
  done
  local median
  median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((reps + 1) / 2))p")
  echo "$median $((peak / 1024)) ${times[*]}"
}
for k in $counts; do
  start=$(date +%s%N)
  "$dotctl" generate holes -k "$k" -t 200 "$work/bunny2.off" \
    -o "$work/b$k.off" >/dev/null
  gen_ms=$((($(date +%s%N) - start) / 1000000))
  read -r ours ours_mib ours_all < <(measure "$dotctl" fill-holes --local \
    "$work/b$k.off" -o "$work/out.ply")
  line=$(printf 'holes %5d  generate %6d ms  dot %6.2f s (%s) %4d MiB' \
    "$k" "$gen_ms" "$ours" "$ours_all" "$ours_mib")
  if [[ "${CGAL:-1}" != 0 ]]; then
    read -r theirs theirs_mib theirs_all < <(measure "$cgal" "$work/b$k.off" \
      "$work/cgal.ply")
    ratio=$(/usr/bin/python3 -c "print(f'{$ours / $theirs:.2f}')")
    line+=$(printf '  CGAL %6.2f s (%s) %4d MiB  dot/CGAL %s' "$theirs" \
      "$theirs_all" "$theirs_mib" "$ratio")
  fi
  echo "$line"
done
