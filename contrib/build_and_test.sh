#!/bin/bash
# Fresh machine: install what is missing, check the formatting of the C++
# files, build (Release, warnings as errors), run the whole test suite; then
# build with AddressSanitizer + UndefinedBehaviorSanitizer (contrib/sanitize.sh,
# outside the source tree) and run the bad-input tests under them: any failed
# test or sanitizer report fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash contrib/install_dependencies.sh clang-format
bash contrib/check_format.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSL_WARNINGS_AS_ERRORS=ON
cmake --build build -j2
(cd build && ctest --output-on-failure -j2)
SL_SANITIZE_JOBS=2 SL_SANITIZE_TARGETS=stabilized_lagrangian SL_SANITIZE_TIMEOUT=900 \
  bash contrib/sanitize.sh -R '^(bad_input|bad_input_corpus|damaged_checkpoint)$'
