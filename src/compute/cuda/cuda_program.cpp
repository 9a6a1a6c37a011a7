#include "compute/cuda/cuda_program.hpp"

#include <algorithm>
#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_errors.hpp"
#include "compute/cuda/cuda_nvrtc_api.hpp"
#include "compute/cuda/cuda_source_text.hpp"
#include "compute/kernel_sources.hpp"

namespace depthtrack::compute::cuda {

const std::map<std::string, std::string>& prelude_files();  // dt_prelude_cuda.h, embedded by CMake

namespace {

// Owns an nvrtcProgram so that every exit path destroys it.
class NvrtcProgram {
 public:
  NvrtcProgram(const NvrtcApi& api, const std::string& source, const std::string& file) : api_(api) {
    check_nvrtc(api, api.nvrtcCreateProgram(&program_, source.c_str(), file.c_str(), 0, nullptr, nullptr),
                "nvrtcCreateProgram");
  }
  ~NvrtcProgram() { api_.nvrtcDestroyProgram(&program_); }
  NvrtcProgram(const NvrtcProgram&) = delete;
  NvrtcProgram& operator=(const NvrtcProgram&) = delete;
  nvrtcProgram get() const { return program_; }

 private:
  const NvrtcApi& api_;
  nvrtcProgram program_ = nullptr;
};

std::vector<int> supported_archs(const NvrtcApi& api) {
  int count = 0;
  check_nvrtc(api, api.nvrtcGetNumSupportedArchs(&count), "nvrtcGetNumSupportedArchs");
  std::vector<int> archs(static_cast<size_t>(std::max(count, 0)));
  if (count > 0) check_nvrtc(api, api.nvrtcGetSupportedArchs(archs.data()), "nvrtcGetSupportedArchs");
  return archs;
}

std::string program_log(const NvrtcApi& api, nvrtcProgram program) {
  size_t size = 0;
  if (api.nvrtcGetProgramLogSize(program, &size) != NVRTC_SUCCESS || size == 0) return {};
  std::string log(size, '\0');
  if (api.nvrtcGetProgramLog(program, log.data()) != NVRTC_SUCCESS) return {};
  log.resize(log.find('\0') == std::string::npos ? size : log.find('\0'));
  return log;
}

// The PTX text or cubin bytes, without PTX's terminating nul.
std::string program_output(const NvrtcApi& api, nvrtcProgram program, bool cubin) {
  size_t size = 0;
  std::string out;
  if (cubin) {
    check_nvrtc(api, api.nvrtcGetCUBINSize(program, &size), "nvrtcGetCUBINSize");
    out.resize(size);
    check_nvrtc(api, api.nvrtcGetCUBIN(program, out.data()), "nvrtcGetCUBIN");
  } else {
    check_nvrtc(api, api.nvrtcGetPTXSize(program, &size), "nvrtcGetPTXSize");
    out.resize(size);
    check_nvrtc(api, api.nvrtcGetPTX(program, out.data()), "nvrtcGetPTX");
    if (!out.empty() && out.back() == '\0') out.pop_back();
  }
  return out;
}

// OpenCL C's precision, which the kernels are written for and the equivalence tests hold OpenCL to:
// division and square root to a few ulp. NVRTC's default rounds both correctly, in a multi-instruction
// sequence per `/` that the refinement's one work-group and the likelihood pay for on every pixel.
// DEPTHTRACK_CUDA_EXTRA_OPTIONS (CMake, space-separated, empty by default) appends options for experiments
// such as measuring --use_fast_math or --ftz=true against this default on a GPU.
std::vector<std::string> fixed_options() {
  std::vector<std::string> options = {"--std=c++17", "--prec-div=false", "--prec-sqrt=false"};
#ifdef DEPTHTRACK_CUDA_EXTRA_OPTIONS
  std::string extra = DEPTHTRACK_CUDA_EXTRA_OPTIONS;
  for (size_t start = 0; start < extra.size();) {
    const size_t end = std::min(extra.find(' ', start), extra.size());
    if (end > start) options.push_back(extra.substr(start, end - start));
    start = end + 1;
  }
#endif
  return options;
}

const std::string& cuda_prelude() {
  static const std::string prelude = program_prelude(prelude_files(), "dt_prelude_cuda.h");
  return prelude;
}

CompiledImage compile(const std::string& name, const std::string& source, const std::vector<std::string>& definitions,
                      int compute_capability, bool want_cubin, const std::string& where) {
  const NvrtcApi& api = require_nvrtc();
  const std::string nvrtc = "NVRTC " + std::to_string(api.major) + "." + std::to_string(api.minor);
  const std::vector<int> archs = supported_archs(api);
  const int arch = choose_arch(compute_capability, archs);
  if (arch < 0)
    throw BackendError(nvrtc + " cannot compile for sm_" + std::to_string(compute_capability) + " on " + where +
                       ": its oldest architecture is sm_" + (archs.empty() ? "?" : std::to_string(archs.front())));
  CompiledImage result;
  result.is_cubin = want_cubin && arch == compute_capability && api.nvrtcGetCUBIN && api.nvrtcGetCUBINSize;
  result.target = (result.is_cubin ? "sm_" : "compute_") + std::to_string(arch);
  std::vector<std::string> options = fixed_options();
  options.push_back("--gpu-architecture=" + result.target);
  for (const std::string& definition : definitions) {
    if (definition.empty() || definition.front() == '=')
      throw InputError("program '" + name + "': definition '" + definition + "' is not NAME or NAME=VALUE");
    options.push_back("-D" + definition);
  }
  for (const std::string& option : options) result.options += (result.options.empty() ? "" : " ") + option;

  // OpenCL C's words in CUDA's terms first (dt_prelude_cuda.h); the log's line numbers are still the source's.
  NvrtcProgram program(api, cuda_prelude() + source, name + ".cu");
  std::vector<const char*> argv;
  for (const std::string& option : options) argv.push_back(option.c_str());
  const nvrtcResult status = api.nvrtcCompileProgram(program.get(), static_cast<int>(argv.size()), argv.data());
  if (status != NVRTC_SUCCESS) {
    const std::string log = program_log(api, program.get());
    throw BackendError("nvrtcCompileProgram failed: " + nvrtc_error_text(api, status) + " building program '" + name +
                       "' for " + result.target + " on " + where + " with " + nvrtc + "\noptions: " + result.options +
                       "\nlog:\n" + log + (log.empty() || log.back() == '\n' ? "" : "\n") +
                       numbered_excerpt(source, first_error_line(log)));
  }
  result.image = program_output(api, program.get(), result.is_cubin);
  return result;
}

}  // namespace

int choose_arch(int compute_capability, const std::vector<int>& supported) {
  int best = -1;
  for (const int arch : supported)
    if (arch <= compute_capability) best = std::max(best, arch);
  return best;
}

std::string compile_signature() {
  std::string signature = "options:";
  for (const std::string& option : fixed_options()) signature += " " + option;
  return signature + "\nprelude:\n" + cuda_prelude();
}

CompiledImage compile_for_device(const std::string& program, const std::string& source,
                                 const std::vector<std::string>& definitions, int compute_capability,
                                 const std::string& where) {
  return compile(program, source, definitions, compute_capability, true, where);
}

std::string compile_to_ptx(const std::string& source, const std::vector<std::string>& definitions,
                           int compute_capability) {
  return compile("ptx", source, definitions, compute_capability, false, "the host (PTX only, no device)").image;
}

std::string nvrtc_unavailable_reason() {
  return nvrtc_api() ? std::string() : nvrtc_failure();
}

}  // namespace depthtrack::compute::cuda
