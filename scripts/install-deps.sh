#!/usr/bin/env bash
# Install every Debian package rescuesim needs to build, test and benchmark.
# Idempotent: when everything is already installed it returns at once without
# touching the network. Works as root or through sudo; never asks questions.
set -euo pipefail

packages=(
  # toolchain and test tools
  build-essential cmake ninja-build pkg-config git ca-certificates
  libgtest-dev libgmock-dev libbenchmark-dev clang
  # make lint: the formatter (with git-clang-format) and the linter, version 14 as Debian 12 has
  clang-format-14 clang-tidy-14
  # core, world authoring, CLI
  libeigen3-dev libtinyxml2-dev libyaml-cpp-dev nlohmann-json3-dev
  libcli11-dev libspdlog-dev libfmt-dev libpng-dev zlib1g-dev
  # physics and ray sensors
  libbullet-dev libbullet-extras-dev libembree-dev libtbb-dev
  # robots of one's own: URDF (urdfdom) and their meshes (assimp)
  liburdfdom-dev libassimp-dev
  # Gazebo worlds and models: SDF (sdformat 12, SDF <= 1.9)
  libsdformat-dev
  # rendering: headless EGL on Mesa, a window, GUI panels
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev libepoxy-dev
  libglfw3-dev libimgui-dev libstb-dev xvfb xauth x11-apps netpbm
  # Foxglove WebSocket server and MCAP recording
  libboost-dev libzstd-dev liblz4-dev nodejs
  # ROS 1 (Debian's roscpp) and its command-line tools for tests
  libroscpp-dev ros-core python3-rostopic python3-rosbag librosbag-dev ros-robot-state-publisher
  libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libtf2-msgs-dev
  libros-rosgraph-msgs-dev python3-sensor-msgs python3-nav-msgs
  python3-tf2-msgs python3-geometry-msgs
  # ROS 1 services (/reset_simulation, /pause_physics, ... as gazebo_ros has them): rosservice
  # and std_srvs's Python types, for users and tests (the bridge itself needs no std_srvs headers)
  python3-rosservice python3-std-srvs
  # SLAM demonstration (docs/demos.md): MRPT's ICP scan-matching SLAM
  libmrpt-slam-dev
  # ROS 2 wire compatibility: Cyclone DDS, and Fast DDS as a second vendor for tests
  cyclonedds-dev cyclonedds-tools libfastrtps-dev fastddsgen
  # Python API and scale-out
  python3 python3-dev pybind11-dev python3-numpy python3-distributed
  # packaging: make deb (CPack runs dpkg-shlibdeps, which needs file); make wheel (python3-build,
  # setuptools and wheel, offline) and its test (a venv)
  dpkg-dev file python3-build python3-setuptools python3-wheel python3-venv
)

# npm: the machine's Node.js may come from NodeSource (which bundles npm and
# conflicts with Debian's npm package); only ask Debian for npm when none is present
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  # dpkg -s succeeds for removed-but-configured packages too, so check the status line
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and not root, and sudo is not available" >&2
  exit 1
fi

echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "install-deps: done"
