#!/usr/bin/env bash
# Installs the Debian 12 packages LCCP Stream needs, only those missing. Run as root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config zlib1g-dev
  libeigen3-dev libtbb-dev libpcl-dev libopenni2-dev
  libspdlog-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libboost-dev
  libgtest-dev libbenchmark-dev
  python3-dev pybind11-dev python3-numpy python3-pytest
  libroscpp-dev libnodeletlib-dev libnodeletlib-tools pluginlib-dev librosbag-dev
  libsensor-msgs-dev libvisualization-msgs-dev libdiagnostic-msgs-dev libstd-msgs-dev
  ros-core python3-rospy python3-rosbag python3-rostest
  python3-sensor-msgs python3-visualization-msgs python3-diagnostic-msgs
  clang libclang-rt-14-dev
  chromium chromium-driver python3-selenium python3-pil
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" >/dev/null
else
  echo "install-deps: all packages present"
fi
