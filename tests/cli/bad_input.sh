#!/usr/bin/env bash
# The bad-input catalogue (issue #13 part 1): every command given broken files, options and
# environments. An error case passes when vplgi exits non-zero (and not by a signal: < 128), prints
# exactly one line on stderr, "vplgi: error: ...", containing the expected text (which names the
# file, key or value at fault), and leaves no file of any kind (image, report directory, JSON, a
# temporary) in its working directory. A warning case (input vplgi accepts but changes or that
# renders black) passes when vplgi exits 0, prints only "vplgi: warning: ..." lines on stderr, one
# containing the expected text, and writes its output.
#
# usage: bad_input.sh path/to/vplgi      (any build: plain, ASan, UBSan)
# Cases run two at a time, each in its own directory; the glTF inputs come from make_bad_gltf.py.
set -u
vplgi=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
here=$(cd "$(dirname "$0")" && pwd)
glsl="$here/../../glsl"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir in
python3 "$here/make_bad_gltf.py" in || { echo "FAIL: make_bad_gltf.py"; exit 1; }
export VPLGI_CACHE_DIR="$work/cache" # caches are not outputs: kept away from the checked directories
unset DISPLAY WAYLAND_DISPLAY       # view must fail on its input, never open a window
# An ASan report must not pass for an ordinary error exit.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}exitcode=134"
jobs_max=2
count=0

# Inputs beyond make_bad_gltf.py's: the old scene-file cases, a regular file to write "under", and
# shader folders with one file missing or broken.
printf '{ "source": "builtin:cornell", ' > in/malformed.json
printf 'not a gltf' > in/broken.gltf
printf '{"source": "builtin:cornell", "lights": [{"name": "bad", "type": "point", "intensity": -3}]}' > in/negative.json
printf '{"source": "builtin:cornell", "colour": 1}' > in/unknownkey.json
printf 'frame 2 screenshot\n' > in/bad-script.txt
: > in/afile
for variant in missing broken noinclude; do cp -r "$glsl" "in/glsl-$variant"; done
rm in/glsl-missing/passes/tonemap.frag
printf 'this is not GLSL;\n' >> in/glsl-broken/passes/direct.frag
rm in/glsl-noinclude/lib/frame.glsl
inputs_before=$(cd in && find . | sort | md5sum)

# check KIND WANT OUTPUT ARGS...: one case, run in ./cNNN; prints "ok: ..." or "FAIL: ...".
# KIND error: non-zero exit, one "vplgi: error:" line containing WANT, nothing written.
# KIND warning: exit 0, only "vplgi: warning:" lines on stderr, one containing WANT, OUTPUT written.
# $limit_kb (when set) caps the size of files the command may write (ulimit -f), SIGXFSZ ignored so
# that the write fails with EFBIG instead of killing the process.
check() {
  local kind="$1" want="$2" output="$3"; shift 3
  local err rc lines label="$*"
  if [ -n "${limit_kb:-}" ]; then
    label="(file size limit ${limit_kb} KiB) $label"
    err=$( (trap '' XFSZ; ulimit -f "$limit_kb"; exec timeout -k 5 120 "$vplgi" "$@") 2>&1 >/dev/null); rc=$?
  else
    err=$(timeout -k 5 120 "$vplgi" "$@" 2>&1 >/dev/null); rc=$?
  fi
  [ -n "${VPLGI_GLSL_DIR:-}" ] && label="VPLGI_GLSL_DIR=${VPLGI_GLSL_DIR#"$work"/} $label"
  # Progress bars and per-frame progress are not messages; everything else on stderr is.
  err=$(printf '%s\n' "$err" | tr '\r' '\n' | grep -Ev '^\s*$|\[[# ]*\] *[0-9]+%$|^frame [0-9]+/[0-9]+ done$')
  lines=$(printf '%s' "$err" | grep -c . || true)
  local fail=""
  if [ "$kind" = error ]; then
    if [ "$rc" -eq 0 ]; then fail="exit 0"
    elif [ "$rc" -eq 124 ] || [ "$rc" -ge 128 ]; then fail="exit $rc (a crash, a sanitizer report or a hang)"
    elif [ "$lines" -ne 1 ]; then fail="$lines lines on stderr, expected one"
    elif [[ "$err" != "vplgi: error: "* ]]; then fail="the line is not 'vplgi: error: ...'"
    elif [[ "$err" != *"$want"* ]]; then fail="the message lacks '$want'"
    elif [ -n "$(find . -mindepth 1 | head -3)" ]; then fail="files were left: $(find . -mindepth 1 | head -3 | tr '\n' ' ')"
    fi
  else
    if [ "$rc" -ne 0 ]; then fail="exit $rc"
    elif printf '%s\n' "$err" | grep . | grep -qv '^vplgi: warning: '; then fail="stderr has more than warnings"
    elif [[ "$err" != *"$want"* ]]; then fail="no warning with '$want'"
    elif [ ! -s "$output" ]; then fail="no $output written"
    fi
  fi
  if [ -z "$fail" ]; then
    echo "ok: $label -> $(printf '%s' "$err" | tr '\n' '|')"
  else
    echo "FAIL: $label: $fail"
    printf '%s\n' "$err" | head -5 | sed 's/^/    /'
  fi
}

