#!/usr/bin/env bash
# vplgi compare's temporal experiment (SMCIR Table 1) end to end at tiny sizes: tracked pixels in
# indirectly lit regions, the tracked-pixel reference (two seeds, its own |E'| and the 0.2x check,
# cached), per-row technique settings, --seeds (means with intervals), --spp 0 (no full-image reference)
# and --tracked-choice grid.
set -eu
vplgi="$1"
here="$(cd "$(dirname "$0")/../.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cache="$work/cache"

common=(--scene "$here/scenes/cornell-moving-light.json" --reference-mode clamped --frames 3
        --width 32 --height 18 --reference-spp 256 --set smcir.vplCount=64 --cache "$cache")
args=(--techniques smcir-rt "${common[@]}")
"$vplgi" compare "${args[@]}" --spp 0 --out "$work/a" > "$work/a.log" 2> "$work/a.err"
grep -q "reference's own |E'|" "$work/a.log"
grep -q "Reference noise" "$work/a/index.html"
python3 - "$work/a/metrics.json" "$work/a.log" <<'PY'
import json, re, sys
d = json.load(open(sys.argv[1]))
# The printed verdict must be the one the numbers give: yes exactly when the reference's own |E'| is
# at most 0.2x the technique's (one technique here, so it is the smallest).
m = re.search(r"reference <= 0.2x it: (yes|NO) \(ratio ([0-9.e+-]+)\)", open(sys.argv[2]).read())
assert m, "no reference noise verdict in the summary"
ratio = d["tracked"]["referenceAbsEPrime"] / d["techniques"][0]["temporalAbsEPrime"]
assert abs(float(m.group(2)) - ratio) <= 6e-3 * ratio, (m.group(2), ratio)  # printed to 3 significant digits
assert (m.group(1) == "yes") == (ratio <= 0.2), (m.group(1), ratio)
tr = d["tracked"]
assert tr["choice"].startswith("indirect"), tr
assert len(tr["pixels"]) == 8 and len({tuple(p) for p in tr["pixels"]}) == 8, tr
assert all(1 <= x <= 30 and 1 <= y <= 16 for x, y in tr["pixels"]), tr  # never on the border
assert tr["referenceSpp"] == 256 and tr["referenceSeconds"] > 0, tr
assert tr["noiseCheckApplies"] is True and tr["referenceAbsEPrime"] > 0, tr
t = d["techniques"][0]
assert t["name"] == "smcir-rt" and t["settings"] == "smcir.vplCount=64", t
# Measured |E| 0.092 and |E'| 0.0030 over the tracked pixels (64 VPLs, 3 frames); bands 3x either way.
assert t["meanAbsToneMapped"] is None and 0.03 < t["temporalAbsE"] < 0.28 and 0.001 < t["temporalAbsEPrime"] < 0.009, t
assert d["reference"]["spp"] == 0 and "maxDepth 4" in d["reference"]["settings"], d["reference"]
PY
test ! -e "$work/a/images/reference-f0000.png"
echo "temporal: indirect tracked pixels, two-seed reference, check and settings in the report"

# The same run again: the tracked-pixel references come from the cache and every number repeats.
"$vplgi" compare "${args[@]}" --spp 0 --out "$work/b" > "$work/b.log" 2> "$work/b.err"
python3 - "$work/a/metrics.json" "$work/b/metrics.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert b["tracked"]["referenceSeconds"] == 0, b["tracked"]
for k in ("pixels", "referenceAbsE", "referenceAbsEPrime"):
    assert a["tracked"][k] == b["tracked"][k], k
for k in ("temporalAbsE", "temporalAbsEPrime"):
    assert a["techniques"][0][k] == b["techniques"][0][k], k
PY
echo "temporal: tracked-pixel references cached, results repeat"

