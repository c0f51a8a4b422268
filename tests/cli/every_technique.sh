#!/usr/bin/env bash
# Every technique `vplgi scenes` lists renders two frames of the moving-light Cornell box (a point
# light, so every RSM technique has a source) at a tiny size. Each image must be finite, and every
# technique but `direct` must add light to direct's image (its indirect pass ran and reached the
# output). CI runs this with the ASan + UBSan vplgi too (scripts/test --asan): every technique's
# passes, uploads and CPU halves under the sanitizers, including the worker thread's hand-over.
set -u
vplgi="$1"
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=small_budgets.sh
. "$here/small_budgets.sh"
scene="$here/../../scenes/cornell-moving-light.json"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export VPLGI_CACHE_DIR="$work/cache"
failures=0

techniques=$("$vplgi" scenes | sed -n 's/^techniques: //p')
[ -n "$techniques" ] || { echo "FAIL: vplgi scenes listed no techniques"; exit 1; }
# direct first: the others are compared with it.
for t in direct $(tr ' ' '\n' <<< "$techniques" | grep -vx direct); do
  small_budgets "$t"
  if ! "$vplgi" render --scene "$scene" --technique "$t" --width 32 --height 24 --frames 2 "${small[@]}" \
       --out "$work/$t.exr" --quiet > "$work/$t.log" 2>&1; then
    echo "FAIL: $t did not render:"; cat "$work/$t.log"; failures=$((failures+1)); continue
  fi
  read -r mean bad < <(python3 "$here/exr_stats.py" mean "$work/$t.exr") # mean over R, G and B
  [ "$t" = direct ] && direct=$mean
  if [ "$bad" -ne 0 ]; then
    echo "FAIL: $t: $bad non-finite values"; failures=$((failures+1)); continue
  fi
  # Indirect light on this scene is a few percent of the direct light or more; 0.1% is far from
  # both that and float noise (two techniques share the direct pass bit for bit).
  if [ "$t" != direct ] && ! python3 -c "import sys; sys.exit(0 if $mean > 1.001 * $direct else 1)"; then
    echo "FAIL: $t: mean radiance $mean does not exceed direct's $direct: no indirect light"
    failures=$((failures+1)); continue
  fi
  echo "ok: $t: mean radiance $mean (direct $direct)"
done
echo "$(wc -w <<< "$techniques") techniques, $failures failures"
[ "$failures" -eq 0 ]
