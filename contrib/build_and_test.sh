#!/bin/bash
# Fresh machine: install what is missing, check the formatting of the C++
# files, build (Release, warnings as errors), run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash contrib/install_dependencies.sh clang-format
bash contrib/check_format.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSL_WARNINGS_AS_ERRORS=ON
cmake --build build -j2
cd build && ctest --output-on-failure -j2
