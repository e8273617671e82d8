#include "io_core/array_plan.h"

#include <algorithm>
#include <charconv>

#include "common/error.h"
#include "mesh/unstructured_mesh.h"

namespace sm::io {
namespace {

struct Group {
  std::string base;
  uint32_t components = 1;
  bool identifier = false;
  bool plain = false;                              // has a step-less array
  std::vector<std::pair<uint64_t, size_t>> steps;  // (step, array index)
};

std::vector<Group> groupArrays(const std::string& source, const std::vector<ArrayInfo>& arrays,
                               std::string_view kind) {
  std::vector<Group> groups;
  for (size_t i = 0; i < arrays.size(); ++i) {
    StepName s = splitStepName(arrays[i].name);
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const Group& g) { return g.base == s.base; });
    if (it == groups.end()) {
      groups.push_back({s.base, arrays[i].components, arrays[i].identifier, false, {}});
      it = groups.end() - 1;
    }
    Group& g = *it;
    if (g.components != arrays[i].components)
      throw FileError(source, "time steps of ", kind, " array '", g.base, "' have ", g.components,
                      " and ", arrays[i].components, " components");
    const uint64_t step = s.step.value_or(0);
    const bool clash =
        (s.step ? g.plain : !g.steps.empty()) ||
        std::any_of(g.steps.begin(), g.steps.end(), [&](const auto& e) { return e.first == step; });
    if (clash)
      throw FileError(source, kind, " array '", arrays[i].name, "' repeats ",
                      s.step ? "a time step" : "a name", " of field '", g.base, "'");
    g.plain = g.plain || !s.step;
    g.steps.emplace_back(step, i);
  }
  for (auto& g : groups) std::sort(g.steps.begin(), g.steps.end());
  return groups;
}

std::string listNames(const std::vector<Group>& groups) {
  std::string s;
  for (const auto& g : groups) {
    if (!s.empty()) s += ", ";
    s += g.base;
    if (g.components > 1) s += concat(" (", g.components, " components)");
  }
  return s.empty() ? "none" : s;
}

void addGroup(std::vector<FieldLoad>& loads, const std::string& source, const Group& g,
              int component, const std::string& field, std::optional<uint64_t> onlyStep,
              std::string_view kind) {
  // Steps run 0 .. n-1 (g.steps is sorted), checked before anything is read or sized: a step
  // number is a name's suffix, and "p@t99999999999" must not size a field with that many steps.
  // With --time, the steps not loaded are checked too, so that a file missing one fails as a full
  // read does.
  for (uint64_t i = 0; i < g.steps.size(); ++i)
    if (g.steps[i].first != i)
      throw FileError(source, kind, " field '", field, "' has no values for time step ", i);
  if (!onlyStep) {
    for (const auto& [step, array] : g.steps) loads.push_back({array, component, field, step});
    return;
  }
  const size_t chosen = std::min<uint64_t>(*onlyStep, g.steps.size() - 1);
  loads.push_back({g.steps[chosen].second, component, field, 0});
}

}  // namespace

std::optional<uint64_t> plainDecimal(std::string_view text) {
  uint64_t v = 0;
  const char* b = text.data();
  const char* e = b + text.size();
  auto [p, ec] = std::from_chars(b, e, v);
  if (text.empty() || ec != std::errc() || p != e || (*b == '0' && text.size() > 1))
    return std::nullopt;
  return v;
}

StepName splitStepName(std::string_view name) {
  size_t at = name.rfind("@t");
  if (at == std::string_view::npos || at == 0 || at + 2 == name.size())
    return {std::string(name), {}};
  // Steps are written in plain decimal (vtu_writer, FORMATS.md): "p@t01" is a name, not step 1 of
  // "p", or it and "p@t1" would both claim that step.
  const std::optional<uint64_t> step = plainDecimal(name.substr(at + 2));
  if (!step) return {std::string(name), {}};
  return {std::string(name.substr(0, at)), *step};
}

// "NAME[k]" -> (NAME, k).
std::optional<std::pair<std::string, int>> splitComponent(std::string_view request) {
  size_t open = request.rfind('[');
  if (open == std::string_view::npos || request.size() < open + 3 || request.back() != ']')
    return std::nullopt;
  // Decimal without leading zeros or a sign, as step numbers are: "v[01]" is an array of that name.
  const std::optional<uint64_t> k =
      plainDecimal(request.substr(open + 1, request.size() - open - 2));
  if (!k || *k > uint64_t(INT32_MAX)) return std::nullopt;
  return std::make_pair(std::string(request.substr(0, open)), int(*k));
}

