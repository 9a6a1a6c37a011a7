#pragma once
// A compute device's facts as JSON, the keys `depthtrack info --json` prints (the Python
// devices() dicts are made from it too). The extensions list is left to the caller, which puts
// it last after facts of its own.
#include <nlohmann/json.hpp>

#include "compute/device_info.hpp"

namespace depthtrack::io {

inline nlohmann::ordered_json device_facts_json(const compute::DeviceInfo& d) {
  nlohmann::ordered_json j;
  j["selector"] = d.selector;
  j["name"] = d.name;
  j["platform"] = d.platform;
  j["vendor"] = d.vendor;
  j["driver"] = d.driver;
  j["version"] = d.version;
  j["gpu"] = d.is_gpu;
  j["global_memory_bytes"] = d.global_memory;
  j["max_allocation_bytes"] = d.max_allocation;
  j["local_memory_bytes"] = d.local_memory;
  j["max_work_group_size"] = d.max_work_group_size;
  j["compute_units"] = d.compute_units;
  j["gl_sharing"] = d.gl_sharing;
  j["external_memory"] = d.external_memory;
  j["fp64"] = d.fp64;
  j["subgroups"] = d.subgroups;
  j["int64_atomics"] = d.int64_atomics;
  return j;
}

}  // namespace depthtrack::io
