#!/usr/bin/env bash
# Packs the release build in build/ (configured with CUDA) into build-carry/, the layout of the build folder
# that scripts/gpu/carried.sh runs on the GPU machine: the CLI, the benchmarks, the library, the tests and
# the Python plotting module. The GPU machine has no OSMesa: a stand-in library whose every call fails
# (scripts/gpu/stubs/osmesa_stub.c) lets the binaries load there, where EGL draws.
#   scripts/pack-carried-build.sh [BUILD_DIR [INTO]]   (default build, build-carry)
# PACK_BUILD=0 packs what is built without building the rest (e.g. an earlier commit's bench alone).
set -euo pipefail
cd "$(dirname "$0")/.."
from=${1:-build}
into=${2:-build-carry}
[[ ${PACK_BUILD:-1} == 0 ]] || cmake --build "$from" >/dev/null
rm -rf "$into"
mkdir -p "$into/src" "$into/tests" "$into/python/depthtrack"
for program in "$from"/depthtrack "$from"/depthtrack_bench*; do [[ -x $program ]] && cp "$program" "$into/"; done
cp -L "$from/src/libdepthtrack.so.0" "$into/src/"
ln -s libdepthtrack.so.0 "$into/src/libdepthtrack.so"
[[ -x $from/tests/depthtrack_tests ]] && cp "$from/tests/depthtrack_tests" "$into/tests/"
cp "$from"/python/depthtrack/*.py "$into/python/depthtrack/" 2>/dev/null || true
gcc -shared -fPIC -O2 -o "$into/src/libOSMesa.so.8" -Wl,-soname,libOSMesa.so.8 scripts/gpu/stubs/osmesa_stub.c
(git -C "$from/.." log --oneline -1 2>/dev/null || git log --oneline -1) >"$into/commit.txt"
du -sh "$into"
