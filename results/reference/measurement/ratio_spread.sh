#!/bin/bash
# x unsorted spread across three invocations: old-style (fixed 5 frames, no rounds) vs rounds (defaults).
O=${OITBENCH:-build/harness/oitbench}
O=$(realpath "$O")
T="-t unsorted -t weighted_blended -t linked_list -t linearized_fragment_buffer -t kbuffer -s quads --size 256x256"
out=${1:?usage: ratio_spread.sh OUT_DIR}; mkdir -p "$out"; cd "$out"
for i in 1 2 3; do
  $O bench $T --warmup 1 --frames 5 --rounds 1 --csv before_$i.csv > before_$i.out 2>&1
  $O bench $T --csv after_$i.csv > after_$i.out 2>&1
done
echo finished > done
