# Sourced by the GPU scripts: device_tests BINARY TAGS runs the test binary's TAGS on CUDA and on NVIDIA
# OpenCL, printing each failure's expansion (its INFO: scene, mode, frame) and the counts. TEST_LIMIT
# (seconds, default 0: none) bounds each backend's run, for a short device budget.
device_tests() {
  local binary=$1 tags=$2 b
  for b in cuda opencl:nvidia; do
    echo "== tests on $b"
    DEPTHTRACK_TEST_DEVICE=$b timeout "${TEST_LIMIT:-0}" "$binary" "$tags" >/tmp/tests.log 2>&1
    grep -E -A8 "FAILED" /tmp/tests.log | head -60
    grep -E "test cases|assertions" /tmp/tests.log
  done
}
