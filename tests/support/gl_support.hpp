#pragma once
// For tests that need an OpenGL context of their own: one, or nullptr after printing why the test skips.
#include <depthtrack/error.hpp>
#include <iostream>
#include <memory>

#include "atlas/gl/gl_context.hpp"

namespace depthtrack::test {

inline std::unique_ptr<render::GlContext> gl_context_or_skip() {
  try {
    return std::make_unique<render::GlContext>();
  } catch (const BackendError& e) {
    std::cout << "SKIPPED: no OpenGL context: " << e.what() << "\n";
    return nullptr;
  }
}

}  // namespace depthtrack::test
