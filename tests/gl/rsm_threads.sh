#!/usr/bin/env bash
# RSM mips bit-identical with LP_NUM_THREADS=1 and 2 (llvmpipe's rasteriser/compute thread count):
# runs the determinism test once per setting, each writing the hash of every mip level, and
# compares the two. Usage: rsm_threads.sh <vplgi_tests_gl>
set -euo pipefail
binary="$1"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
for threads in 1 2; do
  LP_NUM_THREADS=$threads VPLGI_RSM_HASH_FILE="$dir/$threads" "$binary" "RSM mips are bit-identical over runs"
done
echo "LP_NUM_THREADS=1: $(cat "$dir/1")  LP_NUM_THREADS=2: $(cat "$dir/2")"
cmp "$dir/1" "$dir/2"
