#include "compute/opencl/cl_device_query.hpp"

#include <CL/cl_ext.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <sstream>
#include <string>

#include "compute/opencl/cl_errors.hpp"

namespace depthtrack::compute::opencl {

namespace {
constexpr cl_int kPlatformNotFoundKhr = -1001;  // cl_ext.h; what ocl-icd returns with no ICD installed

std::string trimmed(std::string text) {
  // Drivers pad strings and include the terminating NUL in the size.
  while (!text.empty() && (text.back() == '\0' || text.back() == ' ' || text.back() == '\n')) text.pop_back();
  return text;
}

// A string property through an OpenCL info query (ask the size, then the text).
template <class Object, class Name>
std::string info_string(cl_int (*query)(Object, Name, size_t, void*, size_t*), Object object, Name what,
                        const char* call) {
  size_t size = 0;
  check(query(object, what, 0, nullptr, &size), call);
  std::string text(size, '\0');
  check(query(object, what, size, text.data(), nullptr), call);
  return trimmed(text);
}

std::string platform_string(cl_platform_id platform, cl_platform_info what) {
  return info_string(&clGetPlatformInfo, platform, what, "clGetPlatformInfo");
}

std::string device_string(cl_device_id device, cl_device_info what) {
  return info_string(&clGetDeviceInfo, device, what, "clGetDeviceInfo");
}

template <class T>
T device_value(cl_device_id device, cl_device_info what) {
  T value{};
  check(clGetDeviceInfo(device, what, sizeof(T), &value, nullptr), "clGetDeviceInfo");
  return value;
}

std::vector<std::string> split_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}
}  // namespace

std::vector<cl_platform_id> platform_ids() {
  cl_uint count = 0;
  const cl_int status = clGetPlatformIDs(0, nullptr, &count);
  if (status == kPlatformNotFoundKhr || count == 0) return {};
  check(status, "clGetPlatformIDs");
  std::vector<cl_platform_id> ids(count);
  check(clGetPlatformIDs(count, ids.data(), nullptr), "clGetPlatformIDs");
  return ids;
}

std::vector<cl_device_id> device_ids(cl_platform_id platform) {
  cl_uint count = 0;
  const cl_int status = clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count);
  if (status == CL_DEVICE_NOT_FOUND || count == 0) return {};
  check(status, "clGetDeviceIDs");
  std::vector<cl_device_id> ids(count);
  check(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr), "clGetDeviceIDs");
  return ids;
}

DeviceInfo query_device(cl_platform_id platform, cl_device_id device, unsigned platform_index, unsigned device_index) {
  DeviceInfo info;
  info.backend = "opencl";
  info.selector = "opencl:" + std::to_string(platform_index) + "." + std::to_string(device_index);
  info.platform = platform_string(platform, CL_PLATFORM_NAME);
  // The platform's vendor (the driver's maker), which "opencl:<word>" matches: a CPU device's own
  // vendor string is the CPU's ("AuthenticAMD" under PoCL), not the driver's.
  info.vendor = platform_string(platform, CL_PLATFORM_VENDOR);
  info.name = device_string(device, CL_DEVICE_NAME);
  info.driver = device_string(device, CL_DRIVER_VERSION);
  info.version = device_string(device, CL_DEVICE_VERSION);
  info.is_gpu = (device_value<cl_device_type>(device, CL_DEVICE_TYPE) & CL_DEVICE_TYPE_GPU) != 0;
  info.global_memory = device_value<cl_ulong>(device, CL_DEVICE_GLOBAL_MEM_SIZE);
  info.max_allocation = device_value<cl_ulong>(device, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
  info.local_memory = device_value<cl_ulong>(device, CL_DEVICE_LOCAL_MEM_SIZE);
  info.max_work_group_size = device_value<size_t>(device, CL_DEVICE_MAX_WORK_GROUP_SIZE);
  info.compute_units = static_cast<int>(device_value<cl_uint>(device, CL_DEVICE_MAX_COMPUTE_UNITS));
  info.extensions = split_words(device_string(device, CL_DEVICE_EXTENSIONS));
  const auto has = [&](const char* name) {
    return std::find(info.extensions.begin(), info.extensions.end(), name) != info.extensions.end();
  };
  info.gl_sharing = has("cl_khr_gl_sharing");
  info.external_memory = has("cl_khr_external_memory") || has("cl_khr_external_memory_opaque_fd");
  info.fp64 = has("cl_khr_fp64");
  info.int64_atomics = has("cl_khr_int64_extended_atomics");
  info.subgroups = has("cl_khr_subgroups") || has("cl_intel_subgroups");
  if (has("cl_khr_device_uuid")) {
    std::array<unsigned char, CL_UUID_SIZE_KHR> uuid{};
    if (clGetDeviceInfo(device, CL_DEVICE_UUID_KHR, uuid.size(), uuid.data(), nullptr) == CL_SUCCESS) info.uuid = uuid;
  }
  return info;
}

std::optional<std::pair<unsigned, unsigned>> device_indices(const DeviceInfo& device) {
  unsigned platform_index = 0, device_index = 0;
  if (device.backend != "opencl" ||
      std::sscanf(device.selector.c_str(), "opencl:%u.%u", &platform_index, &device_index) != 2)
    return std::nullopt;
  return std::pair{platform_index, device_index};
}

}  // namespace depthtrack::compute::opencl
