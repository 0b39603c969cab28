#!/usr/bin/env bash
# tools/gpu_survey.sh: what to run in one slot on a shared GPU node, with
# binaries that are ALREADY BUILT (it never builds).
#
#   tools/gpu_survey.sh [--build DIR] [--out DIR] [--compare-build DIR] [--only STEP,...]
#                       [--doctor-arg ARG]... [--quick]
#
# Steps, each bounded by `timeout`, each one's command, duration and exit
# status recorded; a failing step does not stop the ones after it, and the
# script exits 1 at the end when any failed:
#   smi_start  nvidia-smi: clocks, temperature, power, driver (when it exists)
#   list       `oitbench list`: the device lines, limits, EGL devices
#   doctor     `oitbench doctor`: profile, clocks, floor, exact techniques held to their class
#   ctest      the GL tests that matter most on a new device (ctest -R, in the build directory)
#   quads      bench: every technique on 32 stacked quads at 1920x1080
#   quads64    bench: every technique on 64 stacked quads at 1920x1080
#   engine     bench: every technique on the engine model at 1920x1080
#   dragon     bench: every technique on the largest packaged mesh (dragon_vrip) at 1920x1080
#   compare    (with --compare-build) `oitbench compare --builds THIS OTHER -- <bench>` in alternating rounds
#   smi_end    nvidia-smi again
# Everything goes to results/reference/gpu/<device>-<date>/ (--out DIR
# instead), with a README.md of what ran, rewritten after every step so that
# a slot cut short still leaves its record.
#
# Caps (seconds; a step past its cap is stopped and recorded as exit 124),
# sized from the first full survey on an H200, whose raster pipeline is slow
# (its steps' times: results/reference/gpu/); together they bound a survey at
# about 16 minutes, 18 with compare:
#   doctor 180: 6 exact techniques x 5 scenes at 64x64, check-order, 24 stress
#     processes.
#   ctest 150: the listed GL suites at their test sizes.
#   quads 150, quads64 200: 15 runs each, each 0.3 s warm-up and at most 1.5 s
#     of timed frames (precision 2 %) but at least 10 frames, in 3 rounds.
#   engine, dragon 150 each: 15 runs each, the same repetition.
#   compare 120: 3 techniques on 32 quads, 8 invocations per build (the
#     fewest with which the paired test can reach p < 0.01).
# --quick: llvmpipe in CI, under 2 minutes: tiny sizes, three techniques,
# the torus and nested spheres for the models, one short ctest; --out is
# required.
set -u -o pipefail

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${OIT_BUILD_DIR:-$REPO/build}
OUT=""
COMPARE_BUILD=""
ONLY=""
QUICK=0
DOCTOR_ARGS=()

usage() { sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; }
fail_usage() { echo "gpu_survey.sh: $1" >&2; usage >&2; exit 2; }

while [ $# -gt 0 ]; do
  case "$1" in
    --build) [ $# -ge 2 ] || fail_usage "--build needs a directory"; BUILD=$2; shift 2 ;;
    --out) [ $# -ge 2 ] || fail_usage "--out needs a directory"; OUT=$2; shift 2 ;;
    --compare-build) [ $# -ge 2 ] || fail_usage "--compare-build needs a directory"; COMPARE_BUILD=$2; shift 2 ;;
    --only) [ $# -ge 2 ] || fail_usage "--only needs a comma-separated list of steps"; ONLY=$2; shift 2 ;;
    --doctor-arg) [ $# -ge 2 ] || fail_usage "--doctor-arg needs an argument"; DOCTOR_ARGS+=("$2"); shift 2 ;;
    --doctor-arg=*) DOCTOR_ARGS+=("${1#--doctor-arg=}"); shift ;;
    --quick) QUICK=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) fail_usage "unknown argument '$1'" ;;
  esac
done

OITBENCH=$BUILD/harness/oitbench
[ -x "$OITBENCH" ] || fail_usage "no oitbench at $OITBENCH: build first (bash setup.sh build, or cmake and ninja), then give --build DIR; this script never builds"
BUILD=$(cd "$BUILD" && pwd)
OITBENCH=$BUILD/harness/oitbench
if [ -n "$COMPARE_BUILD" ]; then
  [ -x "$COMPARE_BUILD/harness/oitbench" ] || fail_usage "--compare-build $COMPARE_BUILD has no harness/oitbench (build it first)"
  COMPARE_BUILD=$(cd "$COMPARE_BUILD" && pwd)
fi
[ "$QUICK" = 0 ] || [ -n "$OUT" ] || fail_usage "--quick writes to --out DIR (results/reference is for real surveys): give one"

STEPS="smi_start list doctor ctest quads quads64 engine dragon compare smi_end"
for step in ${ONLY//,/ }; do
  case " $STEPS " in *" $step "*) ;; *) fail_usage "--only: unknown step '$step' (steps: $STEPS)" ;; esac
