#pragma once
/// @file
/// A device trackers run on, opened once and shared: several Trackers on one Device use its one compute
/// queue and compile each kernel program once between them. The host filters are Devices too.
///
/// Trackers drawing their atlas with OpenGL (TrackerConfig::renderer gl) also share the Device's GL context,
/// made by the first of them (each tracker keeps its own framebuffers, textures and buffers in it). Where the
/// device is OpenCL, lists cl_khr_gl_sharing and GL is EGL or GLX, the Device then opens an OpenCL context
/// against that GL context, with programs of its own, and its GL trackers run there, so that the atlas reaches
/// OpenCL without a copy (the hand-off's description says which path a tracker got, and why).
///
/// Threads: update a Device's trackers from one thread at a time. A GL context is current on one thread at a
/// time, so the Device keeps one GL context per thread that makes GL trackers on it: the trackers made on one
/// thread (a MultiTracker's, made and driven on the calling thread) share it, and a GL tracker is updated on
/// the thread that made it, as before.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace depthtrack {

/// One compute device as `depthtrack info` lists it.
struct DeviceDescription {
  std::string selector;  ///< opens exactly this device: "opencl:0.1", "cuda:0"
  std::string backend;   ///< "opencl", "cuda"
  std::string name;      ///< the device's own name, e.g. a GPU's model or "cpu-haswell-<processor>"
  std::string platform;  ///< e.g. "Portable Computing Language", "NVIDIA CUDA"
  bool is_gpu = false;   ///< a GPU (else a CPU or another accelerator)
};

/// A device trackers run on (see the file's notes): a host filter ("reference", "cpu") or an open compute
/// device. Made only by open(); its compute queue, program cache and GL contexts are the library's own.
class Device {
 public:
  /// Every compute device of every backend built in (none where no runtime is installed). The host
  /// selectors "reference", "cpu" and "cpu:N" always open and are not listed.
  static std::vector<DeviceDescription> list();
  /// Opens the device `selector` names: what TrackerConfig::backend accepts, i.e. "reference" (sequential
  /// host filter), "cpu" / "cpu:N" (the reference on a thread pool of N threads), or a compute selector
  /// ("opencl", "opencl:pocl", "cuda:0", ...). InputError naming the selector and listing what is
  /// available otherwise; BackendError when the compute device is listed but does not open.
  static std::shared_ptr<Device> open(const std::string& selector);

  /// Closes the device once the last Tracker on it is gone (trackers hold it by shared_ptr).
  virtual ~Device();
  Device(const Device&) = delete;             ///< One Device per open(): not copied.
  Device& operator=(const Device&) = delete;  ///< One Device per open(): not copied.

  /// The selector it was opened with ("reference", "cpu:4", "opencl:0.1", "cuda:0", ...).
  const std::string& selector() const;
  /// True for reference and cpu: a host filter, no compute queue.
  bool is_host() const;
  /// The compute device's name, or "host" for reference and cpu.
  std::string name() const;
  /// Kernel programs compiled on this device so far (0 on the host): each (file, definitions) once per
  /// compute context (a context opened against GL for cl_khr_gl_sharing builds its own).
  size_t program_builds() const;
  /// GL contexts made for GL trackers so far: one per GL path asked for and thread (0 before the first).
  size_t gl_contexts() const;

 protected:
  /// Devices come from open() only, which makes the library's own kind.
  Device() = default;
};

}  // namespace depthtrack
