#!/usr/bin/env bash
# Every technique `vplgi scenes` lists renders bit-identical radiance (the EXR's pixels) from the same
# seed: over two runs, with llvmpipe on 1 and 2 threads (and TBB on one CPU), and, for the techniques
# with a sampler worker thread (smcir, ir, smcir-rt), with the worker off (<prefix>.synchronous=true). The scene animates its
# light over several frames, so the worker's hand-over between frames is exercised. The images must
# be lit and finite, or bit-identity would prove nothing, and each technique's image must be brighter
# than direct's (mean > 1.001x): it adds indirect light (the check `cli: every technique, two frames`
# makes in the sanitizer build, here on these renders instead of ten more).
# The worker overlaps the sampling of the next VPL set with the GPU frame, so its frame n shows the
# set the synchronous mode shows at frame n - 1 (core/vpl/vpl_pipeline.h): on a still scene the
# worker's frame 4 must be bit-identical to the synchronous frame 3.
set -u
vplgi="$1"
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=small_budgets.sh
. "$here/small_budgets.sh"
scene="$here/../../scenes/cornell-moving-light.json"
still="$here/../../scenes/cornell.json"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export VPLGI_CACHE_DIR="$work/cache" # LightSkin's caches: computed on the first run, read on the others
failures=0
# The first CPU this process may run on (CPU 0 is not always allowed in a container or under taskset).
one_cpu=$(python3 -c "import os; print(min(os.sched_getaffinity(0)))")
size=(--width 40 --height 24)

render() { # render <technique> <out.exr> <LP_NUM_THREADS> <scene> <frames> [--set ...]
  local technique=$1 out=$2 threads=$3 scene=$4 frames=$5; shift 5
  local small
  small_budgets "$technique"
  # One thread: also one CPU, so TBB (Embree, the CPU samplers) runs on a single worker too.
  local pin=()
  [ "$threads" = 1 ] && pin=(taskset -c "$one_cpu")
  if ! LP_NUM_THREADS=$threads "${pin[@]}" "$vplgi" render --scene "$scene" --technique "$technique" "${size[@]}" \
       --frames "$frames" "${small[@]}" --out "$out" --quiet "$@" > "$work/log" 2>&1; then
    echo "FAIL: $technique ($*) did not render:"; cat "$work/log"; failures=$((failures+1)); return 1
  fi
}

same() { # same <technique> <what> <a.exr> <b.exr>
  if python3 "$here/exr_stats.py" same "$3" "$4"; then
    echo "ok: $1: $2"
  else
    echo "FAIL: $1: $2 differ"; failures=$((failures+1))
  fi
}

techniques=$("$vplgi" scenes | sed -n 's/^techniques: //p')
[ -n "$techniques" ] || { echo "FAIL: vplgi scenes listed no techniques"; exit 1; }
count=0
direct=""
for t in direct $(tr ' ' '\n' <<< "$techniques" | grep -vx direct); do
  count=$((count+1))
  render "$t" "$work/$t-a.exr" 2 "$scene" 3 || continue
  read -r mean bad < <(python3 "$here/exr_stats.py" mean "$work/$t-a.exr")
  if [ "$bad" -ne 0 ] || ! python3 -c "import sys; sys.exit(0 if $mean > 1e-3 else 1)"; then
    echo "FAIL: $t: mean radiance $mean, $bad non-finite values (a black or broken image proves nothing)"
    failures=$((failures+1)); continue
  fi
  [ "$t" = direct ] && direct=$mean
  if [ "$t" != direct ] && ! python3 -c "import sys; sys.exit(0 if $mean > 1.001 * ${direct:-1e30} else 1)"; then
    echo "FAIL: $t: mean radiance $mean does not exceed direct's ${direct:-(not rendered)}: no indirect light"
    failures=$((failures+1))
  fi
  # A second run, on one CPU: equal to the first, it is equal over runs and over thread counts.
  render "$t" "$work/$t-c.exr" 1 "$scene" 3 &&
    same "$t" "a second run on one CPU (taskset -c $one_cpu, LP_NUM_THREADS=1) vs LP_NUM_THREADS=2 (mean $mean)" \
         "$work/$t-a.exr" "$work/$t-c.exr"
  case "$t" in
    smcir|smcir-rt) prefix=smcir ;;
    ir) prefix=ir ;;
    mir) prefix=mir ;;
    *) prefix= ;;
  esac
  if [ -n "$prefix" ]; then
    render "$t" "$work/$t-worker.exr" 2 "$still" 4 &&
      render "$t" "$work/$t-sync.exr" 2 "$still" 3 --set "$prefix.synchronous=true" &&
      same "$t" "the worker's frame 4 vs $prefix.synchronous=true's frame 3 (still scene)" \
           "$work/$t-worker.exr" "$work/$t-sync.exr"
  fi
done
# The comparison itself must be able to fail: two techniques' images differ.
if python3 "$here/exr_stats.py" same "$work/direct-a.exr" "$work/vsgl-a.exr"; then
  echo "FAIL: exr_stats.py same calls direct's and vsgl's images identical"; failures=$((failures+1))
fi
echo "$count techniques, $failures failures"
[ "$failures" -eq 0 ]
