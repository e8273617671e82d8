#include "bench/bench_common.h"

#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/file_util.h"
#include "common/parallel.h"
#include "scene/camera.h"
#include "scene/transfer_function.h"
#include "scene/view_defaults.h"

namespace sm::app::bench {
namespace {

// The value after "key" and ':' on the first line that starts with key, trimmed.
std::string procField(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) != 0) continue;
    auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    auto b = line.find_first_not_of(" \t", colon + 1);
    return b == std::string::npos ? "" : line.substr(b);
  }
  return "";
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) out.push_back(item);
  return out;
}

uint64_t parseCount(const std::string& option, const std::string& item) {
  char* end = nullptr;
  double v = std::strtod(item.c_str(), &end);
  std::string suffix = end ? end : "";
  if (suffix == "k" || suffix == "K")
    v *= 1e3;
  else if (suffix == "M" || suffix == "m")
    v *= 1e6;
  else if (!suffix.empty())
    v = NAN;
  if (item.empty() || !(v >= 1) || v > 1e12)
    throw Error(option, ": '", item, "' is not a count (e.g. 1000000 or 1M)");
  return uint64_t(std::llround(v));
}

}  // namespace

nlohmann::json machineJson() {
  nlohmann::json m;
  m["cpu"] = procField("/proc/cpuinfo", "model name");
  m["logical_cores"] = machineThreads();
  m["threads"] = hardwareThreads();
  std::string mem = procField("/proc/meminfo", "MemTotal");  // "24567 kB"
  m["memory_bytes"] = uint64_t(std::strtoull(mem.c_str(), nullptr, 10)) * 1024;
  double load[3] = {0, 0, 0};
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3)
      load[0] = load[1] = load[2] = 0;
    std::fclose(f);
  }
  m["load_average"] = {load[0], load[1], load[2]};
  utsname u{};
  if (uname(&u) == 0) m["kernel"] = std::string(u.sysname) + " " + u.release;
  return m;
}

std::string machineLine(const nlohmann::json& m) {
  const auto& load = m["load_average"];
  return concat(m["cpu"].get<std::string>(), ", ", m["logical_cores"].get<unsigned>(),
                " logical cores, ", fixed(m["memory_bytes"].get<double>() / double(1ull << 30), 1),
                " GiB; load average ", fixed(load[0].get<double>(), 2), " ",
                fixed(load[1].get<double>(), 2), " ", fixed(load[2].get<double>(), 2));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<uint64_t> parseCounts(const std::string& option, const std::string& value) {
  std::vector<uint64_t> out;
  for (const std::string& item : split(value, ',')) out.push_back(parseCount(option, item));
  if (out.empty()) throw Error(option, ": needs at least one count");
  return out;
}

std::vector<std::pair<int, int>> parseSizes(const std::string& option, const std::string& value) {
  std::vector<std::pair<int, int>> out;
  for (const std::string& item : split(value, ',')) {
    std::vector<std::string> wh = split(item, 'x');
    if (wh.size() == 1) wh.push_back(wh[0]);
    if (wh.size() != 2) throw Error(option, ": '", item, "' is not N or WxH");
    int side[2];
    for (int k = 0; k < 2; ++k) {
      char* end = nullptr;
      long v = std::strtol(wh[k].c_str(), &end, 10);
      if (wh[k].empty() || *end || v < 1 || v > 16384)
        throw Error(option, ": '", item, "' is not an image size (1 .. 16384 per side)");
      side[k] = int(v);
    }
    out.emplace_back(side[0], side[1]);
  }
  if (out.empty()) throw Error(option, ": needs at least one size");
  return out;
}

std::string fixed(double value, int digits) {
  if (!std::isfinite(value)) return value > 0 ? "inf" : "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, value);
  return buf;
}

std::string sizeName(int width, int height) {
  return width == height ? concat(width, "²") : concat(width, "x", height);
}

std::string Table::str() const {
  // Width in code points, so that "²" and "≥" do not push a column out of line.
  auto width = [](const std::string& s) {
    size_t n = 0;
    for (unsigned char c : s) n += (c & 0xC0) != 0x80;
    return n;
  };
  std::vector<size_t> w(headers_.size(), 3);
  auto widen = [&](const std::vector<std::string>& row) {
    for (size_t i = 0; i < row.size() && i < w.size(); ++i) w[i] = std::max(w[i], width(row[i]));
  };
  widen(headers_);
  for (const auto& r : rows_) widen(r);
  auto line = [&](const std::vector<std::string>& row, bool rightAlign) {
    std::string s = "|";
    for (size_t i = 0; i < w.size(); ++i) {
      std::string cell = i < row.size() ? row[i] : "";
      std::string pad(w[i] - width(cell), ' ');
      s += ' ';
      if (rightAlign && i >= textColumns_)
        s.append(pad).append(cell);
      else
        s.append(cell).append(pad);
      s += " |";
    }
    return s + "\n";
  };
  std::string out = line(headers_, false) + "|";
  for (size_t i = 0; i < w.size(); ++i)
    out += i < textColumns_ ? std::string(w[i] + 2, '-') + "|" : std::string(w[i] + 1, '-') + ":|";
  out += "\n";
  for (const auto& r : rows_) out += line(r, true);
  return out;
}

void writeJsonFile(const std::string& path, const nlohmann::json& json) {
  writeTextFile(path, json.dump(2) + "\n");
}

void writeTextFile(const std::string& path, const std::string& text) {
  writeBytesAtomically(path, {reinterpret_cast<const uint8_t*>(text.data()), text.size()});
}

render::RenderSettings isoFrame(const mesh::UnstructuredMesh& m, const mesh::Field& f,
                                const std::string& colormap, int width, int height) {
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  s.camera = scene::frameBounds(m.bounds(), scene::ViewPreset::Iso, double(width) / height);
  s.transferFunction = scene::makeTransferFunction(colormap);
  const mesh::Range r = mesh::fieldRange(f, 0);
  s.transferFunction.lo = r.lo;
  s.transferFunction.hi = r.hi > r.lo ? r.hi : r.lo + 1;
  s.transferFunction.unitDistance = scene::defaultUnitDistance(m.bounds());
  s.dt = scene::elementStep(scene::elementSizeSum(m).mean());
  return s;
}

void checkValidation(const vk::Context& ctx) {
  if (ctx.validationErrors())
    throw Error("the Vulkan validation layer reported ", ctx.validationErrors(), " error(s)");
}

}  // namespace sm::app::bench
