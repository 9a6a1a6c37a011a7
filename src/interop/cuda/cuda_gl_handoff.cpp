// CUDA-GL interop: the pose buffer and each page's colour texture are registered with CUDA once;
// every frame the states are copied device-to-device into the mapped pose buffer, GL draws, and
// each mapped page is copied with one cuMemcpy2DAsync into the atlas buffer, all on the queue's
// stream. Mapping orders the CUDA work after the GL commands issued before it, and unmapping
// orders later GL commands after the CUDA work, so no host wait is needed anywhere.
#include <depthtrack/error.hpp>
#include <string>
#include <utility>

#include "compute/cuda/cuda_driver_api.hpp"
#include "compute/cuda/cuda_errors.hpp"
#include "compute/cuda/cuda_memory.hpp"
#include "interop/atlas_handoff.hpp"

namespace depthtrack::interop {

namespace {
using compute::cuda::DriverApi;

// The queue's CUDA objects, from its native handles (compute/native_handles.hpp), with the calls the
// hand-off makes on them.
struct CudaSide {
  const DriverApi& api;
  CUcontext context;
  CUstream stream;
  CUdevice device;
  std::string where;  // "NVIDIA H100 80GB HBM3 (cuda:0)", for messages

  void make_current() const { check(api.cuCtxSetCurrent(context), "cuCtxSetCurrent"); }
  bool try_make_current() const noexcept { return api.cuCtxSetCurrent(context) == CUDA_SUCCESS; }
  void check(CUresult status, const char* call) const { compute::cuda::check(status, call, where); }
};

// cudaGL.h's entry points, declared here with GL's types from our own GL header (see
// compute::cuda::driver_symbol); the names are those cudaGL.h maps to.
using RegisterBuffer = CUresult (*)(CUgraphicsResource*, GLuint, unsigned int);
using RegisterImage = CUresult (*)(CUgraphicsResource*, GLuint, GLenum, unsigned int);
using GetGlDevices = CUresult (*)(unsigned int*, CUdevice*, unsigned int, unsigned int);
constexpr unsigned int kAllGlDevices = 0x01;  // CU_GL_DEVICE_LIST_ALL

struct GlInteropApi {
  RegisterBuffer register_buffer = nullptr;
  RegisterImage register_image = nullptr;
  GetGlDevices gl_devices = nullptr;
};

// The entry points, or empty with the reason in why_not.
bool load_gl_interop(const DriverApi& api, GlInteropApi& gl, std::string& why_not) {
  gl.register_buffer = reinterpret_cast<RegisterBuffer>(compute::cuda::driver_symbol("cuGraphicsGLRegisterBuffer"));
  gl.register_image = reinterpret_cast<RegisterImage>(compute::cuda::driver_symbol("cuGraphicsGLRegisterImage"));
  gl.gl_devices = reinterpret_cast<GetGlDevices>(compute::cuda::driver_symbol("cuGLGetDevices_v2"));
  if (!gl.register_buffer || !gl.register_image || !gl.gl_devices || !api.cuGraphicsMapResources ||
      !api.cuGraphicsUnmapResources || !api.cuGraphicsUnregisterResource || !api.cuGraphicsSubResourceGetMappedArray ||
      !api.cuGraphicsResourceGetMappedPointer || !api.cuMemcpy2DAsync) {
    why_not = "the CUDA driver lacks the GL interop entry points";
    return false;
  }
  return true;
}

class CudaGlHandoff final : public AtlasHandoff {
 public:
  CudaGlHandoff(CudaSide cuda, render::AtlasRenderer& renderer, const GlInteropApi& gl)
      : cuda_(std::move(cuda)), renderer_(renderer), api_(cuda_.api) {
    const CudaSide& context = cuda_;
    context.make_current();
    renderer_.context().make_current();
    try {
      context.check(gl.register_buffer(&poses_, renderer_.pose_buffer(), CU_GRAPHICS_REGISTER_FLAGS_WRITE_DISCARD),
                    "cuGraphicsGLRegisterBuffer (pose buffer)");
      for (const render::AtlasPage& page : renderer_.pages()) {
        CUgraphicsResource resource = nullptr;
        context.check(
            gl.register_image(&resource, page.color_texture, GL_TEXTURE_2D, CU_GRAPHICS_REGISTER_FLAGS_READ_ONLY),
            "cuGraphicsGLRegisterImage (atlas page)");
        pages_.push_back(resource);
      }
    } catch (...) {
      release();
      throw;
    }
  }
  ~CudaGlHandoff() override { release(); }

