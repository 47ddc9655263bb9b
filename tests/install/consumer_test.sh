#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Installs the build into a scratch prefix (cmake --install), then builds
# tests/install/consumer against it twice, as a C++ user would: with
# find_package(dot) and with pkg-config; both programs must run.
#   tests/install/consumer_test.sh BUILD_DIR
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
echo "installed: $(cd "$work/prefix" && find include/dot -name '*.h' | wc -l) headers," \
     "$(cd "$work/prefix" && find . -name 'libdot_core.a' -o -name 'dotConfig.cmake' -o -name dot.pc | sort | tr '\n' ' ')"
# With the binaries: bash completion, and man pages where help2man is.
test -f "$work/prefix/share/bash-completion/completions/dotctl" ||
  { echo "no bash completion installed"; exit 1; }
if command -v help2man > /dev/null; then
  for page in dotctl dot-server; do
    test -s "$work/prefix/share/man/man1/$page.1" ||
      { echo "no man page of $page installed"; exit 1; }
  done
  echo "man pages: dotctl.1 dot-server.1; bash completion: dotctl"
fi
# The installed dotctl finds its remote half (nothing listens on port 1:
# unreachable, exit 3; without the module it would be a usage error, 2).
rc=0
"$work/prefix/bin/dotctl" --server 127.0.0.1:1 health --health-timeout 2 \
  > "$work/health.log" 2>&1 || rc=$?
if [ "$rc" != 3 ]; then
  echo "installed dotctl health: exit $rc, not 3 (unreachable):"
  cat "$work/health.log"
  exit 1
fi
echo "installed dotctl: loads $(cd "$work/prefix" && find . -name dotctl-remote.so)"
# 1. CMake: find_package(dot) -> dot::core.
cmake -S "$here/consumer" -B "$work/cmake" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/cmake" > "$work/build.log"
echo "find_package(dot): $("$work/cmake/consumer")"
# 2. pkg-config (relocatable: the prefix is where dot.pc is).
pc_dir=$(dirname "$(find "$work/prefix" -name dot.pc)")
flags=$(PKG_CONFIG_PATH=$pc_dir pkg-config --cflags --libs dot)
c++ -std=c++17 -O1 "$here/consumer/main.cc" $flags -o "$work/pc_consumer"
echo "pkg-config dot: $("$work/pc_consumer")"
