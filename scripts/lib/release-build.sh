# Sourced by the GPU suites: release_build DIR OUT PROGRAM TARGET... builds TARGETs in DIR (Release, no
# tests, no Python) unless DIR/PROGRAM is already there; logs go to OUT. Returns non-zero, with the build
# log's tail printed, when configuring or building fails.
release_build() {
  local dir=$1 out=$2 program=$3
  shift 3
  [[ -x $dir/$program ]] && return 0
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_PYTHON=OFF \
    >"$out/configure.log" 2>&1 && cmake --build "$dir" -j"$(nproc)" --target "$@" >"$out/build.log" 2>&1 ||
    { tail -30 "$out/build.log" "$out/configure.log"; return 1; }
}
