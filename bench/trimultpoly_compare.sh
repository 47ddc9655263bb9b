#!/bin/sh
# SPDX-License-Identifier: AGPL-3.0-or-later
# Two loops, dot against the authors' TriMultPoly (Zou, Ju, Carr, SGP 2013)
# on the same inputs: optimal area over Delaunay triangles (both must agree)
# and time. TriMultPoly is not a dependency: build it yourself from its
# public repository (github.com/yig/TriMultPoly; add `#include <algorithm>`
# and `#include <climits>` to src/main.cpp and src/Algorithm/DMWT.cpp for
# GCC 12) and pass its binary.
#
#   bench/trimultpoly_compare.sh /path/to/TriMultPoly [build/client/dotctl]
set -eu
tmp_bin=$(readlink -f "$1")
dotctl=$(readlink -f "${2:-build/client/dotctl}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
/usr/bin/python3 - <<'PY'
import math, random
# Rims as dot-bench --only loops makes them: radius 1 at height 0 and a
# second rim running against it, noise of a third of the point spacing.
cases = [("tube", n, 0.7, 0.8) for n in (50, 200, 500, 1000)] + \
        [("island", n, 0.35, 0.05) for n in (50, 200, 1000)]
for kind, n, r2, z2 in cases:
    rng = random.Random(n)
    loops = []
    for l in range(2):
        radius = r2 if l else 1.0
        noise = 2 * math.pi * radius / n / 3
        loop = []
        for i in range(n):
            a = (-1 if l else 1) * 2 * math.pi * i / n
            r = radius + noise * rng.uniform(-1, 1)
            loop.append((r * math.cos(a), r * math.sin(a),
                         (z2 if l else 0) + noise * rng.uniform(-1, 1)))
        loops.append(loop)
    name = f"{kind}{n}"
    with open(name + ".xyz", "w") as f:
        f.write("\n\n".join("\n".join("%.17g %.17g %.17g" % p for p in L)
                            for L in loops) + "\n")
    with open(name + ".curve", "w") as f:
        f.write(f"2\n{2 * n}\n")
        for L in loops:
            f.write(f"{len(L)}\n" + "".join("%.17g %.17g %.17g\n" % p
                                            for p in L))
PY
printf '%-12s %14s %14s %12s %12s %8s\n' case "TMP area" "dot area" \
  "TMP s" "dot s" ratio
for c in tube50 tube200 tube500 tube1000 island50 island200 island1000; do
  # TriMultPoly: useDT=1 useMinSet=1 area=1 perimeter=0 dihedral=0,
  # no min-max, save the OBJ, no normals. It prints its own time.
  "$tmp_bin" "$c" 1 1 1 0 0 0 1 0 > "$c.tmp.log"
  tmp_cost=$(awk '/^cost:/ {print $2}' "$c.tmp.log")
  tmp_s=$(awk '/time:/ {print $3}' "$c.tmp.log")
  # dot: the same Delaunay space, compute time as the summary reports it.
  "$dotctl" -q triangulate --local --json --space delaunay "$c.xyz" \
    --format obj -o "$c.dot.obj" > "$c.dot.json"
  set -- $(/usr/bin/python3 -c "import json; s = json.load(open('$c.dot.json'))['summary']; print('%.6g %.4f' % (s['total_cost'], s['compute_ms'] / 1000))")
  ratio=$(/usr/bin/python3 -c "print('%.0fx' % ($tmp_s / $2))")
  printf '%-12s %14s %14s %12s %12s %8s\n' "$c" "$tmp_cost" "$1" "$tmp_s" \
    "$2" "$ratio"
done
