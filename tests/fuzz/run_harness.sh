#!/usr/bin/env bash
# Runs one libFuzzer harness over its seed corpus (assembled by make_corpus.py) and prints one line:
#   <harness>: <executions> executions, <crashes> crashes, cov: <edges> ft: <features>, <rate> exec/s
# cov is the number of coverage edges (instrumented code, tinygltf and stb_image included) the corpus
# reaches, ft the finer features libFuzzer tracks (edge counters, comparisons).
#   run_harness.sh HARNESS CORPUS_ROOT FUZZ_SOURCE_DIR [libFuzzer flags, e.g. -runs=N or -max_total_time=S]
# New inputs go to CORPUS_ROOT/<harness>/work (emptied first), reproducers of crashes, leaks, timeouts
# and out-of-memory to CORPUS_ROOT/<harness>/artifacts. Exit status: libFuzzer's (0 = nothing found).
set -u
# Absolute paths: the harness changes into its sandbox directory before libFuzzer reads them.
harness=$(realpath "$1") root=$(realpath "$2") src=$(realpath "$3")
shift 3
name=$(basename "$harness")
seeds="$root/$name/seeds" work="$root/$name/work" artifacts="$root/$name/artifacts"
[ -d "$seeds" ] || { echo "$name: no seed corpus at $seeds (run make_corpus.py)" >&2; exit 2; }
rm -rf "$work" "$artifacts"
mkdir -p "$work" "$artifacts"
log="$root/$name/log.txt"

# -timeout: an input that takes 30 s of wall-clock time is a hang (inputs take milliseconds, the
# largest built-in scene about 1 s under ASan). A run at nice 19 next to builds can be starved for
# longer: raise it there with VPLGI_FUZZ_TIMEOUT (a starved 59 ms input once "timed out" at 10 s).
# rss/malloc limits: libFuzzer's default 2 GB, so a header claiming a huge image or buffer is an
# out-of-memory finding.
VPLGI_FUZZ_FILES="$root/files" "$harness" -dict="$src/$name.dict" -artifact_prefix="$artifacts/" \
  -timeout="${VPLGI_FUZZ_TIMEOUT:-30}" -rss_limit_mb=2048 -print_final_stats=1 "$@" "$work" "$seeds" > "$log" 2>&1
rc=$?

executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
coverage=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1)
crashes=$(find "$artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
if [ "$rc" -ne 0 ] && [ "$crashes" -eq 0 ]; then
  crashes=1 # it stopped for a reason libFuzzer wrote no reproducer for: the log says what
fi
echo "$name: ${executions:-?} executions, $crashes crashes, ${coverage:-cov: ? ft: ?}, ${rate:-?} exec/s"
if [ "$rc" -ne 0 ]; then
  echo "--- $name: exit $rc; last lines of $log:"
  tail -60 "$log"
  ls -l "$artifacts"
fi
exit "$rc"
