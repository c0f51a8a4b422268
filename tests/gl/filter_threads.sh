#!/usr/bin/env bash
# The cross-bilateral filter's output bit-identical with LP_NUM_THREADS=1 and 2 (llvmpipe's thread
# count): runs the determinism test once per setting, each writing the hash of its results, and
# compares the two. Usage: filter_threads.sh <vplgi_tests_gl>
set -euo pipefail
binary="$1"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
for threads in 1 2; do
  LP_NUM_THREADS=$threads VPLGI_FILTER_HASH_FILE="$dir/$threads" "$binary" "bilateral filter: bit-identical over runs"
done
echo "LP_NUM_THREADS=1: $(cat "$dir/1")  LP_NUM_THREADS=2: $(cat "$dir/2")"
cmp "$dir/1" "$dir/2"