# Starts one case in the background (at most $jobs_max at a time), in its own directory.
start() {
  count=$((count + 1))
  local dir
  dir=$(printf 'c%03d' "$count")
  mkdir "$dir"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n; done
  (cd "$dir" && check "$@") > "$dir.result" 2>&1 &
}
error() { local want="$1"; shift; start error "$want" "" "$@"; }
warning() { local want="$1" output="$2"; shift 2; start warning "$want" "$output" "$@"; }

I=../in
S=(--width 16 --height 16) # tiny images: the cases are about input, not pixels

# ---- render: files ----
error "missing.glb: no such file" render --scene missing.glb --out a.png
error "$I/empty.gltf:1:1: invalid JSON" render --scene $I/empty.gltf "${S[@]}" --out a.png
error "$I/empty.glb: Too short data size for glTF Binary" render --scene $I/empty.glb "${S[@]}" --out a.png
error "$I/truncated.glb: Invalid glTF binary" render --scene $I/truncated.glb "${S[@]}" --out a.png
error "$I/malformed.gltf:116:" render --scene $I/malformed.gltf "${S[@]}" --out a.png
error "$I/malformed.json:1:32: invalid JSON" render --scene $I/malformed.json "${S[@]}" --out a.png
error "POSITION: accessor 0: data extends past the end of its buffer" render --scene $I/accessor-offset.gltf "${S[@]}" --out a.png
error "POSITION: accessor 0: data extends past the end of its buffer" render --scene $I/stride-past-end.gltf "${S[@]}" --out a.png
error "POSITION: accessor 0: byteStride 4 is smaller than an element" render --scene $I/stride-small.gltf "${S[@]}" --out a.png
error "primitive 0: index 9 out of range (4 vertices)" render --scene $I/index-range.gltf "${S[@]}" --out a.png
error "indices: accessor 2: data extends past the end of its buffer" render --scene $I/index-count.gltf "${S[@]}" --out a.png
error "indices: indices must be unsigned 8, 16 or 32 bit integers" render --scene $I/indices-float.gltf "${S[@]}" --out a.png
error "POSITION: accessor 0: componentType 5130 is not valid glTF" render --scene $I/component-double.gltf "${S[@]}" --out a.png
error "mesh 0 (floor) primitive 0: POSITION: accessor 0: element 0 is not finite (nan)" render --scene $I/position-nan.gltf "${S[@]}" --out a.png
error "mesh 0 (floor) primitive 0: POSITION: accessor 0: element 1 is not finite (inf)" render --scene $I/position-inf.glb "${S[@]}" --out a.png
error "mesh 0 (floor) primitive 0: NORMAL: accessor 1: element 2 is not finite (nan)" render --scene $I/normal-nan.gltf "${S[@]}" --out a.png
error "$I/light-negative.gltf: light 0 (lamp): intensity must be >= 0" render --scene $I/light-negative.gltf "${S[@]}" --out a.png
error "$I/light-inf.gltf: invalid JSON: number overflow parsing '1e999'" render --scene $I/light-inf.gltf "${S[@]}" --out a.png
error "$I/light-nan.json: invalid JSON: number overflow parsing '1e999'" render --scene $I/light-nan.json "${S[@]}" --out a.png
error "$I/unknownkey.json: unknown key \"colour\"" render --scene $I/unknownkey.json "${S[@]}" --out a.png
error "image 0: uri \"../outside.png\" points outside the scene's folder (refused" render --scene $I/scene/texture-outside.gltf "${S[@]}" --out a.png
error "image 0: uri \"sub/%2E%2E/%2e%2e/outside.png\" points outside the scene's folder (refused" render --scene $I/scene/texture-escaped.gltf "${S[@]}" --out a.png
error "/outside.png\" is an absolute path (refused" render --scene $I/scene/texture-absolute.gltf "${S[@]}" --out a.png
error "buffer 0: uri \"../outside.bin\" points outside the scene's folder (refused" render --scene $I/scene/buffer-outside.gltf "${S[@]}" --out a.png
error "$I/scene/buffer-missing.gltf: File not found : absent.bin" render --scene $I/scene/buffer-missing.gltf "${S[@]}" --out a.png
error "$I/scene/texture-huge.gltf: " render --scene $I/scene/texture-huge.gltf "${S[@]}" --out a.png
error "unsupported required extension KHR_draco_mesh_compression" render --scene $I/required-extension.gltf "${S[@]}" --out a.png
error "$I/source-missing.json: \"source\": $I/absent.gltf: no such file" render --scene $I/source-missing.json "${S[@]}" --out a.png
error "$I/animation-missing-light.json: animations[0]: no light named \"nosuchlight\"" render --scene $I/animation-missing-light.json "${S[@]}" --out a.png
error "unknown scene \"nosuchscene\"" render --scene nosuchscene --out a.png

