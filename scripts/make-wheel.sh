#!/usr/bin/env bash
# Builds a Python wheel of rescuesim (the pybind11 extension and the package around it) from a
# build folder, with Debian's python3-build and setuptools, offline (no isolated environment).
#   scripts/make-wheel.sh [BUILD] [OUT]     default build and build/packages
# The wheel is tagged for this interpreter and platform (cp311-cp311-linux_x86_64 on Debian
# 12): the extension links the Debian libraries rescuesim uses, so it installs where those are
# (pip install into a venv made with --system-site-packages, for Debian's numpy; docs/install.md).
# Exit code 2 for bad arguments or a build without the Python API.
set -euo pipefail

build=${1:-build}
out=${2:-$build/packages}
if [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
here=$(cd "$(dirname "$0")/.." && pwd)
package=$build/python/rescuesim
if ! ls "$package"/_rescuesim*.so >/dev/null 2>&1; then
  echo "make-wheel: $package has no _rescuesim extension: build the Python API first (make build; RESCUESIM_PYTHON)" >&2
  exit 2
fi
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
if [ -z "$version" ]; then
  echo "make-wheel: no project version in $build/CMakeCache.txt" >&2
  exit 2
fi

stage=$build/wheel-stage
rm -rf "$stage"
mkdir -p "$stage/rescuesim" "$out"
cp "$package"/*.py "$package"/_rescuesim*.so "$stage/rescuesim/"
cp "$here/LICENSE" "$stage/LICENSE"
cat > "$stage/pyproject.toml" <<TOML
[build-system]
requires = ["setuptools>=61", "wheel"]
build-backend = "setuptools.build_meta"

[project]
name = "rescuesim"
version = "$version"
description = "A simulator for mobile rescue robots: Bullet physics, mazes and SVG worlds, ROS, missions"
readme = {text = "rescuesim's Python API: Gymnasium-shaped environments, scenarios, batches (docs/python.md).", content-type = "text/plain"}
requires-python = "==$(python3 -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")').*"
license = {file = "LICENSE"}
dependencies = ["numpy"]

[tool.setuptools]
packages = ["rescuesim"]

[tool.setuptools.package-data]
rescuesim = ["_rescuesim*.so"]
TOML
# a distribution with a compiled module: setuptools then tags the wheel for this platform
cat > "$stage/setup.py" <<'PY'
from setuptools import setup
from setuptools.dist import Distribution


class BinaryDistribution(Distribution):
    def has_ext_modules(self):
        return True


setup(distclass=BinaryDistribution)
PY
/usr/bin/python3 -m build --wheel --no-isolation --outdir "$out" "$stage" >"$stage/build.log" 2>&1 || {
  cat "$stage/build.log" >&2
  exit 1
}
ls "$out"/rescuesim-"$version"-*.whl
