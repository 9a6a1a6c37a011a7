#pragma once
// The test-only compute backend "fake" (fake_backend.cpp): one host-memory device, fake:0, that runs no kernels.
#include "compute/backend.hpp"

namespace depthtrack::test::fake {

compute::Backend backend();

}  // namespace depthtrack::test::fake
