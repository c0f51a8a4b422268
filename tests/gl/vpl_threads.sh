#!/usr/bin/env bash
# smcir and ir images bit-identical with LP_NUM_THREADS=1 and 2 (llvmpipe's thread count): runs the
# determinism test once per setting, each appending the hash of its image, and compares.
# Usage: vpl_threads.sh <vplgi_tests_gl>
set -euo pipefail
binary="$1"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
for threads in 1 2; do
  LP_NUM_THREADS=$threads VPLGI_VPL_HASH_FILE="$dir/$threads" "$binary" "[vpl-determinism]" >/dev/null
done
echo "LP_NUM_THREADS=1: $(tr '\n' ' ' < "$dir/1")  LP_NUM_THREADS=2: $(tr '\n' ' ' < "$dir/2")"
cmp "$dir/1" "$dir/2"
