// cl_khr_gl_sharing (AMD, Intel, Mesa GPU drivers): the atlas pages and the pose buffer are GL
// objects OpenCL uses in place (clCreateFromGLTexture, clCreateFromGLBuffer), between
// clEnqueueAcquireGLObjects and clEnqueueReleaseGLObjects. Without cl_khr_gl_event the spec asks
// for glFinish before the acquire and for OpenCL to finish before GL uses the objects again.
// It needs the queue's context created against the GL context (open_gl_shared_queue); untested
// here: no platform on the project's machines lists the extension.
#include <CL/cl_gl.h>

#include <depthtrack/error.hpp>
#include <vector>

#include "compute/opencl/cl_errors.hpp"
#include "compute/opencl/cl_memory.hpp"
#include "compute/native_handles.hpp"
#include "compute/queue.hpp"
#include "interop/atlas_handoff.hpp"
#include "interop/gl_sharing/gl_sharing_choice.hpp"

namespace depthtrack::interop {

namespace {
using compute::opencl::check;
using compute::opencl::MemHandle;

// The context's CL_CONTEXT_PROPERTIES, 0-terminated.
std::vector<cl_context_properties> context_properties(cl_context context) {
  size_t bytes = 0;
  check(clGetContextInfo(context, CL_CONTEXT_PROPERTIES, 0, nullptr, &bytes), "clGetContextInfo");
  std::vector<cl_context_properties> properties(bytes / sizeof(cl_context_properties) + 1, 0);
  if (bytes)
    check(clGetContextInfo(context, CL_CONTEXT_PROPERTIES, bytes, properties.data(), nullptr), "clGetContextInfo");
  return properties;
}

class ClGlSharingHandoff final : public AtlasHandoff {
 public:
  ClGlSharingHandoff(compute::Queue& queue, render::AtlasRenderer& renderer)
      : queue_(queue),
        context_(static_cast<cl_context>(queue.native_handles().cl_context)),
        cl_queue_(static_cast<cl_command_queue>(queue.native_handles().cl_queue)),
        renderer_(renderer) {
    renderer_.context().make_current();
    const std::string& device = queue_.info().name;
    cl_int status = CL_SUCCESS;
    for (const render::AtlasPage& page : renderer_.pages()) {
      pages_.emplace_back(
          clCreateFromGLTexture(context_, CL_MEM_READ_ONLY, GL_TEXTURE_2D, 0, page.color_texture, &status));
      check(status, "clCreateFromGLTexture (atlas page, GL_R32F)", device);
      page_handles_.push_back(pages_.back().get());
    }
    poses_ = MemHandle(clCreateFromGLBuffer(context_, CL_MEM_WRITE_ONLY, renderer_.pose_buffer(), &status));
    check(status, "clCreateFromGLBuffer (pose buffer)", device);
    check(clGetMemObjectInfo(poses_.get(), CL_MEM_SIZE, sizeof pose_bytes_, &pose_bytes_, nullptr),
          "clGetMemObjectInfo (pose buffer)", device);
  }

  void send_poses(const compute::Buffer<float>& states) override {
    const size_t bytes = states.size() * sizeof(float);
    if (bytes > pose_bytes_)
      throw BackendError("cl_khr_gl_sharing pose hand-off: the GL pose buffer holds " + std::to_string(pose_bytes_) +
                         " bytes, the states " + std::to_string(bytes));
    renderer_.finish();  // GL is done with the last draw's poses before OpenCL acquires them
    const cl_mem poses = poses_.get();
    const std::string& device = queue_.info().name;
    check(clEnqueueAcquireGLObjects(cl_queue_, 1, &poses, 0, nullptr, nullptr), "clEnqueueAcquireGLObjects",
          device);
    check(clEnqueueCopyBuffer(cl_queue_, compute::opencl::cl_buffer(states.memory(), "cl_khr_gl_sharing poses"),
                              poses, 0, 0, bytes, 0, nullptr, nullptr),
          "clEnqueueCopyBuffer (states to the GL pose buffer)", device);
    check(clEnqueueReleaseGLObjects(cl_queue_, 1, &poses, 0, nullptr, nullptr), "clEnqueueReleaseGLObjects",
          device);
    queue_.finish();  // OpenCL's writes land, and every earlier use of the pages ended, before GL draws
  }

  void receive_atlas(compute::Buffer<float>& atlas) override {
    const render::AtlasLayout& layout = renderer_.layout();
    if (atlas.size() < layout.floats())
      throw InputError("cl_khr_gl_sharing atlas hand-off: the atlas buffer holds " + std::to_string(atlas.size()) +
                       " floats, the pages " + std::to_string(layout.floats()));
    renderer_.finish();  // GL's draw is done before the acquire (no cl_khr_gl_event)
    const std::string& device = queue_.info().name;
    const cl_uint count = static_cast<cl_uint>(page_handles_.size());
    check(clEnqueueAcquireGLObjects(cl_queue_, count, page_handles_.data(), 0, nullptr, nullptr),
          "clEnqueueAcquireGLObjects (atlas pages)", device);
    const cl_mem target = compute::opencl::cl_buffer(atlas.memory(), "cl_khr_gl_sharing atlas");
    for (size_t p = 0; p < page_handles_.size(); ++p) {
      const render::AtlasPage& page = renderer_.pages()[p];
      const size_t origin[3] = {0, 0, 0};
      const size_t region[3] = {static_cast<size_t>(page.layout.width), static_cast<size_t>(page.layout.height), 1};
      check(clEnqueueCopyImageToBuffer(cl_queue_, page_handles_[p], target, origin, region,
                                       layout.page_offset(p) * sizeof(float), 0, nullptr, nullptr),
            "clEnqueueCopyImageToBuffer (atlas page)", device);
    }
    // Released without a wait: GL next writes the pages after send_poses' finish.
    check(clEnqueueReleaseGLObjects(cl_queue_, count, page_handles_.data(), 0, nullptr, nullptr),
          "clEnqueueReleaseGLObjects (atlas pages)", device);
  }

  std::string name() const override { return "cl_khr_gl_sharing (GL textures used in place, no host copy)"; }

 private:
  compute::Queue& queue_;
  cl_context context_;         // the queue's, made against the GL context (open_gl_shared_queue)
  cl_command_queue cl_queue_;  // the queue's own
  render::AtlasRenderer& renderer_;
  std::vector<MemHandle> pages_;
  std::vector<cl_mem> page_handles_;
  MemHandle poses_;
  size_t pose_bytes_ = 0;
};
}  // namespace

std::unique_ptr<AtlasHandoff> make_cl_gl_sharing_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                         std::string& why_not) {
  const compute::NativeHandles native = queue.native_handles();
  if (!native.cl_context || !native.cl_queue) {
    why_not = "the queue is not an OpenCL queue";
    return nullptr;
  }
  const GlSharingChoice choice = choose_gl_sharing(queue.info().extensions, renderer.context().native(),
                                                   context_properties(static_cast<cl_context>(native.cl_context)));
  if (!choice.share) {
    why_not = choice.reason;
    return nullptr;
  }
  try {
    return std::make_unique<ClGlSharingHandoff>(queue, renderer);
  } catch (const BackendError& e) {
    why_not = e.what();
    return nullptr;
  }
}

}  // namespace depthtrack::interop
