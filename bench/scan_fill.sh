#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Hole filling at scan size: libcgal-demo's bunny00 subdivided twice
# (1.2 M faces), 10 / 100 / 1,000 holes of 200 triangles cut by
# `dotctl generate holes`, then `dotctl fill-holes --local` on each, whole
# process as a user pays (read OFF, repair, fill, write PLY). Prints the
# generator's time and the median of REPS fills with its peak memory.
# Usage: bench/scan_fill.sh [BUILD_DIR] [REPS]   (data in a temp dir)
set -euo pipefail
build=${1:-build}
reps=${2:-3}
dotctl=$build/client/dotctl
mesh=$build/data/meshes/bunny00.off
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$(dirname "$0")/subdivide.py" "$mesh" 2 "$work/bunny2.off" \
  >/dev/null
for k in 10 100 1000; do
  start=$(date +%s%N)
  "$dotctl" generate holes -k "$k" -t 200 "$work/bunny2.off" \
    -o "$work/b$k.off" >/dev/null
  gen_ms=$((($(date +%s%N) - start) / 1000000))
  times=()
  peak=0
  for _ in $(seq "$reps"); do
    /usr/bin/time -f "%e %M" -o "$work/time" "$dotctl" fill-holes --local \
      "$work/b$k.off" -o "$work/out.ply" >/dev/null 2>&1
    read -r t m <"$work/time"
    times+=("$t")
    ((m > peak)) && peak=$m
  done
  median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((reps + 1) / 2))p")
  printf 'holes %5d  generate %6d ms  fill-holes --local median %6.2f s (%s)  peak %d MiB\n' \
    "$k" "$gen_ms" "$median" "${times[*]}" $((peak / 1024))
done
