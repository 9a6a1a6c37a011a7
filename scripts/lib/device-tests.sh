# Sourced by the GPU scripts: device_tests BINARY TAGS runs the test binary's TAGS on CUDA and on NVIDIA
# OpenCL, printing each failure's expansion (its INFO: scene, mode, frame) and the counts.
device_tests() {
  local binary=$1 tags=$2 b
  for b in cuda opencl:nvidia; do
    echo "== tests on $b"
    DEPTHTRACK_TEST_DEVICE=$b "$binary" "$tags" >/tmp/tests.log 2>&1
    grep -E -A8 "FAILED" /tmp/tests.log | head -60
    grep -E "test cases|assertions" /tmp/tests.log
  done
}
