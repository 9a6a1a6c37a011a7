#include "compute/opencl/cl_cached_build.hpp"

namespace depthtrack::compute::opencl {

namespace {
// The one device's binary, or nullopt when the driver offers none.
std::optional<std::string> program_binary(cl_program program) {
  size_t size = 0;
  if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof(size), &size, nullptr) != CL_SUCCESS || size == 0)
    return std::nullopt;
  std::string binary(size, '\0');
  unsigned char* destination = reinterpret_cast<unsigned char*>(binary.data());
  if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof(destination), &destination, nullptr) != CL_SUCCESS)
    return std::nullopt;
  return binary;
}

// The program made from a stored binary, or nullptr when the driver refuses it (another driver's
// binary, a corrupt one that passed the checksum): the caller then builds from source.
std::unique_ptr<ClProgram> from_binary(cl_context context, cl_device_id device, const DeviceInfo& info,
                                       const std::string& name, const std::string& binary, const std::string& options) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(binary.data());
  const size_t length = binary.size();
  cl_int binary_status = CL_SUCCESS, status = CL_SUCCESS;
  ProgramHandle program(clCreateProgramWithBinary(context, 1, &device, &length, &bytes, &binary_status, &status));
  if (status != CL_SUCCESS || binary_status != CL_SUCCESS) return nullptr;
  if (clBuildProgram(program.get(), 1, &device, options.c_str(), nullptr, nullptr) != CL_SUCCESS) return nullptr;
  return std::make_unique<ClProgram>(std::move(program), name, info.name, true);
}
}  // namespace

std::string binary_cache_key(const DeviceInfo& device, const std::string& options, const std::string& source) {
  return "platform: " + device.platform + "\nvendor: " + device.vendor + "\ndevice: " + device.name +
         "\ndriver: " + device.driver + "\nversion: " + device.version + "\noptions: " + options + "\nprelude:\n" +
         opencl_prelude() + "\nsource:\n" + source;
}

std::unique_ptr<ClProgram> build_cached(const std::optional<ProgramBinaryCache>& cache, cl_context context,
                                        cl_device_id device, const DeviceInfo& info, const std::string& name,
                                        const std::string& source, const std::vector<std::string>& definitions) {
  if (!cache) return build_program(context, device, info.name, name, source, definitions);
  const std::string options = build_options(definitions);
  const std::string key = binary_cache_key(info, options, source);
  if (const auto binary = cache->load(key))
    if (auto program = from_binary(context, device, info, name, *binary, options)) return program;
  auto program = build_program(context, device, info.name, name, source, definitions);
  if (const auto binary = program_binary(program->get())) cache->store(key, *binary);  // a failed store costs time only
  return program;
}

}  // namespace depthtrack::compute::opencl
