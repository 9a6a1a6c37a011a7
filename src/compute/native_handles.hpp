#pragma once
// A queue's objects as its backend's API names them, for code that must call that API itself (the GL
// hand-offs in src/interop/), instead of downcasting the queue: each API has its own fields, null (or -1)
// where the queue is not of that API, so a caller asks for what it can use, not for a backend's name.
// Plain pointers: no device header is needed to see them (the layering rule).
namespace depthtrack::compute {

struct NativeHandles {
  // OpenCL: cl_context, cl_device_id, cl_command_queue.
  void* cl_context = nullptr;
  void* cl_device = nullptr;
  void* cl_queue = nullptr;
  // CUDA: the device's primary context (CUcontext), the queue's stream (CUstream) and the device (CUdevice).
  void* cu_context = nullptr;
  void* cu_stream = nullptr;
  int cu_device = -1;
};

}  // namespace depthtrack::compute
