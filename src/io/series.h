// Time series written as one mesh file per step, the way solvers and ParaView write them: a
// ParaView data collection (.pvd, XML) or a file series (NAME.vtu.series, JSON). Every step is the
// same mesh; step k of each field is that field in the k-th file, in time order. The geometry is
// read from the first file, and each later file gives only its fields (docs/FORMATS.md).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/mesh_io.h"

namespace sm::io {

bool isSeries(const std::string& path);  // by extension: .pvd or .series

struct SeriesStep {
  std::string file;  // resolved against the series file's folder
  double time = 0;
};

// The steps a series names, sorted by time. Throws sm::FileError naming the series for an empty or
// malformed index, a time given twice (a .pvd's parts of one step: join them as a .pvtu's pieces),
// a step that is itself a series, and steps of different formats.
std::vector<SeriesStep> readSeriesIndex(const std::string& path);

// Reads a series as one mesh: the first file's geometry (ReadOptions::step: that step's file),
// each field with one step per file, and the steps' times. `readStep` reads one file as readMesh
// does, without averaging cell data onto points (the caller does that once for all steps).
using ReadStepFile =
    std::function<mesh::UnstructuredMesh(const std::string& file, const ReadOptions& options)>;
mesh::UnstructuredMesh readSeries(const std::string& path, const ReadOptions& options,
                                  const ReadStepFile& readStep);

// listFieldSteps, readFieldStep and readCellFieldStep for a series.
std::vector<FieldStepCount> seriesFieldSteps(const std::string& path, const ReadOptions& options);
std::vector<float> seriesFieldStep(const std::string& path, const std::string& field, uint64_t step,
                                   const ReadOptions& options, std::span<const uint32_t> pointMap);
std::vector<float> seriesCellFieldStep(const std::string& path, const std::string& field,
                                       uint64_t step, const ReadOptions& options,
                                       std::span<const uint32_t> cellMap);

}  // namespace sm::io
