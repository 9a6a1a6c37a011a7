// Compiled by the layering tests (tests/CMakeLists.txt) with include/ and Eigen alone on the include path:
// PROBE_HEADER, a public header, must compile without anything from src/.
#include PROBE_HEADER

int main() {
  return 0;
}
