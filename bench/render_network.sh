#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Renders a curve network and the surface dotctl surface made of it, side
# by side, to PNG with gnuplot (before: the curves; after: the surface
# with the curves on it).
# usage: bench/render_network.sh NETWORK.obj SURFACE.obj OUT.png [VIEW] [UP]
#   VIEW: gnuplot "rot_x, rot_z" (default 70, 30); UP: the model's up axis,
#   x, y or z (default z)
set -euo pipefail
network=$1 surface=$2 out=$3 view=${4:-70, 30} up=${5:-z}
# gnuplot's up is z: rotate the model so that its UP axis is.
case $up in
  x) swap='{t=$2; $2=$3; $3=$4; $4=t}' ;;
  y) swap='{t=$3; $3=$4; $4=t; $2=-$2}' ;;
  *) swap='' ;;
esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Triangles as gnuplot polygons: three vertices, then a blank line.
awk "/^v /$swap {print; next} {print}" "$surface" > "$tmp/surface.obj"
awk "/^v /$swap {print; next} {print}" "$network" > "$tmp/network.obj"
awk '/^v /{x[++n]=$2; y[n]=$3; z[n]=$4}
     /^f /{for(i=2;i<=4;i++){split($i,a,"/"); print x[a[1]], y[a[1]], z[a[1]]}; print ""}' \
  "$tmp/surface.obj" > "$tmp/tris.dat"
# Polylines: their points, then a blank line.
awk '/^v /{x[++n]=$2; y[n]=$3; z[n]=$4}
     /^l /{for(i=2;i<=NF;i++){split($i,a,"/"); print x[a[1]], y[a[1]], z[a[1]]}; print ""}' \
  "$tmp/network.obj" > "$tmp/curves.dat"
gnuplot <<GP
set terminal pngcairo size 1400,700 enhanced font "DejaVu Sans,13"
set output "$out"
set multiplot layout 1,2
unset border; unset tics; unset key; unset colorbox
set view $view, 1.0
set view equal xyz
set title "the curve network"
splot "$tmp/curves.dat" using 1:2:3 with lines lw 1.5 lc rgb "#d1495b"
set title "dotctl surface"
set pm3d depthorder lighting primary 0.6 specular 0.15
set pm3d border lc rgb "#6f8fb0" lw 0.2
splot "$tmp/tris.dat" using 1:2:3 with polygons fc rgb "#8fb4e0"
unset multiplot
GP
echo "wrote $out"
