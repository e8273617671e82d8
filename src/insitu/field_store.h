// The fields a simulation hands over each step, kept in the renderer's vertex order, and the one
// the GPU holds. Only a field that changed since its last upload goes to the device: a time step
// costs one scalar upload, never a geometry rebuild.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "prep/prepared_rank.h"
#include "render/gpu_scene.h"

namespace sm::insitu {

// Finite values of a field on this rank (lo > hi when there are none).
struct FieldRange {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
};

class FieldStore {
 public:
  FieldStore() = default;  // no mesh yet
  // vertexMap: a prepared rank of which only vertexSource is used (the rest may be released).
  FieldStore(prep::PreparedRank vertexMap, uint64_t inputVertices);

  // Copies one field in the caller's vertex order; throws sm::Error on a wrong size.
  void set(const std::string& name, std::span<const float> values);
  // Makes field `name` ("" = the first one set) the scene's scalars, uploading it only when it is
  // not there already; returns its range on this rank. A rank without vertices needs no field.
  FieldRange prepare(const std::string& name, render::GpuScene& scene);
  // The name of the first field set ("" before any).
  std::string firstName() const { return fields_.empty() ? std::string() : fields_.front().name; }

 private:
  struct Field {
    std::string name;
    std::vector<float> values;  // renderer's vertex order
    FieldRange range;
    uint64_t version = 0;
  };
  const Field& find(const std::string& name) const;

  prep::PreparedRank vertexMap_;
  uint64_t inputVertices_ = 0;
  bool hasMesh_ = false;
  std::vector<Field> fields_;
  uint64_t nextVersion_ = 1, uploadedVersion_ = 0;
};

}  // namespace sm::insitu
