#pragma once
// A device trackers run on, opened once and shared: several Trackers on one Device use its one compute
// queue and compile each kernel program once between them. The host filters are Devices too.
//
// Trackers drawing their atlas with OpenGL (TrackerConfig::renderer gl) also share the Device's GL context,
// made by the first of them (each tracker keeps its own framebuffers, textures and buffers in it). Where the
// device is OpenCL, lists cl_khr_gl_sharing and GL is EGL or GLX, the Device then opens an OpenCL context
// against that GL context, with programs of its own, and its GL trackers run there, so that the atlas reaches
// OpenCL without a copy (the hand-off's description says which path a tracker got, and why).
//
// Threads: update a Device's trackers from one thread at a time. A GL context is current on one thread at a
// time, so the Device keeps one GL context per thread that makes GL trackers on it: the trackers made on one
// thread (a MultiTracker's, made and driven on the calling thread) share it, and a GL tracker is updated on
// the thread that made it, as before.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace depthtrack {

namespace compute {
struct DeviceContext;  // the library's compute queue and program cache (src/compute/program_cache.hpp)
}
struct GlAtlasDevice;  // a GL tracker's GL context and compute context (src/atlas/gl_atlas_device.hpp)

// One compute device as `depthtrack info` lists it.
struct DeviceDescription {
  std::string selector;  // opens exactly this device: "opencl:0.1", "cuda:0"
  std::string backend;   // "opencl", "cuda"
  std::string name;      // the device's own name, e.g. a GPU's model or "cpu-haswell-<processor>"
  std::string platform;  // e.g. "Portable Computing Language", "NVIDIA CUDA"
  bool is_gpu = false;
};

class Device {
 public:
  // Every compute device of every backend built in (none where no runtime is installed). The host
  // selectors "reference", "cpu" and "cpu:N" always open and are not listed.
  static std::vector<DeviceDescription> list();
  // What TrackerConfig::backend accepts: "reference" (sequential host filter), "cpu" / "cpu:N" (the
  // reference on a thread pool), or a compute selector ("opencl", "opencl:pocl", "cuda:0", ...).
  // InputError naming the selector and listing what is available otherwise.
  static std::shared_ptr<Device> open(const std::string& selector);

  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const std::string& selector() const { return selector_; }
  bool is_host() const { return !context_; }  // reference or cpu: no compute queue
  // The compute device's name, or "host" for reference and cpu.
  std::string name() const;
  // Kernel programs compiled on this device so far (0 on the host): each (file, definitions) once per
  // compute context (a context opened against GL for cl_khr_gl_sharing builds its own).
  size_t program_builds() const;
  // GL contexts made for GL trackers so far: one per GL path asked for and thread (0 before the first).
  size_t gl_contexts() const;

  // The library's side of it; nullptr for a host Device.
  const std::shared_ptr<compute::DeviceContext>& context() const { return context_; }
  // The library's side for a GL tracker on this compute Device: the GL context for `gl_path`
  // (TrackerConfig::gl_path) on the calling thread, made on the first call, and the compute context to run
  // on. BackendError when no GL context can be made (nothing is kept: a later call tries again).
  GlAtlasDevice gl_atlas(const std::string& gl_path) const;

 private:
  Device(std::string selector, std::shared_ptr<compute::DeviceContext> context);
  struct GlAtlases;  // the GL sides made so far, by GL path and thread
  std::string selector_;
  std::shared_ptr<compute::DeviceContext> context_;
  std::unique_ptr<GlAtlases> gl_;  // last: its GL contexts go before the Device's own compute context
};

}  // namespace depthtrack
