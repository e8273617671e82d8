// From a target element count to the size law's scale (see cfd_bodies.h), calibrated by
// measurement for each body with and without the hexahedral block.
#pragma once

#include <cstdint>

#include "gen/generate.h"

namespace sm::gen {

constexpr uint64_t kMinCfdElements = 5000;  // below this a target is an error

// The scale whose mesh has about targetElements elements; targets below cfdMinElements get the
// coarsest mesh the body allows.
double cfdMeshScale(Body body, bool hexBlock, uint64_t targetElements);
uint64_t cfdMinElements(Body body, bool hexBlock);

}  // namespace sm::gen