done
wanted() { [ -z "$ONLY" ] || case ",$ONLY," in *",$1,"*) return 0 ;; *) return 1 ;; esac; }

# The device's name for the folder: nvidia-smi's, else the GL renderer's.
device_slug() {
  local name=""
  if command -v nvidia-smi > /dev/null; then name=$(nvidia-smi --query-gpu=name --format=csv,noheader 2> /dev/null | head -n 1); fi
  [ -n "$name" ] || name=$("$OITBENCH" list 2> /dev/null | sed -n 's/^Device: \([^(]*\).*/\1/p' | head -n 1)
  [ -n "$name" ] || name=unknown-device
  echo "$name" | tr '[:upper:]' '[:lower:]' | sed 's/[^a-z0-9]\{1,\}/-/g; s/^-//; s/-$//'
}

if [ -z "$OUT" ]; then
  base=$REPO/results/reference/gpu/$(device_slug)-$(date -u +%F)
  OUT=$base
  n=2
  while [ -e "$OUT" ]; do OUT=$base-$n; n=$((n + 1)); done  # never into an earlier survey
elif [ -d "$OUT" ] && [ -n "$(ls -A "$OUT")" ]; then
  fail_usage "--out $OUT is not empty: give a new directory (nothing is overwritten)"
fi
mkdir -p "$OUT" || { echo "gpu_survey.sh: cannot create $OUT" >&2; exit 2; }
OUT=$(cd "$OUT" && pwd)
export MESA_SHADER_CACHE_DIR=${MESA_SHADER_CACHE_DIR:-$BUILD/mesa_shader_cache}

# The sizes and caps of each mode.
if [ "$QUICK" = 1 ]; then
  MODE="quick (llvmpipe CI form: tiny sizes, three techniques; the torus and nested spheres stand in for the models)"
  TECHNIQUES=(-t unsorted -t linked_list -t kbuffer)
  SIZE=32x32
  REPETITION=(--frames 3 --warmup 0 --warmup-ms 0 --rounds 1)
  QUADS_LAYERS=4 QUADS64_LAYERS=8
  ENGINE_SCENE=(-s torus)
  DRAGON_SCENE=(-s nested_spheres)
  DOCTOR=(doctor --technique linked_list --technique kbuffer)
  CTEST_REGEX='^OrderIndependence\.ReferenceAgreesWithUncappedDepthPeelingOnMeshes$'
  CAP_DOCTOR=100 CAP_CTEST=60 CAP_BENCH=60 CAP_QUADS64=60 CAP_COMPARE=60
else
  MODE="full (GPU sizes)"
  TECHNIQUES=(-t all)
  SIZE=1920x1080
  REPETITION=(--precision 0.02 --min-frames 10 --max-frames 300 --max-seconds 1.5 --warmup-ms 300 --rounds 3)
  QUADS_LAYERS=32 QUADS64_LAYERS=64
  ENGINE_SCENE=(-s model --scene-set name=engine)
  DRAGON_SCENE=(-s model --scene-set name=dragon_vrip)
  DOCTOR=(doctor)
  # The suites that hold every technique to its class on this device.
  CTEST_REGEX='^(OrderIndependence\.|Every/PaperSize\.|EveryTechnique/Stress\.|EveryTechnique\.|Reference|Doctor\.)'
  CAP_DOCTOR=180 CAP_CTEST=150 CAP_BENCH=150 CAP_QUADS64=200 CAP_COMPARE=120
fi

ROWS=()      # one Markdown row per step
FAILED=()    # the steps that failed
STARTED=$(date -u '+%F %T UTC')
# What ran is the build's revision (the binaries may have been copied to a node
# without the checkout's .git); the checkout's, where there is one, beside it.
BUILD_REVISION=$(sed -n 's/^#define OIT_GIT_REVISION "\(.*\)"$/\1/p' "$BUILD/generated/oit_revision.h" 2> /dev/null)
CHECKOUT=$(git -C "$REPO" rev-parse HEAD 2> /dev/null || echo "none (no .git here)")
DIRTY=$(git -C "$REPO" status --porcelain 2> /dev/null | grep -vc '^??' || true)

