// Which arrays of a file become what in the mesh, by the same rules for every format
// (docs/FORMATS.md): point arrays become fields ("NAME@t<K>" arrays are the steps of field NAME),
// one cell array gives the cluster ids, field data "TimeValue(s)" gives the step times.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io_core/read_options.h"

namespace sm::io {

struct ArrayInfo {
  std::string name;  // as the file names it (legacy names already %XX-decoded)
  uint32_t components = 1;
  bool identifier = false;  // ids and bookkeeping (GlobalIds, vtkGhostType): only when asked
};

// One field step to load: component `component` (-1: the scalar, or a vector's magnitude) of
// point array `array`, as step `step` of field `field`.
struct FieldLoad {
  size_t array = 0;
  int component = -1;
  std::string field;
  uint64_t step = 0;
};

struct StepName {
  std::string base;
  std::optional<uint64_t> step;
};
// "p@t12" -> ("p", 12); any other name -> (name, none).
StepName splitStepName(std::string_view name);

// Digits alone, without a sign or a leading zero ("0", "12"; not "012", "+1", "-0"): how step and
// component numbers are written in array names and field requests.
std::optional<uint64_t> plainDecimal(std::string_view text);

// A field request "NAME[k]" -> (NAME, k); a request without a component -> none.
std::optional<std::pair<std::string, int>> splitComponent(std::string_view request);

// The loads that options ask for (every non-identifier array when options.fields is empty).
// Throws sm::FileError(source, ...) for a requested name the file lacks (listing what it has), a
// component out of range, or a name given both plain and with time steps.
// `cellData` (dataCellArrays), where given, says that the requests were looked for among the cell
// data too, so that the message names both places and what each holds; a format without cell
// data passes none. `kind` names the arrays in messages ("point", or "cell" when planning cell
// data).
std::vector<FieldLoad> planFields(const std::string& source,
                                  const std::vector<ArrayInfo>& pointArrays,
                                  const ReadOptions& options,
                                  const std::vector<std::string>* cellData = nullptr,
                                  std::string_view kind = "point");

// Which of options.fields a reader loads from point data and which from cell data (to be averaged
// onto the points): a request is cell data when it names no point array (by its name, a component
// "NAME[k]" or time steps "NAME@tK") but a cell array. Point data wins where both have the name.
// Cell data is read only when asked for by name: with no fields named, `cells` is empty.
struct FieldSplit {
  ReadOptions points;  // options with only the point requests (loadFields off if none is left)
  ReadOptions cells;   // options with only the cell requests (loadFields off if none)
};
// True when `arrays` hold field `request` ("NAME", its steps "NAME@tK", or the array of "NAME[k]").
bool holdsField(const std::vector<ArrayInfo>& arrays, const std::string& request);
FieldSplit splitFieldRequests(const std::vector<ArrayInfo>& pointArrays,
                              const std::vector<ArrayInfo>& cellArrays, const ReadOptions& options);

// The cell data among the cell arrays `names`, by field name (the steps "NAME@tK" of one field
// listed once, as NAME): not bookkeeping (isBookkeepingArray) and not cluster ids
// (options.clusterArray, "cluster", "partition", "vtkProcessId").
std::vector<std::string> dataCellArrays(const std::vector<std::string>& names,
                                        const ReadOptions& options);

// Index of the cell array with cluster ids: options.clusterArray (sm::FileError listing the cell
// arrays when absent), else the first of "cluster", "partition", "vtkProcessId"; none: cluster 0.
std::optional<size_t> chooseClusterArray(const std::string& source,
                                         const std::vector<std::string>& cellArrays,
                                         const ReadOptions& options);

// Arrays VTK and solvers use for bookkeeping rather than data: never loaded unless asked by name.
bool isBookkeepingArray(std::string_view name);
// Field data arrays that hold the time of each step.
bool isTimeValuesArray(std::string_view name);

}  // namespace sm::io