  void send_poses(const compute::Buffer<float>& states) override {
    const CudaSide& context = cuda_;
    const auto& source =
        compute::cuda::cuda_memory(states.memory(), context.device, context.where, "CUDA-GL pose hand-off");
    context.make_current();
    renderer_.context().make_current();
    CUstream stream = context.stream;
    context.check(api_.cuGraphicsMapResources(1, &poses_, stream), "cuGraphicsMapResources (pose buffer)");
    CUdeviceptr target = 0;
    size_t bytes = 0;
    const CUresult mapped = api_.cuGraphicsResourceGetMappedPointer(&target, &bytes, poses_);
    const CUresult copied = mapped == CUDA_SUCCESS && bytes >= source.bytes()
                                ? api_.cuMemcpyDtoDAsync(target, source.pointer(), source.bytes(), stream)
                                : CUDA_SUCCESS;
    context.check(api_.cuGraphicsUnmapResources(1, &poses_, stream), "cuGraphicsUnmapResources (pose buffer)");
    context.check(mapped, "cuGraphicsResourceGetMappedPointer (pose buffer)");
    if (bytes < source.bytes())
      throw BackendError("CUDA-GL pose hand-off: the GL pose buffer holds " + std::to_string(bytes) +
                         " bytes, the states " + std::to_string(source.bytes()));
    context.check(copied, "cuMemcpyDtoDAsync (states to the GL pose buffer)");
  }

  void receive_atlas(compute::Buffer<float>& atlas) override {
    const CudaSide& context = cuda_;
    const auto& target =
        compute::cuda::cuda_memory(atlas.memory(), context.device, context.where, "CUDA-GL atlas hand-off");
    const render::AtlasLayout& layout = renderer_.layout();
    if (atlas.size() < layout.floats())
      throw InputError("CUDA-GL atlas hand-off: the atlas buffer holds " + std::to_string(atlas.size()) +
                       " floats, the pages " + std::to_string(layout.floats()));
    context.make_current();
    renderer_.context().make_current();
    CUstream stream = context.stream;
    const unsigned count = static_cast<unsigned>(pages_.size());
    context.check(api_.cuGraphicsMapResources(count, pages_.data(), stream), "cuGraphicsMapResources (atlas pages)");
    CUresult status = CUDA_SUCCESS;
    const char* failed = nullptr;
    for (size_t p = 0; p < pages_.size() && status == CUDA_SUCCESS; ++p) {
      CUarray array = nullptr;
      status = api_.cuGraphicsSubResourceGetMappedArray(&array, pages_[p], 0, 0);
      failed = "cuGraphicsSubResourceGetMappedArray (atlas page)";
      if (status != CUDA_SUCCESS) break;
      const render::AtlasPageLayout& page = renderer_.pages()[p].layout;
      CUDA_MEMCPY2D copy{};
      copy.srcMemoryType = CU_MEMORYTYPE_ARRAY;
      copy.srcArray = array;
      copy.dstMemoryType = CU_MEMORYTYPE_DEVICE;
      copy.dstDevice = target.pointer() + layout.page_offset(p) * sizeof(float);
      copy.dstPitch = static_cast<size_t>(page.width) * sizeof(float);
      copy.WidthInBytes = copy.dstPitch;
      copy.Height = static_cast<size_t>(page.height);
      status = api_.cuMemcpy2DAsync(&copy, stream);
      failed = "cuMemcpy2DAsync (atlas page to the atlas buffer)";
    }
    context.check(api_.cuGraphicsUnmapResources(count, pages_.data(), stream),
                  "cuGraphicsUnmapResources (atlas pages)");
    if (status != CUDA_SUCCESS) context.check(status, failed);
  }

  std::string name() const override { return "CUDA-GL interop (zero-copy)"; }

 private:
  void release() noexcept {
    if (!cuda_.try_make_current()) return;
    for (CUgraphicsResource r : pages_) api_.cuGraphicsUnregisterResource(r);
    if (poses_) api_.cuGraphicsUnregisterResource(poses_);
    pages_.clear();
    poses_ = nullptr;
  }

  CudaSide cuda_;
  render::AtlasRenderer& renderer_;
  const DriverApi& api_;
  CUgraphicsResource poses_ = nullptr;
  std::vector<CUgraphicsResource> pages_;
};
}  // namespace

std::unique_ptr<AtlasHandoff> make_cuda_gl_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                   std::string& why_not) {
  const compute::NativeHandles native = queue.native_handles();
  if (!native.cu_context) {
    why_not = "not a CUDA device";
    return nullptr;
  }
  const DriverApi& api = compute::cuda::require_driver();  // loaded: the queue runs on it
  CudaSide cuda{api, static_cast<CUcontext>(native.cu_context), static_cast<CUstream>(native.cu_stream),
                static_cast<CUdevice>(native.cu_device), queue.info().name + " (" + queue.info().selector + ")"};
  GlInteropApi gl;
  if (!load_gl_interop(api, gl, why_not)) return nullptr;
  cuda.make_current();
  renderer.context().make_current();
  // The GL context must run on the queue's GPU (llvmpipe, or another GPU's EGL device, does not).
  unsigned int count = 0;
  CUdevice devices[16] = {};
  const CUresult status = gl.gl_devices(&count, devices, 16, kAllGlDevices);
  if (status != CUDA_SUCCESS) {
    why_not =
        "cuGLGetDevices: the GL context is not on an NVIDIA GPU (" + compute::cuda::cuda_error_text(api, status) + ")";
    return nullptr;
  }
  bool same = false;
  for (unsigned i = 0; i < count && i < 16; ++i) same = same || devices[i] == cuda.device;
  if (!same) {
    why_not = "the GL context runs on another GPU than " + cuda.where;
    return nullptr;
  }
  return std::make_unique<CudaGlHandoff>(std::move(cuda), renderer, gl);
}

}  // namespace depthtrack::interop
