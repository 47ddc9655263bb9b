#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Before and after hole filling, side by side, rendered with gnuplot: the
# input mesh in blue, the faces dotctl fill-holes added in orange (input
# faces it split keep their index and colour).
# usage: bench/render_fill.sh INPUT.off FILLED.off OUT.png [ROT_X ROT_Z]
set -euo pipefail
input=$1 filled=$2 out=$3 rx=${4:-60} rz=${5:-30}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# OFF (header, counts, vertices, faces) -> gnuplot polygons (x y z lines,
# a blank line after each), the faces from index `first_new` on only when
# `part` is "new", the others only when it is "old".
to_polygons() {
  awk -v first_new="$2" -v part="$3" 'BEGIN { v = 0; f = 0 }
    /^#/ || NF == 0 { next }
    !header { header = 1; next }
    !counts { counts = 1; nv = $1; next }
    nv > 0 && v < nv { x[v] = $1; y[v] = $2; z[v] = $3; v++; next }
    NF >= 4 {
      if ((f >= first_new) == (part == "new")) {
        for (i = 2; i <= 4; i++) print x[$i], y[$i], z[$i]
        print ""
      }
      f++
    }' "$1"
}
faces_of() { awk '/^#/ || NF == 0 { next } ++k == 2 { print $2; exit }' "$1"; }
first_new=$(faces_of "$input")
to_polygons "$input" "$first_new" old > "$tmp/before.dat"
to_polygons "$filled" "$first_new" old > "$tmp/after_old.dat"
to_polygons "$filled" "$first_new" new > "$tmp/after_new.dat"
gnuplot <<GP
set terminal png size 1100,500 font "DejaVu Sans,12"
set output "$out"
unset border; unset tics; unset key; unset colorbox
set view $rx, $rz, 1.5
set view equal xyz
set pm3d depthorder border lc rgb "#23395b" lw 1
set style fill solid 1.0
set multiplot layout 1,2
set title "before: $(basename "$input")"
splot "$tmp/before.dat" with polygons fc rgb "#8fb3dd"
set title "after dotctl fill-holes (new faces orange)"
splot "$tmp/after_old.dat" with polygons fc rgb "#8fb3dd", \\
      "$tmp/after_new.dat" with polygons fc rgb "#f08a24"
unset multiplot
GP
echo "wrote $out"
