// What this build left out, for tests that skip then (compiled with the build's DEPTHTRACK_WITH_* options).
#include <iostream>

#include "device_support.hpp"

namespace depthtrack::test {

bool gl_built() {
#ifdef DEPTHTRACK_WITH_GL
  return true;
#else
  std::cout << "SKIPPED: the GL atlas is not built (DEPTHTRACK_WITH_GL=OFF)\n";
  return false;
#endif
}

}  // namespace depthtrack::test
