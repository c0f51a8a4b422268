#!/usr/bin/env bash
# Results bit-identical with LP_NUM_THREADS=1 and 2 (llvmpipe's rasteriser and compute thread
# count): runs the given Catch2 test spec once per setting; the tests append the hashes of their
# results to $VPLGI_HASH_FILE (tests/common/determinism.h); the two files must be equal and not empty.
# Usage: threads_identical.sh <test binary> <test spec>
set -euo pipefail
binary="$1"
spec="$2"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
for threads in 1 2; do
  LP_NUM_THREADS=$threads VPLGI_HASH_FILE="$dir/$threads" "$binary" "$spec" >/dev/null
done
echo "LP_NUM_THREADS=1: $(tr '\n' ' ' < "$dir/1")  LP_NUM_THREADS=2: $(tr '\n' ' ' < "$dir/2")"
test -s "$dir/1"
cmp "$dir/1" "$dir/2"
