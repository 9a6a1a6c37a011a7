#pragma once
// A GL context's window-system handles, for APIs that share with it (cl_khr_gl_sharing wants the
// display and the context). Free of GL and EGL headers: the handles are opaque pointers.
namespace depthtrack::render {

struct GlNativeContext {
  enum class Api { None, Egl, Glx };  // None: OSMesa, which no other API can share with
  Api api = Api::None;
  void* display = nullptr;  // EGLDisplay or Display*
  void* context = nullptr;  // EGLContext or GLXContext
};

}  // namespace depthtrack::render