# ---- render: options, parameters, budgets ----
error "unknown option --bogus" render --scene cornell --bogus
error "--width -5 is outside" render --scene cornell --width -5 --out a.png
error "--width 65536 is outside [1, 16384]" render --scene cornell --width 65536 --height 32768 --out a.png
error "unknown technique \"nope\"" render --scene cornell --technique nope --out a.png
error "unknown parameter \"renderer.exposur\"" render --scene cornell --set renderer.exposur=2 --out a.png
error "renderer.exposure = -1 is outside" render --scene cornell --set renderer.exposure=-1 --out a.png
error "parameter smcir.vplCount = 2000000 is outside [1, 1048576]" render --scene cornell --technique smcir --set smcir.vplCount=2000000 "${S[@]}" --out a.png
error "lightskin.cacheDistance = 0.000100 m would cut an instance into about" render --scene cornell --technique lightskin --set lightskin.cacheDistance=0.0001 "${S[@]}" --out a.png
error "no camera \"nocam\"" render --scene cornell --camera nocam --out a.png
error "must end in .png or .exr" render --scene cornell --out a.jpg
error "--scene is required" render
error "unknown command" paint
error "needs a value" render --scene

# ---- render: outputs, shaders ----
error "$I/afile/a.png: $I/afile is not a directory" render --scene cornell "${S[@]}" --out $I/afile/a.png
error "/proc/a.png: cannot write in /proc" render --scene cornell "${S[@]}" --out /proc/a.png
limit_kb=4 error "big.exr: write failed: File too large" render --scene cornell --width 128 --height 128 --out big.exr
VPLGI_GLSL_DIR=$work/in/glsl-missing error "glsl/passes/tonemap.frag: cannot open shader file" render --scene cornell "${S[@]}" --out a.png
VPLGI_GLSL_DIR=$work/in/glsl-broken error "glsl/passes/direct.frag:" render --scene cornell "${S[@]}" --out a.png
VPLGI_GLSL_DIR=$work/in/glsl-noinclude error "frame.glsl" render --scene cornell "${S[@]}" --out a.png
VPLGI_GLSL_DIR=$work/in/no-such-glsl error "shader directory $work/in/no-such-glsl not found" render --scene cornell "${S[@]}" --out a.png

# ---- view (no display here: every case must fail on its input first) ----
error "missing.glb: no such file" view --scene missing.glb
error "element 0 is not finite (nan)" view --scene $I/position-nan.gltf
error "missing.txt" view --scene cornell --script missing.txt
error "$I/bad-script.txt:1:" view --scene cornell --script $I/bad-script.txt
error "--width 0 is outside" view --scene cornell --width 0
error "unknown option --out" view --scene cornell --out a.png
error "no display (DISPLAY is not set)" view --scene cornell

# ---- reference ----
error "--spp 0 is outside" reference --scene cornell "${S[@]}" --spp 0 --out r.exr
error "bogus" reference --scene cornell "${S[@]}" --mode bogus --out r.exr
error "r.png: the reference is linear radiance: write an .exr" reference --scene cornell "${S[@]}" --out r.png
error "--width 2147483648 is outside" reference --scene cornell --width 2147483648 --out r.exr
error "/proc/r.exr: cannot write in /proc" reference --scene cornell "${S[@]}" --spp 1 --out /proc/r.exr
error "--cache $I/afile: not a directory" reference --scene cornell "${S[@]}" --spp 1 --cache $I/afile --out r.exr
limit_kb=4 error "r.exr: write failed: File too large" reference --scene cornell --width 128 --height 128 --spp 1 --no-cache --out r.exr

