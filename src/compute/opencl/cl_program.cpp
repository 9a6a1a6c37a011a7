#include "compute/opencl/cl_program.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <regex>
#include <sstream>

#include "compute/kernel_sources.hpp"
#include "compute/opencl/cl_errors.hpp"
#include "compute/opencl/cl_kernel.hpp"
#include "compute/source_excerpt.hpp"

namespace depthtrack::compute::opencl {

const std::map<std::string, std::string>& prelude_files();  // dt_prelude_opencl.h, embedded by CMake

const std::string& opencl_prelude() {
  static const std::string prelude = program_prelude(prelude_files(), "dt_prelude_opencl.h");
  return prelude;
}

std::string build_options(const std::vector<std::string>& definitions) {
  std::string options = "-cl-std=CL1.2";
  for (const auto& definition : definitions) {
    // The driver splits options at blanks, so a blank inside a definition would silently change its meaning.
    const bool blank = std::any_of(definition.begin(), definition.end(),
                                   [](unsigned char c) { return std::isspace(c) != 0 || c == '"' || c == '\''; });
    if (definition.empty() || blank || definition.front() == '=')
      throw InputError("kernel definition '" + definition + "' is not of the form NAME or NAME=VALUE without blanks");
    options += " -D " + definition;
  }
  return options;
}

namespace {

std::string build_log(cl_program program, cl_device_id device) {
  size_t size = 0;
  if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) != CL_SUCCESS)
    return "(no build log)";
  std::string log(size, '\0');
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log.empty() ? "(empty build log)" : log;
}

// The first line the log blames with an error (clang's "<file>:LINE:COLUMN:", as PoCL, NVIDIA and
// AMD print it); 0 when there is none. The kernel itself usually starts after a long prelude.
int first_error_line(const std::string& log) {
  std::istringstream log_lines(log);
  const std::regex position(R"(:(\d{1,9}):\d+:)");
  for (std::string line; std::getline(log_lines, line);) {
    std::smatch match;
    if (line.find("error") != std::string::npos && std::regex_search(line, match, position))
      return std::stoi(match[1].str());
  }
  return 0;
}

std::string kernel_names(cl_program program) {
  size_t size = 0;
  if (clGetProgramInfo(program, CL_PROGRAM_KERNEL_NAMES, 0, nullptr, &size) != CL_SUCCESS) return "(unknown)";
  std::string names(size, '\0');
  clGetProgramInfo(program, CL_PROGRAM_KERNEL_NAMES, size, names.data(), nullptr);
  while (!names.empty() && names.back() == '\0') names.pop_back();
  std::string list;
  std::istringstream in(names);
  for (std::string name; std::getline(in, name, ';');)  // the API separates them with ';'
    if (!name.empty()) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "(none)" : list;
}
}  // namespace

std::unique_ptr<Kernel> ClProgram::kernel(const std::string& name) {
  cl_int status = CL_SUCCESS;
  KernelHandle kernel(clCreateKernel(program_.get(), name.c_str(), &status));
  if (status != CL_SUCCESS)
    check(status, "clCreateKernel", device_,
          "program '" + name_ + "' has no kernel '" + name + "'; its kernels: " + kernel_names(program_.get()));
  return std::make_unique<ClKernel>(std::move(kernel), name, device_);
}

std::unique_ptr<ClProgram> build_program(cl_context context, cl_device_id device, const std::string& device_name,
                                         const std::string& name, const std::string& source,
                                         const std::vector<std::string>& definitions) {
  const std::string options = build_options(definitions);
  // OpenCL C's words first (dt_prelude_opencl.h); the build log's line numbers are still the source's.
  const std::string& prelude = opencl_prelude();
  const char* texts[] = {prelude.c_str(), source.c_str()};
  const size_t lengths[] = {prelude.size(), source.size()};
  cl_int status = CL_SUCCESS;
  ProgramHandle program(clCreateProgramWithSource(context, 2, texts, lengths, &status));
  check(status, "clCreateProgramWithSource", device_name, "program '" + name + "'");
  status = clBuildProgram(program.get(), 1, &device, options.c_str(), nullptr, nullptr);
  if (status != CL_SUCCESS) {
    const std::string log = build_log(program.get(), device);
    throw BackendError(failure_message(status, "clBuildProgram", device_name, "program '" + name + "'") +
                       "\noptions: " + options + "\nbuild log:\n" + log + "\n" +
                       numbered_excerpt(source, first_error_line(log)));
  }
  return std::make_unique<ClProgram>(std::move(program), name, device_name);
}

}  // namespace depthtrack::compute::opencl
