#!/usr/bin/env bash
# vplgi conform end to end, beside the CI subset (conform_subset.sh): --shard runs disjoint cells whose
# --merge equals the unsharded run's cells; the report's parts; bad input is one error line.
set -eu
vplgi="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(--scenes furnace,glossy --techniques vpl-brsm,ir --seeds 2 --width 16 --height 12 --spp 16
        --set ir.vplCount=64 --set rsm.size=32 --set vpl-brsm.count=64 --cache "$work/cache")
"$vplgi" conform "${common[@]}" --out "$work/all" > "$work/all.md" 2> /dev/null
"$vplgi" conform "${common[@]}" --shard 1/2 --out "$work/s1" > /dev/null 2>&1
"$vplgi" conform "${common[@]}" --shard 2/2 --out "$work/s2" > /dev/null 2>&1
"$vplgi" conform --merge "$work/s1,$work/s2" --out "$work/merged" > "$work/merged.md"
for f in conform.json index.html images/cell0-matched.png images/cell0-technique.png images/cell0-error.png; do
  test -s "$work/all/$f" || { echo "FAIL: $f missing"; exit 1; }
done
test "$(grep -c '^| furnace\|^| glossy' "$work/all.md")" -eq 4 || { echo "FAIL: table rows"; cat "$work/all.md"; exit 1; }
python3 - "$work/all/conform.json" "$work/s1/conform.json" "$work/s2/conform.json" "$work/merged/conform.json" <<'PY'
import json, sys
a, s1, s2, m = (json.load(open(p))["cells"] for p in sys.argv[1:])
key = lambda c: (c["scene"], c["technique"])
assert [key(c) for c in s1] == [("furnace", "vpl-brsm"), ("glossy", "vpl-brsm")], [key(c) for c in s1]
assert [key(c) for c in s2] == [("furnace", "ir"), ("glossy", "ir")], [key(c) for c in s2]
drop = lambda c: {k: v for k, v in c.items() if k not in ("images", "seconds")}  # wall times differ by run
assert sorted(map(drop, m), key=key) == sorted(map(drop, a), key=key), "merged shards differ from the full run"
for c in a:
    assert c["seeds"] == 2 and c["biasMatched"]["count"] == 2 and c["biasMatched"]["halfWidth95"] > 0, c
    assert c["matchedMeanLuminance"] > 0 and c["techniqueMeanLuminance"] > 0, c
    assert c["drift"] is None, c  # one frame: no drift
    assert c["seconds"] > 0, c  # the cell's wall time, for sizing a matrix
PY
grep -q 'images/cell0-matched.png' "$work/all/index.html"
echo "conform: shards merge into the full run's cells; report complete"

# Bad input: one error line, non-zero exit, no report.
printf '{"source": "builtin:furnace", "replaceLights": true}\n' > "$work/dark.json"
bad() { # bad <expected text> <args...>
  local text=$1; shift
  if "$vplgi" conform "$@" --out "$work/bad" > /dev/null 2> "$work/e.log"; then echo "FAIL: conform $* passed"; exit 1; fi
  test "$(grep -c 'vplgi: error:' "$work/e.log")" -eq 1 && grep -q "$text" "$work/e.log" \
    || { echo "FAIL: conform $*: expected one error line with \"$text\""; cat "$work/e.log"; exit 1; }
  test ! -e "$work/bad" || { echo "FAIL: conform $* left a report"; exit 1; }
}
bad "has no light" --scenes "$work/dark.json" --techniques ir --seeds 1 --width 8 --height 8 --spp 1
bad "must be I/N" --scenes furnace --shard 3/2
bad "must be I/N" --scenes furnace --shard x
bad "is required" --techniques ir
bad "no conform.json" --merge "$work/nothing"
bad 'unknown parameter "nonsense.key"' --scenes furnace --set nonsense.key=1
echo "conform: bad input is one error line"
