#include "compute/cuda/cuda_cached_build.hpp"

#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_nvrtc_api.hpp"
#include "compute/cuda/cuda_program.hpp"

namespace depthtrack::compute::cuda {

namespace {
// "cubin" or "ptx", the target and the options (each after its length), then the image.
std::string serialize(const CompiledImage& image) {
  std::string out = image.is_cubin ? "cubin\n" : "ptx\n";
  for (const std::string* field : {&image.target, &image.options}) out += std::to_string(field->size()) + "\n" + *field;
  return out + image.image;
}

// Reads a "<length>\n<bytes>" field at offset, advancing it; false when the text does not hold one.
bool read_field(const std::string& in, size_t& offset, std::string& field) {
  const size_t newline = in.find('\n', offset);
  if (newline == std::string::npos || newline == offset || newline - offset > 9) return false;
  size_t length = 0;
  for (size_t i = offset; i < newline; ++i) {
    if (in[i] < '0' || in[i] > '9') return false;
    length = length * 10 + static_cast<size_t>(in[i] - '0');
  }
  if (length > in.size() - newline - 1) return false;
  field = in.substr(newline + 1, length);
  offset = newline + 1 + length;
  return true;
}

std::optional<CompiledImage> deserialize(const std::string& in) {
  CompiledImage image;
  size_t offset = 0;
  if (in.rfind("cubin\n", 0) == 0) {
    image.is_cubin = true;
    offset = 6;
  } else if (in.rfind("ptx\n", 0) == 0) {
    offset = 4;
  } else {
    return std::nullopt;
  }
  if (!read_field(in, offset, image.target) || !read_field(in, offset, image.options) || offset == in.size())
    return std::nullopt;
  image.image = in.substr(offset);
  return image;
}
}  // namespace

std::string binary_cache_key(const DeviceInfo& device, const std::vector<std::string>& definitions,
                             const std::string& source) {
  const NvrtcApi* nvrtc = nvrtc_api();
  std::string key =
      "backend: cuda\ndevice: " + device.name + "\ndriver: " + device.driver + "\nversion: " + device.version +
      "\nnvrtc: " + (nvrtc ? std::to_string(nvrtc->major) + "." + std::to_string(nvrtc->minor) : "absent") +
      "\ndefinitions:\n";
  for (const std::string& definition : definitions) key += std::to_string(definition.size()) + ":" + definition + "\n";
  return key + compile_signature() + "\nsource:\n" + source;
}

std::unique_ptr<CudaProgram> build_cached(const std::optional<ProgramBinaryCache>& cache,
                                          const std::shared_ptr<const Context>& context, const std::string& name,
                                          const std::string& source, const std::vector<std::string>& definitions) {
  const auto compile = [&] {
    return compile_for_device(name, source, definitions, context->compute_capability(), context->where());
  };
  if (!cache) return std::make_unique<CudaProgram>(context, name, source, compile());
  const std::string key = binary_cache_key(context->info(), definitions, source);
  if (const auto stored = cache->load(key))
    if (const auto image = deserialize(*stored)) {
      try {
        return std::make_unique<CudaProgram>(context, name, source, *image, true);
      } catch (const BackendError&) {
        // the driver refused it (another driver's cubin, newer PTX): compiled and stored again below
      }
    }
  const CompiledImage image = compile();
  auto program = std::make_unique<CudaProgram>(context, name, source, image);
  cache->store(key, serialize(image));  // a failed store costs time only
  return program;
}

}  // namespace depthtrack::compute::cuda