std::vector<FieldLoad> planFields(const std::string& source,
                                  const std::vector<ArrayInfo>& pointArrays,
                                  const ReadOptions& options,
                                  const std::vector<std::string>* cellData, std::string_view kind) {
  std::vector<FieldLoad> loads;
  if (!options.loadFields) return loads;
  const std::vector<Group> groups = groupArrays(source, pointArrays, kind);
  if (options.fields.empty()) {
    for (const auto& g : groups)
      if (!g.identifier) addGroup(loads, source, g, -1, g.base, options.step, kind);
    return loads;
  }
  std::vector<std::string> done;
  for (const std::string& request : options.fields) {
    if (std::find(done.begin(), done.end(), request) != done.end()) continue;
    done.push_back(request);
    auto byName = [&](const std::string& n) {
      return std::find_if(groups.begin(), groups.end(),
                          [&](const Group& g) { return g.base == n; });
    };
    if (auto it = byName(request); it != groups.end()) {
      addGroup(loads, source, *it, -1, request, options.step, kind);
      continue;
    }
    auto split = splitComponent(request);
    auto it = split ? byName(split->first) : groups.end();
    if (it == groups.end()) {
      // A name that is no array at all: the cell data is listed too, where the field may be.
      const std::vector<std::string> none;
      const std::vector<std::string>& cellNames = cellData ? *cellData : none;
      const std::string hint = mesh::cellArrayHint(cellNames, request);
      std::string cells;
      if (cellData && hint.empty()) {
        for (const std::string& n : cellNames) cells += (cells.empty() ? "" : ", ") + n;
        cells = "; cell data: " + (cells.empty() ? std::string("none") : cells);
      }
      throw FileError(source, "has no ", kind, cellData && hint.empty() ? " or cell" : "",
                      " array '", split ? split->first : request, "' (", kind,
                      " arrays: ", listNames(groups), cells, ")", hint);
    }
    if (uint32_t(split->second) >= it->components)
      throw FileError(source, "field '", request, "': ", kind, " array '", it->base, "' has ",
                      it->components, it->components == 1 ? " component" : " components");
    addGroup(loads, source, *it, split->second, request, options.step, kind);
  }
  return loads;
}

std::optional<size_t> chooseClusterArray(const std::string& source,
                                         const std::vector<std::string>& cellArrays,
                                         const ReadOptions& options) {
  auto find = [&](std::string_view n) -> std::optional<size_t> {
    auto it = std::find(cellArrays.begin(), cellArrays.end(), n);
    if (it == cellArrays.end()) return std::nullopt;
    return static_cast<size_t>(it - cellArrays.begin());
  };
  if (!options.clusterArray.empty()) {
    if (auto i = find(options.clusterArray)) return i;
    std::string names;
    for (const auto& n : cellArrays) names += (names.empty() ? "" : ", ") + n;
    throw FileError(source, "has no cell array '", options.clusterArray,
                    "' for cluster ids (cell arrays: ", names.empty() ? "none" : names, ")");
  }
  for (std::string_view n : {"cluster", "partition", "vtkProcessId"})
    if (auto i = find(n)) return i;
  return std::nullopt;
}

bool holdsField(const std::vector<ArrayInfo>& arrays, const std::string& request) {
  const auto c = splitComponent(request);
  for (const ArrayInfo& a : arrays) {
    const std::string base = splitStepName(a.name).base;
    if (base == request || (c && base == c->first)) return true;
  }
  return false;
}

FieldSplit splitFieldRequests(const std::vector<ArrayInfo>& pointArrays,
                              const std::vector<ArrayInfo>& cellArrays,
                              const ReadOptions& options) {
  FieldSplit split{options, options};
  split.cells.fields.clear();
  if (options.fields.empty() || !options.loadFields) {
    split.cells.loadFields = false;
    return split;
  }
  split.points.fields.clear();
  for (const std::string& r : options.fields) {
    if (!holdsField(pointArrays, r) && holdsField(cellArrays, r))
      split.cells.fields.push_back(r);
    else
      split.points.fields.push_back(r);
  }
  split.points.loadFields = !split.points.fields.empty();
  split.cells.loadFields = !split.cells.fields.empty();
  return split;
}

std::vector<std::string> dataCellArrays(const std::vector<std::string>& names,
                                        const ReadOptions& options) {
  std::vector<std::string> data;
  for (const std::string& n : names) {
    if (isBookkeepingArray(n) || n == options.clusterArray || n == "cluster" || n == "partition" ||
        n == "vtkProcessId")
      continue;
    std::string base = splitStepName(n).base;  // "p@t0", "p@t1": the field p
    if (std::find(data.begin(), data.end(), base) == data.end()) data.push_back(std::move(base));
  }
  return data;
}

bool isBookkeepingArray(std::string_view name) {
  for (std::string_view n :
       {"vtkGhostType", "vtkValidPointMask", "vtkOriginalPointIds", "vtkOriginalCellIds",
        "GlobalNodeId", "PedigreeNodeId", "GlobalElementId", "PedigreeElementId", "vtkGlobalIds"})
    if (name == n) return true;
  return false;
}

bool isTimeValuesArray(std::string_view name) {
  return name == "TimeValue" || name == "TimeValues";
}

}  // namespace sm::io