# --seeds 3: smcir-rt (seed key smcir.seed) three times, direct (no seed of its own) once. Seed 1 is
# run a (the seeds default to 1); the interval is recomputed here from the per-seed values.
"$vplgi" compare "${common[@]}" --techniques smcir-rt,direct --spp 0 --seeds 3 --out "$work/s" > "$work/s.log" 2> "$work/s.err"
python3 - "$work/a/metrics.json" "$work/s/metrics.json" "$work/s/metrics.csv" "$work/s.log" <<'PY'
import csv, json, math, statistics, sys
a, s = (json.load(open(p)) for p in sys.argv[1:3])
t, d = s["techniques"]
assert t["name"] == "smcir-rt" and t["seeds"] == 3 and d["name"] == "direct" and d["seeds"] == 1, (t, d)
for k in ("temporalAbsE", "temporalAbsEPrime"):
    per = t[k + "PerSeed"]
    assert len(per) == 3 and per[0] == a["techniques"][0][k], (k, per, a["techniques"][0][k])
    assert len(set(per)) == 3, (k, per)  # the seed reaches the sampler: three different VPL sets
    assert abs(t[k] - sum(per) / 3) <= 1e-12 * t[k], (k, t[k], per)
    half = 4.303 * statistics.stdev(per) / math.sqrt(3)  # t(0.975, 2 dof) = 4.3027, 3 decimals as meanInterval
    assert abs(t[k + "Half95"] - half) <= 1e-9 + 1e-6 * half, (k, t, half)
    assert d[k + "Half95"] == 0 and len(d[k + "PerSeed"]) == 1, d
rows = list(csv.DictReader(open(sys.argv[3])))
assert rows[0]["seeds"] == "3" and abs(float(rows[0]["temporal_abs_e_prime_half95"]) - t["temporalAbsEPrimeHalf95"]) <= 1e-5 * t["temporalAbsEPrimeHalf95"], rows[0]
assert "(3 seeds)" in open(sys.argv[4]).read()
PY
test -s "$work/s/images/smcir-rt-f0002.png"
if "$vplgi" compare "${args[@]}" --spp 0 --seeds 2 --set smcir.seed=5 --out "$work/x" 2> "$work/e.log"; then exit 1; fi
grep -q -- '--seeds 2 sets smcir.seed to 1..2: do not also set it (smcir-rt)' "$work/e.log"
test ! -e "$work/x"
echo "temporal: --seeds, mean and Student-t interval over the seeds"

# The grid choice and a full-image reference (image metrics back).
"$vplgi" compare "${args[@]}" --tracked-choice grid --tracked 4 --spp 2 --out "$work/g" > "$work/g.log" 2> "$work/g.err"
python3 - "$work/g/metrics.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["tracked"]["choice"].startswith("grid") and len(d["tracked"]["pixels"]) == 4, d["tracked"]
# The full-image metrics are back: measured tone-mapped |E| 0.091 against a 2-spp reference; band 3x.
assert 0.03 < d["techniques"][0]["meanAbsToneMapped"] < 0.27, d["techniques"][0]
PY
test -s "$work/g/images/reference-f0000.png"
# The same with --seeds 2: the image metrics become means over the seeds, seed 1 being run g.
"$vplgi" compare "${args[@]}" --tracked-choice grid --tracked 4 --spp 2 --seeds 2 --out "$work/gs" > "$work/gs.log" 2> "$work/gs.err"
python3 - "$work/g/metrics.json" "$work/gs/metrics.json" <<'PY'
import json, sys
g, s = (json.load(open(p))["techniques"][0] for p in sys.argv[1:])
per = s["imageMetricsPerSeed"]
for key in ("meanAbsToneMapped", "rmse", "meanLuminanceBias"):
    assert len(per[key]) == 2 and per[key][0] == g[key] and per[key][0] != per[key][1], (key, per, g)
    assert abs(s[key] - sum(per[key]) / 2) <= 1e-12 * abs(s[key]), (key, s[key], per[key])
PY
grep -q "image metrics' mean |E|, RMSE" "$work/gs/index.html"
test -s "$work/g/images/smcir-rt-f0002-error.png"
echo "temporal: grid choice, full-image reference"

if "$vplgi" compare "${args[@]}" --tracked-choice random --out "$work/x" 2> "$work/e.log"; then exit 1; fi
grep -q 'must be indirect or grid' "$work/e.log"
test ! -e "$work/x"
echo "temporal checks passed"
