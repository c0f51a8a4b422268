#!/usr/bin/env bash
# Bad input gives one line naming the problem, a non-zero exit, no crash and no output file.
set -u
vplgi="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0

expect_error() { # expect_error "<substring of the message>" args...
  local want="$1"; shift
  local out rc lines
  out=$("$vplgi" "$@" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c . || true)
  if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
    echo "FAIL: exit $rc for: $*"; failures=$((failures+1)); return
  fi
  if [ "$lines" -ne 1 ]; then
    echo "FAIL: expected one line, got $lines for: $*"; printf '%s\n' "$out"; failures=$((failures+1)); return
  fi
  case "$out" in
    *"$want"*) echo "ok: $* -> $out" ;;
    *) echo "FAIL: message '$out' lacks '$want' for: $*"; failures=$((failures+1)) ;;
  esac
  if [ -n "$(find . -name '*.png' -o -name '*.exr' | head -1)" ]; then
    echo "FAIL: an output file was written for: $*"; failures=$((failures+1)); rm -f ./*.png ./*.exr
  fi
}

printf '{ "source": "builtin:cornell", ' > malformed.json
printf 'not a gltf' > broken.gltf
printf '{"source": "builtin:cornell", "lights": [{"name": "bad", "type": "point", "intensity": -3}]}' > negative.json
printf '{"source": "builtin:cornell", "colour": 1}' > unknownkey.json

expect_error "no such file" render --scene missing.glb --out a.png
expect_error "no such file" render --scene missing.json --out a.png
expect_error "invalid JSON" render --scene malformed.json --out a.png
expect_error "broken.gltf" render --scene broken.gltf --out a.png
expect_error "intensity" render --scene negative.json --out a.png
expect_error "colour" render --scene unknownkey.json --out a.png
expect_error "unknown scene \"nosuchscene\"" render --scene nosuchscene --out a.png
expect_error "unknown option --bogus" render --scene cornell --bogus
expect_error "--width -5 is outside" render --scene cornell --width -5 --out a.png
expect_error "--height \"abc\" is not an integer" render --scene cornell --height abc --out a.png
expect_error "unknown technique \"nope\"" render --scene cornell --technique nope --out a.png
expect_error "unknown parameter \"renderer.exposur\"" render --scene cornell --set renderer.exposur=2 --out a.png
expect_error "renderer.exposure = -1 is outside" render --scene cornell --set renderer.exposure=-1 --out a.png
expect_error "no camera \"nocam\"" render --scene cornell --camera nocam --out a.png
expect_error "must end in .png or .exr" render --scene cornell --out a.jpg
expect_error "does not exist" render --scene cornell --out nodir/a.png
expect_error "a sequence pattern has one frame number" render --scene cornell --out 'a%s.png'
expect_error "unknown technique \"nope\"" render --list-params --technique nope
expect_error "--scene is required" render
expect_error "unknown command" paint
expect_error "needs a value" render --scene

# --help works on every subcommand and exits 0.
for cmd in render view scenes; do
  if ! "$vplgi" "$cmd" --help | grep -q "usage: vplgi $cmd"; then
    echo "FAIL: vplgi $cmd --help"; failures=$((failures+1))
  fi
done
"$vplgi" --help | grep -q "commands:" || { echo "FAIL: vplgi --help"; failures=$((failures+1)); }

echo "$failures failures"
[ "$failures" -eq 0 ]
