// Compiled by the layering tests (tests/CMakeLists.txt) with the include paths of src/filter's target:
// PROBE_HEADER is a device API header, which must stop the build with the layering rule's message, or
// an allowed header of the compute seam, which must compile.
#include PROBE_HEADER

int main() {
  return 0;
}
