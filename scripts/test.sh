#!/usr/bin/env bash
# Second command: build and run the default ctest suite (the long studies
# are labelled 'long' and excluded; run them with: ctest --test-dir build -L long).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-dependencies.sh
# ccache keys paths relative to the tree and leaves the build directory
# out of its keys (deal.II's flags ask for debug information), so another
# clone reuses the cache.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
cmake --build build -j "$(nproc)"
ctest --test-dir build -j "$(nproc)" --output-on-failure -LE long
