#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Renders an OBJ mesh and its boundary polygon to PNG with gnuplot.
# usage: bench/render_mesh.sh MESH.obj POLYGON.xyz OUT.png [TITLE]
set -euo pipefail
mesh=$1 polygon=$2 out=$3 title=${4:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Triangles as gnuplot polygons: three vertices, then a blank line.
awk '/^v /{x[++n]=$2; y[n]=$3; z[n]=$4}
     /^f /{for(i=2;i<=4;i++){split($i,a,"/"); print x[a[1]], y[a[1]], z[a[1]]}; print ""}' \
  "$mesh" > "$tmp/tris.dat"
awk 'NF>=3{print $1, $2, $3; if(!f){f=$0}} END{split(f,a," "); print a[1], a[2], a[3]}' \
  "$polygon" > "$tmp/loop.dat"
gnuplot <<GP
set terminal pngcairo size 900,700 enhanced font "DejaVu Sans,12"
set output "$out"
set title "$title"
unset border; unset tics; unset key
set view 48, 22, 1.3
unset colorbox
set view equal xyz
set pm3d depthorder border lc rgb "#1f3b57" lw 0.6
set style fill transparent solid 0.85
set palette defined (0 "#2f5f98", 1 "#d6e8fa")
splot "$tmp/tris.dat" using 1:2:3:(\$3) with polygons fc palette, \
      "$tmp/loop.dat" using 1:2:3 with lines lw 3 lc rgb "#d1495b"
GP
echo "wrote $out"
