#!/usr/bin/env bash
# opengl_only_with_cameras.sh RESCUESIM
# `rescuesim run --no-cameras` loads no EGL or GL library (libepoxy opens them on first use),
# so it runs on machines without OpenGL; the same run with cameras does load libEGL (the
# control, so the check cannot pass by seeing nothing). Reads the dynamic loader's own log.
set -euo pipefail
exe=${1:?usage: opengl_only_with_cameras.sh RESCUESIM}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gl_loaded() {  # the EGL/GL/Mesa driver files the loader opened, from its log $1
  grep -o 'file=[^ ;]*\(libEGL\|libGLX\|libGL\.\|libgbm\|_dri\.so\)[^ ;]*' "$1" | sort -u || true
}
LD_DEBUG=files "$exe" run --no-cameras --duration 0.3 -q -o "$tmp/nocam" > /dev/null 2> "$tmp/nocam.log"
LD_DEBUG=files "$exe" run --duration 0.3 -q -o "$tmp/cam" > /dev/null 2> "$tmp/cam.log"
without=$(gl_loaded "$tmp/nocam.log")
with=$(gl_loaded "$tmp/cam.log")
echo "without cameras: ${without:-(none)}"
echo "with cameras: ${with:-(none)}"
status=0
if [[ -n $without ]]; then
  echo "FAIL: --no-cameras loaded OpenGL libraries" >&2
  status=1
fi
if ! grep -q libEGL <<< "$with"; then
  echo "FAIL: a run with cameras did not load libEGL (is the loader log readable?)" >&2
  status=1
fi
exit $status
