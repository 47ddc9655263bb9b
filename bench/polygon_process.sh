#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# DOT1 (area) against CGAL 5.5's triangulate_hole_polyline as whole
# processes, in turn, on 11 polygons: Monkey, Spiral and Mobius curves of
# 500-5,000 vertices and three hole boundaries of 1,600-2,700 vertices cut
# from libcgal-demo meshes. Each tool's compute time as it reports it, its whole
# process (wall, kernel) and the ratios, medians of REPS runs; no
# environment variable is set for either.
# Usage: bench/polygon_process.sh [BUILD_DIR] [REPS] [MESH_DIR]
set -euo pipefail
build=$(realpath "${1:-build}")
reps=${2:-5}
meshes=${3:-$build/data/meshes}
dotctl=${DOTCTL:-$build/client/dotctl}  # DOTCTL=... compares another build
cgal=$build/bench/cgal_polyline_file
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

inputs=()
for spec in monkey:500 monkey:2000 monkey:5000 spiral:500 spiral:2000 \
  spiral:5000 mobius:500 mobius:1000; do
  f=$work/${spec/:/_}.xyz
  "$dotctl" generate curve "${spec%:*}" -n "${spec#*:}" -o "$f" >/dev/null
  inputs+=("$f")
done
# Hole boundaries: holes grown on the meshes until their rims have 1,600-
# 2,700 vertices, kept when both tools triangulate them.
for spec in bunny00:12000:1 refined_elephant:15000:1 bunny00:20000:1; do
  IFS=: read -r mesh triangles seed <<<"$spec"
  f=$work/hole_${mesh}_$triangles.xyz
  "$dotctl" generate hole "$meshes/$mesh.off" -t "$triangles" --seed "$seed" \
    -o "$f" >/dev/null
  if "$cgal" "$f" "$work/probe.obj" >/dev/null 2>&1 &&
    "$dotctl" triangulate --local --area 1 "$f" -o "$work/probe.obj" \
      >/dev/null 2>&1; then
    inputs+=("$f")
  else
    echo "skipped $(basename "$f"): not triangulable by both" >&2
  fi
done

"$python" - "$dotctl" "$cgal" "$reps" "$work" "${inputs[@]}" <<'PY'
# Each run in turn: wall from the parent, user and kernel time from
# getrusage, compute time as each tool reports it.
import json, os, resource, statistics, subprocess, sys, time
dotctl, cgal, reps, work, inputs = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5:]

def run(argv):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run(argv, check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return out, wall, after.ru_stime - before.ru_stime

rows = []
compute, process = [], []
for f in inputs:
    runs = []
    for _ in range(reps):
        out, dot_wall, dot_sys = run([dotctl, 'triangulate', '--local', '--area', '1',
                                      '--json', f, '-o', os.path.join(work, 'dot.obj')])
        dot_ms = json.loads(out)['summary']['compute_ms']
        out, cgal_wall, cgal_sys = run([cgal, f, os.path.join(work, 'cgal.obj')])
        cgal_ms = float(out.split()[1])
        runs.append((dot_ms, cgal_ms, dot_wall, cgal_wall, dot_sys))
    m = [statistics.median(c) for c in zip(*runs)]
    compute.append(m[0] / m[1])
    process.append(m[2] / m[3])
    n = sum(1 for line in open(f) if line.strip())
    rows.append(f'| {os.path.basename(f)[:-4]} | {n} | {m[0]:.1f} | {m[1]:.1f} '
                f'| {compute[-1]:.2f} | {1e3 * m[2]:.0f} | {1e3 * m[3]:.0f} '
                f'| {process[-1]:.2f} | {100 * m[4] / m[2]:.0f} % |')
print('| input | n | dot compute ms | CGAL compute ms | compute ratio '
      '| dot process ms | CGAL process ms | process ratio | dot kernel share |')
print('|---|---:|---:|---:|---:|---:|---:|---:|---:|')
print('\n'.join(rows))
print(f'\nmedian compute ratio {statistics.median(compute):.2f} '
      f'(range {min(compute):.2f}-{max(compute):.2f}); median process ratio '
      f'{statistics.median(process):.2f} '
      f'(range {min(process):.2f}-{max(process):.2f}); {len(inputs)} inputs, '
      f'medians of {reps} runs')
PY
