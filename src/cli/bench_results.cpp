#include "cli/bench_results.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace depthtrack::cli {

namespace fs = std::filesystem;

double median_of(std::vector<double> s) {
  if (s.empty()) return NAN;
  std::sort(s.begin(), s.end());
  const size_t n = s.size();
  return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

double p95_of(std::vector<double> s) {
  if (s.empty()) return NAN;
  std::sort(s.begin(), s.end());
  const auto rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(s.size())));
  return s[std::max<size_t>(rank, 1) - 1];
}

namespace {

nlohmann::ordered_json number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

// 'path', built by appending (GCC 12 warns falsely on "'" + string).
std::string quoted(const fs::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

const char* const kTextColumns[] = {"backend", "platform", "device", "driver", "commit", "test", "metric", "unit"};

}  // namespace

void write_results(const BenchResults& results, const fs::path& path) {
  nlohmann::ordered_json root;
  root["format"] = "depthtrack-bench";
  root["version"] = 1;
  nlohmann::ordered_json rows = nlohmann::json::array();
  for (const BenchRow& r : results.rows) {
    nlohmann::ordered_json j;
    const std::string* text[] = {&r.backend, &r.platform, &r.device, &r.driver, &r.commit, &r.test, &r.metric, &r.unit};
    for (size_t i = 0; i < std::size(kTextColumns); ++i) j[kTextColumns[i]] = *text[i];
    j["median"] = number(r.median);
    j["p95"] = number(r.p95);
    j["samples"] = r.samples;
    rows.push_back(j);
  }
  root["rows"] = rows;
  root["notes"] = results.notes;
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial);
    out << root.dump(1) << "\n";
    out.close();  // the buffer's last bytes fail only here on a full disk
    if (out.fail()) throw Error("cannot write " + quoted(partial));
  }
  std::error_code error;
  fs::rename(partial, path, error);
  if (error) throw Error("cannot rename " + quoted(partial) + " to " + quoted(path) + ": " + error.message());
}

BenchResults read_results(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the bench results " + quoted(path));
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(quoted(path) + " is not valid JSON: " + e.what());
  }
  if (!root.is_object() || !root.contains("rows") || !root["rows"].is_array())
    throw InputError(quoted(path) + " has no \"rows\" array: is it a results.json of depthtrack bench?");
  BenchResults results;
  for (size_t i = 0; i < root["rows"].size(); ++i) {
    const nlohmann::json& j = root["rows"][i];
    const std::string where = quoted(path) + " row " + std::to_string(i);
    if (!j.is_object()) throw InputError(where + " is not an object");
    BenchRow r;
    std::string* text[] = {&r.backend, &r.platform, &r.device, &r.driver, &r.commit, &r.test, &r.metric, &r.unit};
    for (size_t c = 0; c < std::size(kTextColumns); ++c) {
      if (!j.contains(kTextColumns[c])) throw InputError(where + " has no '" + kTextColumns[c] + "'");
      if (!j[kTextColumns[c]].is_string()) throw InputError(where + ": '" + kTextColumns[c] + "' must be a string");
      *text[c] = j[kTextColumns[c]].get<std::string>();
    }
    for (auto [name, value] : {std::pair{"median", &r.median}, std::pair{"p95", &r.p95}}) {
      if (!j.contains(name)) throw InputError(where + " has no '" + name + "'");
      if (j[name].is_null())
        *value = NAN;
      else if (j[name].is_number())
        *value = j[name].get<double>();
      else
        throw InputError(where + ": '" + name + "' must be a number or null");
    }
    if (!j.contains("samples") || !j["samples"].is_number_integer())
      throw InputError(where + ": 'samples' must be an integer");
    r.samples = j["samples"].get<int>();
    results.rows.push_back(std::move(r));
  }
  if (results.rows.empty()) throw InputError(quoted(path) + " has no rows");
  if (root.contains("notes") && root["notes"].is_array())
    for (const auto& n : root["notes"])
      if (n.is_string()) results.notes.push_back(n.get<std::string>());
  return results;
}

std::string compare_table(const std::vector<std::pair<std::string, BenchResults>>& files) {
  struct Column {
    std::string label;
    std::map<std::pair<std::string, std::string>, double> values;  // (test, metric) -> median
  };
  std::vector<Column> columns;
  std::vector<std::pair<std::string, std::string>> keys;  // in order of first appearance
  std::map<std::pair<std::string, std::string>, std::string> units;
  for (const auto& [name, results] : files) {
    std::map<std::string, size_t> by_backend;
    for (const BenchRow& r : results.rows) {
      auto [it, fresh] = by_backend.try_emplace(r.backend, columns.size());
      if (fresh) columns.push_back({fs::path(name).filename().string() + ":" + r.backend + " (" + r.device + ")", {}});
      const auto key = std::pair{r.test, r.metric};
      if (!units.count(key)) {
        keys.push_back(key);
        units[key] = r.unit;
      }
      columns[it->second].values[key] = r.median;
    }
  }
  // Each test's metrics together, tests in the order they first appear.
  std::map<std::string, size_t> test_rank;
  for (const auto& key : keys) test_rank.try_emplace(key.first, test_rank.size());
  std::stable_sort(keys.begin(), keys.end(),
                   [&](const auto& a, const auto& b) { return test_rank[a.first] < test_rank[b.first]; });
  std::ostringstream out;
  for (size_t c = 0; c < columns.size(); ++c) out << "[" << c + 1 << "] " << columns[c].label << "\n";
  size_t width = 4;
  for (const auto& [test, metric] : keys) width = std::max(width, test.size() + metric.size() + 1);
  char cell[64];
  out << std::string(width, ' ') << "  unit    ";
  for (size_t c = 0; c < columns.size(); ++c) {
    char label[32];
    std::snprintf(label, sizeof label, "[%zu]", c + 1);
    std::snprintf(cell, sizeof cell, "%22s", label);
    out << cell;
  }
  out << "\n";
  for (const auto& key : keys) {
    const std::string name = key.first + " " + key.second;
    out << name << std::string(width - name.size(), ' ') << "  ";
    std::snprintf(cell, sizeof cell, "%-8s", units[key].c_str());
    out << cell;
    const auto first = columns.front().values.find(key);
    const double base = first == columns.front().values.end() ? NAN : first->second;
    for (size_t c = 0; c < columns.size(); ++c) {
      const auto v = columns[c].values.find(key);
      if (v == columns[c].values.end() || !std::isfinite(v->second)) {
        std::snprintf(cell, sizeof cell, "%22s", "-");
      } else if (c == 0 || !std::isfinite(base) || base == 0) {
        std::snprintf(cell, sizeof cell, "%22.4g", v->second);
      } else {
        std::snprintf(cell, sizeof cell, "%13.4g (x%.2f)", v->second, v->second / base);
      }
      out << cell;
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace depthtrack::cli
