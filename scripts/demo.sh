#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Quick start 1: install dependencies, build, start dot-server on localhost,
# triangulate a bundled hole boundary with dotctl, write the mesh, stop.
set -euo pipefail
cd "$(dirname "$0")/.."
[ "$(id -u)" = 0 ] || SUDO=sudo
SUDO=${SUDO:-} scripts/install-deps.sh
scripts/build.sh
port=${DOT_DEMO_PORT:-50051}
build/server/dot-server --listen "127.0.0.1:$port" --metrics-port 0 \
  --source-archive "" --log-level warn &
server=$!
trap 'kill -TERM $server 2>/dev/null; wait $server 2>/dev/null || true' EXIT
for _ in $(seq 50); do
  build/client/dotctl --server "127.0.0.1:$port" health >/dev/null 2>&1 && break
  sleep 0.1
done
mkdir -p out
echo "== dotctl triangulate data/samples/elephant-hole.xyz (a 300-triangle hole, with the mesh's normals)"
build/client/dotctl --server "127.0.0.1:$port" triangulate \
  data/samples/elephant-hole.xyz -o out/elephant-hole.obj \
  --area 1 --squared-dihedral 0.5 --normal-deviation 0.2 --protect-edges --validate
echo "== dotctl triangulate data/samples/spiral.xyz --json"
build/client/dotctl --server "127.0.0.1:$port" triangulate data/samples/spiral.xyz \
  -o out/spiral.obj --squared-dihedral 1 --json
echo "meshes written to out/"
