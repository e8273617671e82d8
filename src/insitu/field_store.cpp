#include "field_store.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "prep/prepare.h"

namespace sm::insitu {

FieldStore::FieldStore(prep::PreparedRank vertexMap, uint64_t inputVertices)
    : vertexMap_(std::move(vertexMap)), inputVertices_(inputVertices), hasMesh_(true) {}

void FieldStore::set(const std::string& name, std::span<const float> values) {
  if (!hasMesh_) throw Error("setField: no mesh (call setMesh first)");
  if (name.empty()) throw Error("setField: the field needs a name");
  if (values.size() != inputVertices_)
    throw Error("setField: field '", name, "' has ", values.size(), " values, but setMesh gave ",
                inputVertices_, " vertices (one value per vertex)");
  auto it =
      std::find_if(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == name; });
  Field& f = it != fields_.end() ? *it : fields_.emplace_back(Field{name, {}, {}, 0});
  f.values = prep::gatherScalars(vertexMap_, values);
  f.range = FieldRange{};
  for (float v : f.values) {
    if (!std::isfinite(v)) continue;  // renders transparent; says nothing about the range
    f.range.lo = std::min(f.range.lo, double(v));
    f.range.hi = std::max(f.range.hi, double(v));
  }
  f.version = nextVersion_++;
}

const FieldStore::Field& FieldStore::find(const std::string& name) const {
  if (fields_.empty()) throw Error("render: no field on this rank (call setField before render)");
  if (name.empty()) return fields_.front();
  for (const Field& f : fields_)
    if (f.name == name) return f;
  std::string names;
  for (const Field& f : fields_) names += (names.empty() ? "'" : ", '") + f.name + "'";
  throw Error("render: no field '", name, "' on this rank (set: ", names, ")");
}

FieldRange FieldStore::prepare(const std::string& name, render::GpuScene& scene) {
  if (scene.numVertices() == 0) return {};
  const Field& f = find(name);
  if (f.version != uploadedVersion_) {
    scene.setScalars(f.values);
    uploadedVersion_ = f.version;
  }
  return f.range;
}

}  // namespace sm::insitu
