#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Runs the README's TLS walk-through (the block between the
# tls-walkthrough markers) as written, in a scratch directory, with the
# build's dot-server and dotctl first on PATH and its port made free.
#   tls_walkthrough_test.sh README.md DOT_SERVER DOTCTL
set -euo pipefail
readme=$1 server=$2 dotctl=$3
command -v openssl >/dev/null || { echo "openssl not installed: skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT  # the walk-through stops its own server
mkdir "$work/bin"
ln -s "$(realpath "$server")" "$work/bin/dot-server"
ln -s "$(realpath "$(dirname "$server")/dot-delaunay-helper")" \
  "$work/bin/dot-delaunay-helper" 2>/dev/null || true
ln -s "$(realpath "$dotctl")" "$work/bin/dotctl"
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
sed -n '/<!-- tls-walkthrough -->/,/<!-- \/tls-walkthrough -->/p' "$readme" |
  sed '1,/^```sh$/d; /^```$/,$d' | sed "s/50443/$port/g" > "$work/walkthrough.sh"
[ -s "$work/walkthrough.sh" ] || { echo "no walk-through in $readme"; exit 1; }
cd "$work"
PATH="$work/bin:$PATH" bash -e walkthrough.sh > out.txt 2>&1 || {
  cat out.txt; echo "the walk-through failed"; exit 1; }
cat out.txt
grep -q '^SERVING$' out.txt || { echo "no SERVING with a client certificate"; exit 1; }
grep -q 'UNREACHABLE' out.txt || { echo "no refusal without one"; exit 1; }
echo "TLS walk-through: ok"
