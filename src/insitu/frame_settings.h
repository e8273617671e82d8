// From the API's per-frame settings to the renderer's: defaults that depend on the whole mesh
// (camera, sample distance, unit distance), validation with messages in the API's terms, and a
// digest for checking that every rank asked for the same frame.
#pragma once

#include <cstdint>

#include "mesh/unstructured_mesh.h"
#include "render/render_settings.h"
#include "shellmarch/insitu.h"

namespace sm::insitu {

// What every rank agrees on after setMesh.
struct MeshFrame {
  mesh::Bounds whole;
  double meanElementSize = 0;
  uint64_t elements = 0;  // all ranks
};

// Everything of the frame except the transfer function's range (which may need a reduction).
// Throws sm::Error naming the setting at fault.
render::RenderSettings toRenderSettings(const shellmarch::insitu::RenderSettings& s,
                                        const MeshFrame& frame);

// Digest of the settings that must match on every rank.
uint64_t settingsDigest(const shellmarch::insitu::RenderSettings& s);

}  // namespace sm::insitu
