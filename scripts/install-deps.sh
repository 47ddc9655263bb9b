#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Installs the Debian bookworm packages dot builds and tests with. Idempotent.
# Run as root (or through sudo).
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config git ccache
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libtet1.5-dev libcgal-dev libeigen3-dev libtbb-dev libspdlog-dev libcli11-dev prometheus-cpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcgal-demo   # real meshes (data.tar.gz) for the hole tests
  openssl curl gnuplot-nox
  help2man  # man pages of dotctl and dot-server, from their --help
  python3-grpcio  # raw-wire service tests (/usr/bin/python3)
  python3-protobuf python3-numpy python3-pytest  # dot_client and its tests
  python3-meshio  # dot_client's mesh files (optional for it; its tests use it)
  blender  # the Blender add-on's headless tests (3.4, on the system Python)
  chromium  # the viewer pages' headless browser test
)
# The viewer's script is bundled from the npm registry at build time: npm
# and Node.js from Debian unless the machine has them already (another
# nodejs package may provide both).
if ! command -v npm >/dev/null || ! command -v node >/dev/null; then
  packages+=(nodejs npm)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  ${SUDO:-} apt-get update -qq
  ${SUDO:-} apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