# ---- compare ----
error "unknown option --reference" compare --scene cornell "${S[@]}" --reference missing.exr --out c
error "unknown technique \"nope\"" compare --scene cornell "${S[@]}" --techniques direct,nope --out c
error "parameter smcir.vplCount = 0 is outside" compare --scene cornell "${S[@]}" --techniques 'smcir[smcir.vplCount=0]' --out c
error "--against \"vsgl\" must be one of --techniques" compare --scene cornell "${S[@]}" --against vsgl --out c
error "--seeds 0 is outside [1, 1000]" compare --scene cornell "${S[@]}" --seeds 0 --out c
error "--width 4 is outside [8, 8192]" compare --scene cornell --width 4 --height 16 --out c
error "$I/afile/c: $I/afile is not a directory" compare --scene cornell "${S[@]}" --out $I/afile/c
error "/proc/c: cannot write in /proc" compare --scene cornell "${S[@]}" --out /proc/c
VPLGI_GLSL_DIR=$work/in/glsl-broken error "glsl/passes/direct.frag:" compare --scene cornell "${S[@]}" --spp 1 --reference-spp 1 --tracked 1 --tracked-choice grid --out c
# --spp 0: no full-image reference, so the first large file is the report's own (a technique's EXR).
limit_kb=4 error "write failed: File too large" compare --scene cornell --width 64 --height 64 --spp 0 --reference-spp 1 --tracked 1 --tracked-choice grid --out c

# ---- bench ----
error "--frames 0 is outside" bench --scene cornell "${S[@]}" --frames 0
error "unknown technique \"nope\"" bench --scene cornell "${S[@]}" --against nope
error "--against-set needs --against" bench --scene cornell "${S[@]}" --against-set smcir.vplCount=8
error "parameter vsgl.count = 0 is outside" bench --scene cornell "${S[@]}" --technique vsgl --set vsgl.count=0
error "/proc/b.json: cannot write in /proc" bench --scene cornell "${S[@]}" --frames 1 --json /proc/b.json
error "$I/afile/b.json: $I/afile is not a directory" bench --scene cornell "${S[@]}" --frames 1 --json $I/afile/b.json

# ---- smcir-selection ----
error "--frames 5 is outside" smcir-selection --scene cornell --frames 5
error "--checkpoints must be a comma-separated list of integers (got \"10,x\")" smcir-selection --scene cornell --frames 10 --checkpoints 10,x
error "--checkpoints must lie in [0, --frames] (got 20)" smcir-selection --scene cornell --frames 10 --checkpoints 20
error "unknown parameter \"smcir.rankRadiancee\"" smcir-selection --scene cornell --frames 10 --variant "smcir.rankRadiancee=candidate"
error "parameter smcir.rankRadiance: \"best\" is not one of" smcir-selection --scene cornell --frames 10 --variant "smcir.rankRadiance=best"

# ---- accepted with a warning: the decisions (README "Bad input") ----
warning "$I/no-lights.gltf: the scene has no lights" a.png render --scene $I/no-lights.gltf "${S[@]}" --out a.png
warning "$I/degenerate.gltf: dropped 2 degenerate (zero-area) triangles in 1 primitive, first in mesh 0 (floor) primitive 0" a.png render --scene $I/degenerate.gltf "${S[@]}" --out a.png
warning "dropped 1 degenerate (zero-area) triangle in 1 primitive, first in mesh 1 (lamp-line) primitive 0; 1 of them emissive; 1 primitive left empty" r.exr reference --scene $I/emissive-zero-area.gltf "${S[@]}" --spp 4 --out r.exr
warning "$I/all-degenerate.gltf: the scene has no triangles" a.png render --scene $I/all-degenerate.gltf "${S[@]}" --out a.png

wait
failures=0
for result in c*.result; do
  cat "$result"
  grep -q '^FAIL' "$result" && failures=$((failures + 1))
done
# No case may write next to its inputs (a temporary beside a scene file, a cache in the wrong place).
if [ "$(cd in && find . | sort | md5sum)" != "$inputs_before" ]; then
  echo "FAIL: files appeared or vanished under the inputs"; failures=$((failures + 1))
fi

# --help works on every subcommand and exits 0.
for cmd in render view scenes reference compare bench conform smcir-selection; do
  if ! "$vplgi" "$cmd" --help | grep -q "usage: vplgi $cmd"; then
    echo "FAIL: vplgi $cmd --help"; failures=$((failures + 1))
  fi
done
"$vplgi" --help | grep -q "commands:" || { echo "FAIL: vplgi --help"; failures=$((failures + 1)); }

echo "$count cases, $failures failures"
[ "$failures" -eq 0 ]
