#pragma once
// A linked GLSL program built from shader files embedded at build time (shaders/, by name).
#include <string>

#include "render/gl_functions.hpp"

namespace depthtrack::render {

// Compiles and links; BackendError with the shader's name and the info log on failure.
GLuint build_program(const GlFunctions& gl, const std::string& vertex_file, const std::string& fragment_file);

// Text of an embedded shader file; BackendError when there is none of that name.
const std::string& shader_source(const std::string& file);

}  // namespace depthtrack::render
