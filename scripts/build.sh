#!/usr/bin/env bash
# Configures and builds everything into build/ (Release). Arguments are cmake
# configure options, e.g. -DLCCP_BUILD_TESTS=OFF.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(nproc)"
