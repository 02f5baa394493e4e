#!/bin/bash
# Fresh machine: install what is missing, build (Release), run the default scene
# (the elastic patin of the seed paper) in build/run-default.
set -euo pipefail
cd "$(dirname "$0")/.."
bash contrib/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
mkdir -p build/run-default
cd build/run-default && ../stabilized_lagrangian
