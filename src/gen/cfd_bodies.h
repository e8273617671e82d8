// The bodies of the CFD-like meshes and the mesh-size law around them. Units: the main body has
// radius 1 about the x axis, its nose at x = 0; the free stream flows along +x, the wake trails
// behind. Bodies are OpenCASCADE solids in gmsh's current model.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "gen/generate.h"

namespace sm::gen {

// A part of a body for the size law: points within `radius` of the segment [a, b] are (roughly)
// inside it. Near a part the mesh size is at most `floor`, however coarse the mesh: enough
// elements around a leg or a nozzle for gmsh to mesh it and for the layer to follow it.
struct BodyPart {
  glm::dvec3 a, b;
  double radius;
  double floor;
};

struct BodyShape {
  std::vector<BodyPart> parts;
  double rearX;  // where the body ends and the wake begins
};

struct BuiltBody {
  int volume = -1;             // OCC volume tag
  std::vector<int> recombine;  // wall surfaces meshed with quads (hexahedra in the layer)
  BodyShape shape;
};

// Builds the body in gmsh's current model (OCC kernel, synchronised).
BuiltBody buildBody(Body body);

// The far-field box, the optional hexahedral block in the wake, and the size law: sizes grow away
// from the body and more slowly along the wake, and scale with one factor, so the element count
// falls roughly as scale^-3 (tetrahedra) and scale^-2 (layer on the wall).
struct Box {
  glm::dvec3 lo, hi;
};
Box farField(const BodyShape& shape);
Box hexBlockRegion(const BodyShape& shape);

class SizeLaw {
 public:
  SizeLaw(BodyShape shape, double scale, bool hexBlock);
  double operator()(const glm::dvec3& p) const;
  double wallSize() const;        // target edge length on the body (before part floors)
  double hexBlockSize() const;    // edge length of the hexahedra
  double layerThickness() const;  // total boundary-layer thickness

 private:
  BodyShape shape_;
  double scale_;
  bool hexBlock_;
  Box block_;
};

}  // namespace sm::gen
