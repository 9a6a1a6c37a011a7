#pragma once
// A platform's GetProcAddress, free of GL headers so that osmesa.h (which pulls in GL/gl.h) and
// GL/glcorearb.h never meet in one file.
namespace depthtrack::render {
using GlProc = void (*)();
using GlProcLoader = GlProc (*)(const char* name);
}  // namespace depthtrack::render
