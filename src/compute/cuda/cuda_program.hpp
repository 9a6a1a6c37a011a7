#pragma once
// Compiling cl/ kernel text as CUDA C++ with NVRTC. Needs no GPU and no driver, only NVRTC, so
// these functions are usable (and tested) on machines without an NVIDIA GPU. The text is compiled
// after dt_prelude_cuda.h (this folder), which maps the OpenCL C words; __OPENCL_VERSION__ stays
// undefined.
#include <string>
#include <vector>

namespace depthtrack::compute::cuda {

// What NVRTC made of one program, ready for cuModuleLoadDataEx.
struct CompiledImage {
  std::string image;  // cubin bytes, or PTX text
  bool is_cubin = false;
  std::string target;   // "sm_90" (cubin) or "compute_90" (PTX the driver compiles)
  std::string options;  // the NVRTC options, for messages
};

// What a compiled image depends on besides the source, the definitions, the device and NVRTC's
// version: the fixed options and the CUDA prelude (the program binary cache keys on it).
std::string compile_signature();

// Compiles for a device of compute capability `compute_capability` (major * 10 + minor, e.g. 90):
// a cubin for exactly that architecture when NVRTC knows it, else PTX for the newest architecture
// NVRTC knows below it (an NVRTC older than the GPU), which the driver finishes. `definitions` are
// "NAME=VALUE" or "NAME"; `where` names the device in messages. A failed compile throws
// BackendError with "nvrtcCompileProgram failed", the symbolic error, `where`, the options, the
// full log and the numbered source lines around the first error.
CompiledImage compile_for_device(const std::string& program, const std::string& source,
                                 const std::vector<std::string>& definitions, int compute_capability,
                                 const std::string& where);

// PTX for compute_<compute_capability> (or the newest older architecture NVRTC knows), as above.
std::string compile_to_ptx(const std::string& source, const std::vector<std::string>& definitions,
                           int compute_capability);

// The architecture to compile for: compute_capability itself when `supported` lists it, else the
// newest listed one below it; -1 when every listed architecture is newer than the device.
int choose_arch(int compute_capability, const std::vector<int>& supported);

// The names of the __kernel functions in source, found in the text (for "no such kernel" messages).
std::vector<std::string> kernel_names(const std::string& source);

// Empty when NVRTC loads; otherwise why it does not.
std::string nvrtc_unavailable_reason();

}  // namespace depthtrack::compute::cuda
