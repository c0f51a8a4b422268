#!/usr/bin/env bash
# The CPU test binary (core library only) has no GL, EGL, GLX, GLFW or epoxy library among its
# direct dependencies (DT_NEEDED). Libraries that dependencies pull in themselves (OpenImageIO's
# own) are not ours to control and are not checked.
set -eu
binary="$1"
needed=$(readelf -d "$binary" | grep NEEDED)
if echo "$needed" | grep -E 'lib(GL|EGL|GLX|OpenGL|epoxy|glfw)[.-]'; then
  echo "FAIL: $binary links a GL library directly"; exit 1
fi
echo "$(basename "$binary") links no GL library:"
echo "$needed"
