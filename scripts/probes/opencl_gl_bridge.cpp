// Probe: can NVIDIA OpenCL read what GL rendered without a host round trip? Neither GL
// (GL_EXT_memory_object_fd) nor OpenCL (cl_khr_external_memory_opaque_fd) can export memory, only
// import it, so a third allocator must export it: here CUDA's virtual memory management
// (cuMemCreate + cuMemExportToShareableHandle, POSIX fd). GL imports it as a pixel-pack buffer and
// glReadPixels into it (a copy on the GPU); OpenCL imports it as a buffer and reads it.
// Build and run on the GPU machine (after `source .device/enter .devdeps`):
//   g++ -std=c++17 -O2 scripts/probes/opencl_gl_bridge.cpp -I/usr/local/cuda/include -lEGL -lOpenCL -ldl -o /tmp/probe
//   /tmp/probe
#define CL_TARGET_OPENCL_VERSION 300
#define EGL_NO_X11
#include <CL/cl.h>
#include <CL/cl_ext.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <GL/glext.h>
#include <cuda.h>
#include <dlfcn.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#define REQUIRE(ok, what)                      \
  do {                                         \
    if (!(ok)) {                               \
      std::printf("FAILED: %s\n", what);       \
      std::exit(1);                            \
    }                                          \
  } while (0)

template <class F>
F gl_proc(const char* name) {
  F f = reinterpret_cast<F>(eglGetProcAddress(name));
  if (!f) std::printf("missing %s\n", name);
  return f;
}