write_readme() {
  local tmp=$OUT/.README.md.tmp
  {
    echo "# GPU survey: $(sed -n 's/^Device: \(.*\)/\1/p' "$OUT/list.txt" 2> /dev/null | sed 's/ — .*//' | head -n 1)"
    echo
    echo "Written by \`tools/gpu_survey.sh\`, mode $MODE."
    echo
    echo "- started: $STARTED; this file last written: $(date -u '+%F %T UTC')"
    echo "- build's revision (what ran; '-dirty' when built from a changed tree): ${BUILD_REVISION:-unknown}"
    echo "- checkout: $CHECKOUT (${DIRTY:-0} files changed from it, untracked ones not counted)"
    echo "- build: $BUILD"
    [ -z "$COMPARE_BUILD" ] || echo "- compared build (A/B): $COMPARE_BUILD"
    echo "- failed steps: ${FAILED[*]:-none}"
    echo
    echo "| step | command | seconds | exit status | output |"
    echo "|---|---|---|---|---|"
    printf '%s\n' "${ROWS[@]}"
    if [ -s "$OUT/list.txt" ]; then
      echo
      echo "## Device (\`oitbench list\`)"
      echo
      echo '```'
      sed '/^Techniques:/,$d' "$OUT/list.txt"
      echo '```'
    fi
    echo
    echo "Exit status 124: the step ran past its cap and was stopped. nvidia-smi's readings at the start and"
    echo "end are in smi_start.txt and smi_end.txt; each bench step's runs in its CSV (oitbench export --wide"
    echo "gives one row per run)."
  } > "$tmp" && mv "$tmp" "$OUT/README.md"
}

# step NAME CAP_SECONDS OUTPUT_FILE COMMAND...: runs it bounded, records it.
step() {
  local name=$1 cap=$2 output=$3
  shift 3
  wanted "$name" || return 0
  local shown=${SHOWN:-}
  [ -n "$shown" ] || shown=$(printf '%q ' "$@" | sed "s|$BUILD|\$BUILD|g; s|$OUT/||g; s| $||")
  echo "== $name: $shown" >&2
  local begin end status
  begin=$(date +%s.%N)
  timeout --kill-after=10 "$cap" "$@" > "$OUT/$output" 2>&1
  status=$?
  end=$(date +%s.%N)
  local seconds
  seconds=$(awk -v b="$begin" -v e="$end" 'BEGIN { printf "%.1f", e - b }')
  echo "   exit $status after $seconds s" >&2
  [ "$status" = 0 ] || FAILED+=("$name")
  ROWS+=("| $name | \`${shown//|/\\|}\` | $seconds | $status | $output |")
  write_readme
}

# nvidia-smi's clocks, temperature, power and driver (a command line: step
# runs it under `timeout`, which takes no shell function).
SMI_QUERY="nvidia-smi --query-gpu=name,driver_version,pstate,clocks.sm,clocks.mem,clocks.max.sm,temperature.gpu,power.draw --format=csv"
SMI_DETAIL="nvidia-smi -q -d CLOCK,TEMPERATURE,PERFORMANCE"
SMI="if command -v nvidia-smi > /dev/null; then $SMI_QUERY && $SMI_DETAIL; else
  echo 'nvidia-smi not found: no NVIDIA driver here (software GL or another vendor)'; fi"
BENCH=("$OITBENCH" bench "${TECHNIQUES[@]}" --size "$SIZE" "${REPETITION[@]}")

SHOWN="$SMI_QUERY; $SMI_DETAIL" step smi_start 30 smi_start.txt bash -c "$SMI"
step list 60 list.txt "$OITBENCH" list
step doctor "$CAP_DOCTOR" doctor.txt "$OITBENCH" "${DOCTOR[@]}" "${DOCTOR_ARGS[@]}"
step ctest "$CAP_CTEST" ctest.txt ctest --test-dir "$BUILD" --output-on-failure --no-tests=error -j 4 \
  --timeout "$CAP_CTEST" -R "$CTEST_REGEX"
step quads "$CAP_BENCH" quads.txt "${BENCH[@]}" -s quads --scene-set "layers=$QUADS_LAYERS" --csv "$OUT/quads.csv"
step quads64 "$CAP_QUADS64" quads64.txt "${BENCH[@]}" -s quads --scene-set "layers=$QUADS64_LAYERS" --csv "$OUT/quads64.csv"
step engine "$CAP_BENCH" engine.txt "${BENCH[@]}" "${ENGINE_SCENE[@]}" --csv "$OUT/engine.csv"
step dragon "$CAP_BENCH" dragon.txt "${BENCH[@]}" "${DRAGON_SCENE[@]}" --csv "$OUT/dragon.csv"
if [ -n "$COMPARE_BUILD" ]; then
  step compare "$CAP_COMPARE" compare.txt "$OITBENCH" compare --builds "$BUILD" "$COMPARE_BUILD" --build-rounds 8 --out "$OUT/compare" -- \
    -t unsorted -t linked_list -t linearized_fragment_buffer -s quads --scene-set layers=32 --size "$SIZE" "${REPETITION[@]}"
fi
SHOWN="$SMI_QUERY; $SMI_DETAIL" step smi_end 30 smi_end.txt bash -c "$SMI"
write_readme

echo "gpu_survey.sh: wrote $OUT (README.md); failed steps: ${FAILED[*]:-none}" >&2
[ ${#FAILED[@]} -eq 0 ]
