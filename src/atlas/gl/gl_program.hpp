#pragma once
// A linked GLSL program built from shader files embedded at build time (shaders/, by name).
#include <string>
#include <vector>

#include "atlas/gl/gl_functions.hpp"

namespace depthtrack::render {

// Compiles and links, with each of `defines` ("NAME" or "NAME VALUE") as a #define after the
// #version line; BackendError with the shader's name and the info log on failure.
GLuint build_program(const GlFunctions& gl, const std::string& vertex_file, const std::string& fragment_file,
                     const std::vector<std::string>& defines = {});

// Text of an embedded shader file; BackendError when there is none of that name.
const std::string& shader_source(const std::string& file);

}  // namespace depthtrack::render
