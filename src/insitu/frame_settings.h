// From the API's per-frame settings to the session layer's frame request (session/frame_request.h,
// which makes the renderer's settings as for every front end): what only the API has is checked
// here (its strings, a given range, the legend's colour), and a digest checks that every rank asked
// for the same frame. Errors name the API's fields: "render: sampleDistance: ...".
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "mesh/bounds.h"
#include "session/frame_request.h"
#include "shellmarch/insitu.h"

namespace sm::insitu {

// What every rank agrees on after setMesh.
struct MeshFrame {
  mesh::Bounds whole;
  double meanElementSize = 0;
  uint64_t elements = 0;  // all ranks
};

session::FrameRequest frameRequest(const shellmarch::insitu::RenderSettings& s);
session::DataExtent dataExtent(const MeshFrame& frame);

// Runs f; a SettingError it throws becomes an Error naming the API's field, "render: <field>:
// <detail>".
void inApiTerms(const std::function<void()>& f);

// Digest of the settings that must match on every rank.
uint64_t settingsDigest(const shellmarch::insitu::RenderSettings& s);

}  // namespace sm::insitu