int main() {
  // CUDA: an exportable allocation on device 0.
  void* libcuda = dlopen("libcuda.so.1", RTLD_NOW);
  REQUIRE(libcuda, "dlopen libcuda");
#define CU(f) auto f = reinterpret_cast<decltype(&::f)>(dlsym(libcuda, #f))
  CU(cuInit);
  CU(cuDeviceGet);
  CU(cuDevicePrimaryCtxRetain);
  CU(cuCtxSetCurrent);
  CU(cuMemGetAllocationGranularity);
  CU(cuMemCreate);
  CU(cuMemExportToShareableHandle);
  REQUIRE(cuInit && cuMemCreate && cuMemExportToShareableHandle, "CUDA VMM entry points");
  REQUIRE(cuInit(0) == CUDA_SUCCESS, "cuInit");
  CUdevice device;
  CUcontext context;
  REQUIRE(cuDeviceGet(&device, 0) == CUDA_SUCCESS, "cuDeviceGet");
  REQUIRE(cuDevicePrimaryCtxRetain(&context, device) == CUDA_SUCCESS && cuCtxSetCurrent(context) == CUDA_SUCCESS,
          "primary context");
  CUmemAllocationProp prop{};
  prop.type = CU_MEM_ALLOCATION_TYPE_PINNED;
  prop.location.type = CU_MEM_LOCATION_TYPE_DEVICE;
  prop.location.id = device;
  prop.requestedHandleTypes = CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR;
  size_t granularity = 0;
  REQUIRE(cuMemGetAllocationGranularity(&granularity, &prop, CU_MEM_ALLOC_GRANULARITY_MINIMUM) == CUDA_SUCCESS,
          "granularity");
  const int width = 4096, height = 4096;
  const size_t bytes = (size_t(width) * height * 4 + granularity - 1) / granularity * granularity;
  CUmemGenericAllocationHandle handle;
  REQUIRE(cuMemCreate(&handle, bytes, &prop, 0) == CUDA_SUCCESS, "cuMemCreate (exportable)");
  int fd_gl = -1, fd_cl = -1;
  REQUIRE(cuMemExportToShareableHandle(&fd_gl, handle, CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR, 0) == CUDA_SUCCESS &&
              cuMemExportToShareableHandle(&fd_cl, handle, CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR, 0) == CUDA_SUCCESS,
          "cuMemExportToShareableHandle");
  std::printf("CUDA VMM: %zu bytes exported as fds %d, %d\n", bytes, fd_gl, fd_cl);

  // GL on EGL device 0.
  auto query_devices = gl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto get_display = gl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  EGLDeviceEXT devices[8];
  EGLint count = 0;
  REQUIRE(query_devices(8, devices, &count) && count > 0, "eglQueryDevicesEXT");
  EGLDisplay display = get_display(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
  REQUIRE(eglInitialize(display, nullptr, nullptr), "eglInitialize");
  eglBindAPI(EGL_OPENGL_API);
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
  EGLConfig config;
  REQUIRE(eglChooseConfig(display, config_attributes, &config, 1, &count) && count == 1, "eglChooseConfig");
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext gl_context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  REQUIRE(gl_context != EGL_NO_CONTEXT && eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, gl_context),
          "GL 4.5 context");
  auto glGetError_ = gl_proc<PFNGLGETERRORPROC>("glGetError");
  auto glGetString_ = gl_proc<PFNGLGETSTRINGPROC>("glGetString");
  auto glCreateMemoryObjectsEXT_ = gl_proc<PFNGLCREATEMEMORYOBJECTSEXTPROC>("glCreateMemoryObjectsEXT");
  auto glImportMemoryFdEXT_ = gl_proc<PFNGLIMPORTMEMORYFDEXTPROC>("glImportMemoryFdEXT");
  auto glBufferStorageMemEXT_ = gl_proc<PFNGLBUFFERSTORAGEMEMEXTPROC>("glBufferStorageMemEXT");
  auto glGenBuffers_ = gl_proc<PFNGLGENBUFFERSPROC>("glGenBuffers");
  auto glBindBuffer_ = gl_proc<PFNGLBINDBUFFERPROC>("glBindBuffer");
  auto glGenTextures_ = gl_proc<PFNGLGENTEXTURESPROC>("glGenTextures");
  auto glBindTexture_ = gl_proc<PFNGLBINDTEXTUREPROC>("glBindTexture");
  auto glTexStorage2D_ = gl_proc<PFNGLTEXSTORAGE2DPROC>("glTexStorage2D");
  auto glGenFramebuffers_ = gl_proc<PFNGLGENFRAMEBUFFERSPROC>("glGenFramebuffers");
  auto glBindFramebuffer_ = gl_proc<PFNGLBINDFRAMEBUFFERPROC>("glBindFramebuffer");
  auto glFramebufferTexture2D_ = gl_proc<PFNGLFRAMEBUFFERTEXTURE2DPROC>("glFramebufferTexture2D");
  auto glClearColor_ = gl_proc<PFNGLCLEARCOLORPROC>("glClearColor");
  auto glClear_ = gl_proc<PFNGLCLEARPROC>("glClear");
  auto glReadPixels_ = gl_proc<PFNGLREADPIXELSPROC>("glReadPixels");
  auto glFinish_ = gl_proc<PFNGLFINISHPROC>("glFinish");
  std::printf("GL: %s / %s\n", glGetString_(GL_RENDERER), glGetString_(GL_VERSION));
  REQUIRE(glCreateMemoryObjectsEXT_ && glImportMemoryFdEXT_ && glBufferStorageMemEXT_, "GL_EXT_memory_object_fd");
  GLuint memory = 0, pack = 0, texture = 0, framebuffer = 0;
  glCreateMemoryObjectsEXT_(1, &memory);
  glImportMemoryFdEXT_(memory, bytes, GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd_gl);
  std::printf("glImportMemoryFdEXT: GL error 0x%x\n", glGetError_());
  glGenBuffers_(1, &pack);
  glBindBuffer_(GL_PIXEL_PACK_BUFFER, pack);
  glBufferStorageMemEXT_(GL_PIXEL_PACK_BUFFER, bytes, memory, 0);
  std::printf("glBufferStorageMemEXT: GL error 0x%x\n", glGetError_());
  glGenTextures_(1, &texture);
  glBindTexture_(GL_TEXTURE_2D, texture);
  glTexStorage2D_(GL_TEXTURE_2D, 1, GL_R32F, width, height);
  glGenFramebuffers_(1, &framebuffer);
  glBindFramebuffer_(GL_FRAMEBUFFER, framebuffer);
  glFramebufferTexture2D_(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
  glClearColor_(3.5f, 0, 0, 0);
  glClear_(GL_COLOR_BUFFER_BIT);
  glReadPixels_(0, 0, width, height, GL_RED, GL_FLOAT, nullptr);  // into the imported buffer
  glFinish_();
  std::printf("clear + glReadPixels into the imported buffer: GL error 0x%x\n", glGetError_());
  for (int repeat = 0; repeat < 3; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
    glReadPixels_(0, 0, width, height, GL_RED, GL_FLOAT, nullptr);
    glFinish_();
    std::printf("glReadPixels of %dx%d R32F into it: %.3f ms\n", width, height,
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }

  // OpenCL: the NVIDIA platform imports the same memory.
  cl_uint platforms = 0;
  clGetPlatformIDs(0, nullptr, &platforms);
  std::vector<cl_platform_id> ids(platforms);
  clGetPlatformIDs(platforms, ids.data(), nullptr);
  cl_platform_id nvidia = nullptr;
  for (auto p : ids) {
    char name[256] = {};
    clGetPlatformInfo(p, CL_PLATFORM_NAME, sizeof name, name, nullptr);
    if (std::strstr(name, "NVIDIA")) nvidia = p;
  }
  REQUIRE(nvidia, "NVIDIA OpenCL platform");
  cl_device_id cl_device;
  REQUIRE(clGetDeviceIDs(nvidia, CL_DEVICE_TYPE_GPU, 1, &cl_device, nullptr) == CL_SUCCESS, "clGetDeviceIDs");
  cl_int status = 0;
  cl_context cl = clCreateContext(nullptr, 1, &cl_device, nullptr, nullptr, &status);
  cl_command_queue queue = clCreateCommandQueueWithProperties(cl, cl_device, nullptr, &status);
  const cl_mem_properties properties[] = {CL_EXTERNAL_MEMORY_HANDLE_OPAQUE_FD_KHR, cl_mem_properties(fd_cl),
                                          CL_DEVICE_HANDLE_LIST_KHR, cl_mem_properties(cl_device),
                                          CL_DEVICE_HANDLE_LIST_END_KHR, 0};
  cl_mem buffer = clCreateBufferWithProperties(cl, properties, CL_MEM_READ_WRITE, bytes, nullptr, &status);
  std::printf("clCreateBufferWithProperties(opaque fd): %d\n", status);
  REQUIRE(status == CL_SUCCESS, "OpenCL import");
  auto acquire = reinterpret_cast<clEnqueueAcquireExternalMemObjectsKHR_fn>(
      clGetExtensionFunctionAddressForPlatform(nvidia, "clEnqueueAcquireExternalMemObjectsKHR"));
  auto release = reinterpret_cast<clEnqueueReleaseExternalMemObjectsKHR_fn>(
      clGetExtensionFunctionAddressForPlatform(nvidia, "clEnqueueReleaseExternalMemObjectsKHR"));
  if (acquire) std::printf("acquire: %d\n", acquire(queue, 1, &buffer, 0, nullptr, nullptr));
  std::vector<float> got(size_t(width) * height);
  status = clEnqueueReadBuffer(queue, buffer, CL_TRUE, 0, got.size() * 4, got.data(), 0, nullptr, nullptr);
  if (release) release(queue, 1, &buffer, 0, nullptr, nullptr);
  clFinish(queue);
  size_t right = 0;
  for (float v : got) right += v == 3.5f;
  std::printf("OpenCL read %d: %zu of %zu floats are GL's 3.5 (first %g)\n", status, right, got.size(), got[0]);
  std::printf(right == got.size() ? "BRIDGE WORKS\n" : "BRIDGE FAILS\n");
  return right == got.size() ? 0 : 1;
}
