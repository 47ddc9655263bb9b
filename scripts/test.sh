#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Quick start 2: install dependencies, build, run the whole test suite.
# BUILD_DIR and extra cmake arguments as for build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
[ "$(id -u)" = 0 ] || SUDO=sudo
SUDO=${SUDO:-} scripts/install-deps.sh
scripts/build.sh "$@"
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j 2 --timeout 900
