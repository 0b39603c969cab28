#!/usr/bin/env bash
# Builds the libFuzzer targets with clang into BUILD_DIR and runs each loader
# (and bucketed_kbuffer's transfer-function text parser, transfer_text)
# for SECONDS seconds from a copy of the seed corpus (libFuzzer adds the
# inputs it finds to its corpus directory; the committed seeds stay as they
# are). Exit code non-zero on any finding; the crashing input is left in
# BUILD_DIR/findings.
#   bash tests/fuzz/run_fuzzers.sh BUILD_DIR [SECONDS]
# Leak detection is off: a loader that rejects a file by exception may leave
# OpenMesh's or tinygltf's caches allocated, which is not what this hunts.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$1"
seconds="${2:-10}"
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
ninja -C "$build" >/dev/null
rm -rf "$build/findings"
mkdir -p "$build/findings"
for format in obj off ply stl gltf glb transfer_text; do
  corpus="$build/corpus/$format"
  rm -rf "$corpus"
  mkdir -p "$corpus"
  cp "$here/corpus/$format/"* "$corpus/"
  echo "fuzz_$format: ${seconds}s"
  "$build/fuzz_$format" -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 -detect_leaks=0 \
    -print_final_stats=1 -artifact_prefix="$build/findings/${format}_" "$corpus" 2>&1 |
    grep -E "^(Done|stat::number_of_executed_units)|ERROR|SUMMARY" || true
  # libFuzzer exits non-zero on a finding; pipefail does not see it through
  # grep, so check the artifacts instead.
  if compgen -G "$build/findings/${format}_*" >/dev/null; then
    echo "fuzz_$format: finding(s) in $build/findings" >&2
    exit 1
  fi
done
