#!/usr/bin/env bash
# The soak's limits can fail: scripts/soak --summarize on made-up `render --stats` CSVs. A clean run
# passes; one GL error, one NaN pixel or 5% resident-memory growth after warm-up each fail it.
set -euo pipefail
soak="$(dirname "$0")/../../scripts/soak"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# 20 frames: warm-up is frames 0-1; RSS at frame 1 is 100000 KiB. $1: the last frame's RSS, $2: GL
# errors of frame 10, $3: NaN/Inf pixels of frame 15.
make_csv() {
  echo "frame,ms,rss_kb,gl_errors,nonfinite_pixels"
  for f in $(seq 0 19); do
    rss=100000
    [ "$f" -eq 0 ] && rss=90000 # warm-up growth does not count
    [ "$f" -eq 19 ] && rss=$1
    errors=0; [ "$f" -eq 10 ] && errors=$2
    nonfinite=0; [ "$f" -eq 15 ] && nonfinite=$3
    echo "$f,10.5,$rss,$errors,$nonfinite"
  done
}
expect() { # name, expected status, csv arguments
  local name=$1 want=$2
  shift 2
  make_csv "$@" > "$dir/$name.csv"
  set +e
  out=$(bash "$soak" --summarize "$dir/$name.csv")
  status=$?
  set -e
  echo "$out"
  if [ "$status" -ne "$want" ]; then
    echo "FAIL: $name: exit status $status, expected $want"
    exit 1
  fi
}
expect clean 0 104900 0 0        # +4.9%: under the limit
expect gl-error 1 100000 1 0
expect nonfinite 1 100000 0 1
expect rss-growth 1 105000 0 0   # +5.0%: at the limit fails
echo "soak limits: ok"
