#!/usr/bin/env bash
# Imperfect shadow maps bit-identical with LP_NUM_THREADS=1 and 2 (llvmpipe's compute thread count):
# runs the determinism test once per setting, each writing the hash of the maps, and compares the
# two. Usage: ism_threads.sh <vplgi_tests_gl>
set -euo pipefail
binary="$1"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
for threads in 1 2; do
  LP_NUM_THREADS=$threads VPLGI_ISM_HASH_FILE="$dir/$threads" "$binary" "ISM: the maps are bit-identical run to run"
done
echo "LP_NUM_THREADS=1: $(cat "$dir/1")  LP_NUM_THREADS=2: $(cat "$dir/2")"
cmp "$dir/1" "$dir/2"
