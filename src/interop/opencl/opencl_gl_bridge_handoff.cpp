// OpenCL without cl_khr_gl_sharing (NVIDIA) takes the atlas without a host round trip through
// memory that CUDA allocates and exports (ExportableMemory): GL imports it as a pixel-pack buffer
// and reads each page into it on the GPU; OpenCL imports it too and copies it into the atlas buffer.
// Proven on the H100 by scripts/probes/opencl_gl_bridge.cpp before it was built here.
#include <unistd.h>

#include <algorithm>
#include <depthtrack/error.hpp>

#include "compute/opencl/cl_external_memory.hpp"
#include "interop/atlas_handoff.hpp"
#include "interop/cuda/exportable_memory.hpp"

namespace depthtrack::interop {

namespace {

// GL_EXT_memory_object(_fd), declared here: glcorearb.h does not carry them.
constexpr GLenum kOpaqueFd = 0x9586;  // GL_HANDLE_TYPE_OPAQUE_FD_EXT
struct GlMemoryApi {
  void (*create_memory_objects)(GLsizei, GLuint*) = nullptr;
  void (*delete_memory_objects)(GLsizei, const GLuint*) = nullptr;
  void (*import_memory_fd)(GLuint, GLuint64, GLenum, GLint) = nullptr;
  void (*buffer_storage_mem)(GLenum, GLsizeiptr, GLuint, GLuint64) = nullptr;
};

class OpenclGlBridgeHandoff final : public AtlasHandoff {
 public:
  OpenclGlBridgeHandoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                        std::unique_ptr<ExportableMemory> memory, const GlMemoryApi& api)
      : queue_(queue), renderer_(renderer), memory_(std::move(memory)), api_(api) {
    render::GlContext& context = renderer_.context();
    context.make_current();
    const render::GlFunctions& gl = context.gl();
    api_.create_memory_objects(1, &gl_memory_);
    const int gl_fd = memory_->export_fd();  // GL owns it once imported
    api_.import_memory_fd(gl_memory_, memory_->bytes(), kOpaqueFd, gl_fd);
    if (const GLenum e = gl.GetError(); e != GL_NO_ERROR) {
      close(gl_fd);
      release_gl();
      throw BackendError(std::string("glImportMemoryFdEXT of the exported atlas memory: ") + render::gl_error_name(e));
    }
    gl.GenBuffers(1, &pack_buffer_);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer_);
    api_.buffer_storage_mem(GL_PIXEL_PACK_BUFFER, static_cast<GLsizeiptr>(memory_->bytes()), gl_memory_, 0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (const GLenum e = gl.GetError(); e != GL_NO_ERROR) {
      release_gl();
      throw BackendError(std::string("glBufferStorageMemEXT on the exported atlas memory: ") +
                         render::gl_error_name(e));
    }
    const int cl_fd = memory_->export_fd();
    try {
      shared_ = compute::opencl::import_opaque_fd(queue_, cl_fd, memory_->bytes());
    } catch (...) {
      close(cl_fd);
      release_gl();
      throw;
    }
    close(cl_fd);  // OpenCL imported a duplicate
  }
  ~OpenclGlBridgeHandoff() override {
    try {
      renderer_.context().make_current();
      release_gl();
    } catch (...) {  // the context is gone, and its objects with it
    }
  }

  void send_poses(const compute::Buffer<float>& states) override { send_poses_through_host(states, renderer_, host_); }

  void receive_atlas(compute::Buffer<float>& atlas) override {
    const render::AtlasLayout& layout = renderer_.layout();
    queue_.finish();  // OpenCL is done with the last frame's copy before GL overwrites it
    for (size_t p = 0; p < renderer_.pages().size(); ++p)
      renderer_.read_page_into(renderer_.pages()[p], pack_buffer_, layout.page_offset(p) * sizeof(float));
    renderer_.finish();  // GL's writes land before OpenCL reads
    compute::opencl::acquire_external(queue_, *shared_);
    queue_.copy(*shared_, 0, atlas.memory(), 0, layout.floats() * sizeof(float));
    compute::opencl::release_external(queue_, *shared_);
  }

  std::string name() const override { return "GL-OpenCL bridge through CUDA-exported memory (no host copy)"; }

 private:
  void release_gl() {
    const render::GlFunctions& gl = renderer_.context().gl();
    if (pack_buffer_) gl.DeleteBuffers(1, &pack_buffer_);
    if (gl_memory_) api_.delete_memory_objects(1, &gl_memory_);
    pack_buffer_ = gl_memory_ = 0;
  }

  compute::Queue& queue_;
  render::AtlasRenderer& renderer_;
  std::unique_ptr<ExportableMemory> memory_;
  GlMemoryApi api_;
  GLuint gl_memory_ = 0, pack_buffer_ = 0;
  std::unique_ptr<compute::DeviceMemory> shared_;
  std::vector<float> host_;
};

template <class F>
F gl_entry(render::GlContext& context, const char* name) {
  return reinterpret_cast<F>(context.proc_address(name));
}
}  // namespace

std::unique_ptr<AtlasHandoff> make_opencl_gl_bridge_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                            std::string& why_not) {
  const auto& extensions = queue.info().extensions;
  if (!queue.native_handles().cl_context ||
      std::find(extensions.begin(), extensions.end(), "cl_khr_external_memory_opaque_fd") == extensions.end()) {
    why_not = "the OpenCL device lacks cl_khr_external_memory_opaque_fd";
    return nullptr;
  }
  render::GlContext& context = renderer.context();
  context.make_current();
  if (!context.has_extension("GL_EXT_memory_object_fd")) {
    why_not = "GL lacks GL_EXT_memory_object_fd";
    return nullptr;
  }
  GlMemoryApi api;
  api.create_memory_objects = gl_entry<decltype(api.create_memory_objects)>(context, "glCreateMemoryObjectsEXT");
  api.delete_memory_objects = gl_entry<decltype(api.delete_memory_objects)>(context, "glDeleteMemoryObjectsEXT");
  api.import_memory_fd = gl_entry<decltype(api.import_memory_fd)>(context, "glImportMemoryFdEXT");
  api.buffer_storage_mem = gl_entry<decltype(api.buffer_storage_mem)>(context, "glBufferStorageMemEXT");
  if (!api.create_memory_objects || !api.delete_memory_objects || !api.import_memory_fd || !api.buffer_storage_mem) {
    why_not = "GL lists GL_EXT_memory_object_fd but lacks its entry points";
    return nullptr;
  }
  auto memory = ExportableMemory::make(queue.info().uuid, renderer.layout().floats() * sizeof(float), why_not);
  if (!memory) return nullptr;
  try {
    return std::make_unique<OpenclGlBridgeHandoff>(queue, renderer, std::move(memory), api);
  } catch (const BackendError& e) {
    why_not = e.what();
    return nullptr;
  }
}

}  // namespace depthtrack::interop
