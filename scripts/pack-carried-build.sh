#!/usr/bin/env bash
# Packs the release build in build/ (configured with CUDA) into build-carry/, the layout of the build folder
# that scripts/gpu/carried.sh runs on the GPU machine: the CLI, the benchmarks, the library and the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build >/dev/null
rm -rf build-carry
mkdir -p build-carry/src build-carry/tests
cp build/depthtrack build/depthtrack_bench* build/depthtrack_confidence_samples build-carry/ 2>/dev/null || true
cp -L build/src/libdepthtrack.so.0 build-carry/src/
ln -s libdepthtrack.so.0 build-carry/src/libdepthtrack.so
cp build/tests/depthtrack_tests build-carry/tests/
git log --oneline -1 >build-carry/commit.txt
git status --short | head -5 >>build-carry/commit.txt
du -sh build-carry
