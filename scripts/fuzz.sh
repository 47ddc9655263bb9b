#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Builds the libFuzzer targets of tests/fuzz/ with clang-14 (ASan + UBSan)
# into build-fuzz/ (or $BUILD_DIR) and runs each for SECONDS (default 60)
# over a scratch copy of its seed corpus tests/fuzz/corpus/<target>/ (the
# committed corpus is never written). Prints the executions per target and
# exits non-zero on any crash, leak, timeout, out-of-memory or sanitizer
# report (the reproducer and the log stay in the scratch directory).
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#
# Targets: polygon_text_fuzz polygon_obj_fuzz mesh_file_fuzz request_fuzz
# fill_stream_fuzz triangulate_fuzz network_fuzz
# (default: all). Environment:
#   FUZZ_RUNS=N        also stop a target after N executions
#   FUZZ_WORK=DIR      scratch directory (kept); default a temporary one,
#                      removed when every target passed
#   FUZZ_BUILD_JOBS=N  parallel compile jobs (default 1: a 2-core machine)
#   FUZZ_ASAN=0        build without AddressSanitizer (UBSan only) into
#                      build-fuzz-fast/: several times faster, for long
#                      campaigns; replay their corpus under ASan afterwards
#   FUZZ_SEED=DIR      also start from the inputs in DIR/<target>/ (e.g. a
#                      kept FUZZ_WORK/<target>/corpus of an earlier run)
# Installs what it needs (as root, or with sudo): the build dependencies
# (scripts/install-deps.sh) and clang-14 with libFuzzer (libclang-rt-14-dev).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
if (($#)); then shift; fi
all_targets=(polygon_text_fuzz polygon_obj_fuzz mesh_file_fuzz request_fuzz fill_stream_fuzz triangulate_fuzz network_fuzz)
targets=("$@")
((${#targets[@]})) || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $t "* ]] || {
    echo "fuzz.sh: unknown target '$t' (have: ${all_targets[*]})" >&2
    exit 2
  }
done
[[ "$seconds" =~ ^[0-9]+$ ]] || {
  echo "usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]" >&2
  exit 2
}

# Dependencies.
[ "$(id -u)" = 0 ] || SUDO=${SUDO-sudo}
SUDO=${SUDO:-} scripts/install-deps.sh
fuzz_packages=(clang-14 libclang-rt-14-dev)
missing=()
for p in "${fuzz_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  ${SUDO:-} apt-get update -qq
  ${SUDO:-} apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Build: only the fuzz targets and the libraries they link.
asan=${FUZZ_ASAN:-1}
if [ "$asan" = 0 ]; then
  build=${BUILD_DIR:-build-fuzz-fast}
  asan_flag=OFF
else
  build=${BUILD_DIR:-build-fuzz}
  asan_flag=ON
fi
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
fi
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  "${launcher[@]}" -DDOT_FUZZ=ON -DDOT_FUZZ_ASAN="$asan_flag" -DDOT_BUILD_SERVICE=ON \
  -DDOT_BUILD_TESTS=OFF -DDOT_BUILD_BENCH=OFF >/dev/null
nice -n 19 cmake --build "$build" --target "${targets[@]}" \
  -j "${FUZZ_BUILD_JOBS:-1}"

# Run.
if [ -n "${FUZZ_WORK:-}" ]; then
  work=$FUZZ_WORK
  keep=1
  mkdir -p "$work"
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/dot-fuzz.XXXXXX")
  keep=0
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# System libraries' one-time globals (protobuf, gRPC), as in CI.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/.ci/lsan.supp:print_suppressions=0}
max_len() {
  case $1 in
    polygon_text_fuzz | polygon_obj_fuzz) echo 4096 ;;
    request_fuzz) echo 2048 ;;
    fill_stream_fuzz) echo 4096 ;;
    triangulate_fuzz) echo 512 ;;
    network_fuzz) echo 2048 ;;
  esac
}
fuzz_stat() { sed -n "s/^stat::$1: *//p" "$2" | tail -1; }

failed=()
summary=()
for t in "${targets[@]}"; do
  corpus=$work/$t/corpus
  rm -rf "$corpus"
  mkdir -p "$corpus" "$work/$t/artifacts"
  cp tests/fuzz/corpus/"$t"/* "$corpus"/
  if [ -n "${FUZZ_SEED:-}" ] && [ -d "$FUZZ_SEED/$t" ]; then
    find "$FUZZ_SEED/$t" -maxdepth 1 -type f -exec cp -t "$corpus" {} +
  fi
  log=$work/$t/fuzz.log
  args=("$corpus" -max_total_time="$seconds" -max_len="$(max_len "$t")"
    -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
    -artifact_prefix="$work/$t/artifacts/")
  [ -n "${FUZZ_RUNS:-}" ] && args+=(-runs="$FUZZ_RUNS")
  echo "== $t: ${seconds}s${FUZZ_RUNS:+ or $FUZZ_RUNS runs}, log $log"
  start=$EPOCHREALTIME
  rc=0
  nice -n 19 "$build/tests/fuzz/$t" "${args[@]}" >"$log" 2>&1 || rc=$?
  elapsed=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')
  execs=$(fuzz_stat number_of_executed_units "$log")
  rate=$(fuzz_stat average_exec_per_sec "$log")
  files=$(find "$corpus" -type f | wc -l)
  bytes=$(du -sb "$corpus" | cut -f1)
  # A sanitizer report that did not end the run still fails it.
  if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)|runtime error:|ORACLE FAILED" "$log"; then
    ((rc)) || rc=1
  fi
  verdict=ok
  if ((rc)); then
    verdict="FAILED (exit $rc)"
    failed+=("$t")
    grep -E "ERROR|SUMMARY|ORACLE|runtime error|Test unit written|#[0-9]+ +(pulse|NEW|REDUCE)" "$log" |
      tail -25 >&2 || true
    tail -5 "$log" >&2
    ls "$work/$t/artifacts" >&2
  fi
  line=$(printf "%-18s %12s execs %8s s %8s exec/s  corpus %5s files %8s bytes  %s" \
    "$t" "${execs:-?}" "$elapsed" "${rate:-?}" "$files" "$bytes" "$verdict")
  echo "$line"
  summary+=("$line")
done

echo "== fuzz summary"
printf '%s\n' "${summary[@]}"
if ((${#failed[@]})); then
  echo "fuzz.sh: findings in ${failed[*]}; reproducers and logs in $work" >&2
  exit 1
fi
((keep)) || rm -rf "$work"
