#!/usr/bin/env bash
# Tests the shader-validation test: on a scratch shader tree, a deliberate error in an included file
# must fail it and be reported at glsl/<included file>:<line>; a shader that needs a define must fail
# without it and pass with it; resource counts unlike gl::kResourceNeeds must fail --resource-needs;
# an empty tree must not pass.
#   usage: validator_catches_errors.sh <vplgi_validate_shaders> <glslangValidator>
set -u
validator="$1"
glslang="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures+1)); }

mkdir -p "$work/glsl/lib" "$work/glsl/passes" "$work/empty"
printf '// line 1\n// line 2\nfloat broken() { return undefinedThing; }\n' > "$work/glsl/lib/broken.glsl"
printf '#version 450 core\n#include "../lib/broken.glsl"\nout vec4 color;\nvoid main() { color = vec4(broken()); }\n' \
  > "$work/glsl/passes/broken.frag"
printf '#version 450 core\nlayout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer Out { float result; };\nvoid main() { result = VALUE; }\n' \
  > "$work/glsl/passes/needs_define.comp"
run() { "$validator" --glslang "$glslang" --root "$work/glsl" "$@" 2>&1; }

out=$(run --define passes/needs_define.comp:VALUE=1.0 "$work/glsl"); rc=$?
echo "$out"
[ "$rc" -eq 1 ] || fail "a broken shader gave exit status $rc, expected 1"
case "$out" in *"ERROR: glsl/lib/broken.glsl:3: 'undefinedThing'"*) ;; *) fail "the error is not reported at glsl/lib/broken.glsl:3" ;; esac
case "$out" in *"ok   passes/needs_define.comp -DVALUE=1.0"*) ;; *) fail "the shader with its define was not accepted" ;; esac
case "$out" in *"1 of 2 shader entry points valid"*) ;; *) fail "the summary does not count 1 of 2" ;; esac

rm "$work/glsl/passes/broken.frag"
out=$(run "$work/glsl"); rc=$?
echo "$out"
[ "$rc" -eq 1 ] || fail "a shader without its define gave exit status $rc, expected 1"
case "$out" in *"'VALUE' : undeclared identifier"*) ;; *) fail "the missing define is not named" ;; esac

out=$(run --define passes/needs_define.comp:VALUE=1.0 "$work/glsl"); rc=$?
echo "$out"
[ "$rc" -eq 0 ] || fail "a valid tree gave exit status $rc, expected 0"

# --resource-needs: this tree's counts (one storage block, binding 0; no bindings.h) are not
# gl::kResourceNeeds, so the comparison must fail and say which number differs.
mkdir -p "$work/glsl/shared"
printf 'VPLGI_CONST int kBindingOut = 0; // SSBO float\n' > "$work/glsl/shared/bindings.h"
out=$(run --define passes/needs_define.comp:VALUE=1.0 --resource-needs "$work/glsl"); rc=$?
echo "$out"
[ "$rc" -eq 1 ] || fail "resource counts unlike kResourceNeeds gave exit status $rc, expected 1"
case "$out" in *"storage buffer binding points: 1 / "*) ;; *) fail "the binding points of the scratch bindings.h were not counted as 1" ;; esac
case "$out" in *"compute storage blocks: 1 / "*) ;; *) fail "the scratch compute shader's storage block was not counted" ;; esac
case "$out" in *"FAIL compute storage blocks: counted 1, kResourceNeeds says"*) ;; *) fail "the differing count is not named" ;; esac

out=$(run "$work/empty"); rc=$?
echo "$out"
[ "$rc" -eq 2 ] || fail "an empty tree gave exit status $rc, expected 2 (nothing validated must not pass)"

out=$(run --define passes/gone.comp:X=1 "$work/glsl"); rc=$?
echo "$out"
[ "$rc" -eq 2 ] || fail "a --define for a missing file gave exit status $rc, expected 2"

[ "$failures" -eq 0 ] && echo "the shader validator catches what it should"
exit $((failures > 0))
