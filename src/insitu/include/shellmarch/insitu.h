// shellmarch in situ: direct volume rendering of a simulation's unstructured mesh from its own
// arrays, data-parallel over the simulation's MPI ranks (docs/INSITU.md).
//
//   shellmarch::insitu::Renderer r(MPI_COMM_WORLD);      // collective
//   r.setMesh({points, tets, {}, wedges, hexes});         // collective, once
//   for each step:
//     r.setField("temperature", T);                      // local: copies the scalars
//     r.setCellField("pressure", p);                     // collective: one value per element
//     Image img = r.render(settings);                    // collective; the image on rank 0
//
// Collective calls must be made by every rank of the communicator, in the same order. An error
// in a collective call (bad input on any rank) is thrown on every rank as Error, naming the rank
// that failed; no rank is left waiting. This header includes nothing of shellmarch's internals.
#pragma once

#include <mpi.h>

#include <array>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <ranges>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#define SHELLMARCH_INSITU_API __attribute__((visibility("default")))

namespace shellmarch::insitu {

class SHELLMARCH_INSITU_API Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Any 32- or 64-bit integer (int, unsigned, long, long long, int64_t, ...).
template <typename T>
concept VertexIndex =
    std::integral<T> && !std::same_as<T, bool> && (sizeof(T) == 4 || sizeof(T) == 8);

// A read-only view of one element type's connectivity (numVertices ids per element, back to
// back), in whichever integer type the simulation stores. Nothing is copied on construction: the
// array must live until the setMesh call that reads it returns.
class IndexSpan {
 public:
  IndexSpan() = default;
  template <VertexIndex T>
  IndexSpan(std::span<const T> ids) : data_(ids.data()), size_(ids.size()), kind_(kindOf<T>()) {}
  template <std::ranges::contiguous_range R>
  requires VertexIndex<std::ranges::range_value_t<R>> IndexSpan(const R& ids)
      : IndexSpan(std::span<const std::ranges::range_value_t<R>>(std::ranges::data(ids),
                                                                 std::ranges::size(ids))) {}

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Id i widened to 64 bits (an unsigned id above 2^63 - 1 reads as negative: out of range).
  int64_t operator[](size_t i) const {
    switch (kind_) {
      case Kind::I32:
        return load<int32_t>(i);
      case Kind::U32:
        return load<uint32_t>(i);
      case Kind::I64:
        return load<int64_t>(i);
      case Kind::U64:
        return static_cast<int64_t>(load<uint64_t>(i));
    }
    return -1;
  }

 private:
  enum class Kind : uint8_t { I32, U32, I64, U64 };
  template <typename T>
  static constexpr Kind kindOf() {
    if constexpr (sizeof(T) == 4) return std::is_signed_v<T> ? Kind::I32 : Kind::U32;
    return std::is_signed_v<T> ? Kind::I64 : Kind::U64;
  }
  // memcpy: the caller's type may be long long where int64_t is long (no aliasing questions).
  template <typename T>
  T load(size_t i) const {
    T v;
    std::memcpy(&v, static_cast<const char*>(data_) + i * sizeof(T), sizeof v);
    return v;
  }
  const void* data_ = nullptr;
  size_t size_ = 0;
  Kind kind_ = Kind::I32;
};

// This rank's part of the mesh. Ids index `points` (0-based); vertex order within an element is
// VTK's (VTK_TETRA, VTK_PYRAMID, VTK_WEDGE, VTK_HEXAHEDRON). Elements may be inverted (they are
// reoriented); vertices no element uses are allowed. Ranks may share vertices (duplicated, with
// identical coordinates) but not elements.
struct MeshView {
  std::span<const double> points;  // x, y, z per vertex
  IndexSpan tetrahedra;            // 4 ids per element
  IndexSpan pyramids;              // 5
  IndexSpan wedges;                // 6
  IndexSpan hexahedra;             // 8
  // Optional: the simulation's global number of each vertex (one per vertex, >= 0, the same on
  // every rank that holds the vertex). setCellField then finds vertices shared between ranks by
  // these numbers instead of by their coordinates, which keeps apart the two sides of a baffle
  // (coincident vertices that are not one) when each side is on its own rank.
  IndexSpan globalIds;
  // Optional: general polyhedra (OpenFOAM, Fluent and STAR-CCM+ cells), as VTK's face streams one
  // after another: for each polyhedron its number of faces, then for each face its number of
  // vertices and their ids, the faces turning the same way (all outward or all inward). Each is
  // split into tetrahedra on its own vertices (docs/FORMATS.md, "Polyhedra"); one that cannot be
  // is skipped with a warning. Element order for setCellField: polyhedra come last.
  IndexSpan polyhedra;
};

struct Camera {
  std::array<double, 3> eye{0, 0, 1}, at{0, 0, 0}, up{0, 0, 1};
  double fovyDeg = 30.0;  // vertical field of view
};

// Keeps the half-space the normal points into, dot(x - point, normal) >= 0 (VTK's convention).
struct ClipPlane {
  std::array<double, 3> point{0, 0, 0}, normal{0, 0, 1};
};

// Per frame. Every rank must pass the same settings.
struct RenderSettings {
  int width = 512, height = 512;
  std::string field;                 // "" = the first field given with setField
  std::optional<Camera> camera;      // unset: frame the whole mesh from `view`
  std::string view = "iso";          // "iso", "+x", "-x", "+y", "-y", "+z", "-z" (looking along it)
  std::string colormap = "viridis";  // built-in name or a ParaView colour map .json file
  // When not empty: the transfer function's RGBA table (>= 2 entries, rgb and opacity in [0, 1],
  // interpolated linearly over the range); replaces `colormap`.
  std::vector<std::array<float, 4>> table;
  std::optional<std::array<double, 2>> range;  // unset: the field's min and max over all ranks
  // Map the field's logarithm onto the table (the range must then be positive; values <= 0 take
  // the table's first entry).
  bool logScale = false;
  double opacityScale = 1.0;
  double unitDistance = 0;    // opacity 1 means optical depth 1 over this; <= 0: diagonal / 8
  double sampleDistance = 0;  // between samples along a ray; <= 0: half the mean element size, at
                              // most the diagonal / 256 (exact: the longest linear piece)
  // "exact": every element crossing integrated whole with a pre-integrated transfer function (far
  // less error at about the time of the default step); "sampled": samples every sampleDistance
  // on a grid shared by all ranks (the paper's method).
  std::string integration = "exact";
  double earlyTermination = 0.99;     // a ray stops once this opaque; >= 1 never stops early
  std::vector<ClipPlane> clipPlanes;  // up to 6: only what every plane keeps is drawn
  // Draw the colour legend into the image, as `render --legend` does: the colour map at the
  // right with the field's name and range. It is opaque; its text is white when the image will
  // be shown over a dark `legendBackground` and black over a light one.
  bool legend = false;
  std::array<float, 3> legendBackground{0, 0, 0};
};

// Premultiplied RGBA, 4 floats per pixel, row 0 at the top. Empty on ranks other than 0.
struct SHELLMARCH_INSITU_API Image {
  int width = 0, height = 0;
  std::vector<float> rgba;

  bool empty() const { return rgba.empty(); }
  // The same premultiplied colour and opacity as 8-bit values (4 per pixel).
  std::vector<uint8_t> toRgba8() const;
  // Composited over `background` and written as an 8-bit RGB PNG (atomically: a reader never sees
  // a partial file). Throws Error on failure.
  void writePng(const std::string& path, std::array<float, 3> background = {0, 0, 0}) const;
  // Written as an 8-bit RGBA PNG that keeps the image's alpha, its colour un-premultiplied (as
  // `shellmarch render --background transparent`), for pages and slides of any colour.
  void writeTransparentPng(const std::string& path) const;
};

struct Options {
  std::string device;       // "" = the best device; a number = that index; else a name substring
  bool validation = false;  // Khronos validation layer (also on with SHELLMARCH_VALIDATION=1)
  // How shell crossings are traced: "auto" (ray queries where the device offers them, else a ray
  // tracing pipeline), "query" or "pipeline". Images are the same either way.
  std::string tracer = "auto";
};

struct Stats {
  std::string deviceName;
  std::string tracer;  // "query" or "pipeline": the one that renders
  uint64_t vertices = 0, elements = 0, shellTriangles = 0;  // this rank, as prepared
  uint64_t geometryBuilds = 0;  // mesh uploads and acceleration structure builds on this rank
  uint64_t scalarUploads = 0;   // field uploads on this rank
  uint64_t validationErrors = 0, validationWarnings = 0;
  double prepareSeconds = 0;  // last setMesh on this rank: preparation and upload
  double frameMs = 0;         // last render, wall clock on this rank
};

class SHELLMARCH_INSITU_API Renderer {
 public:
  // Collective over `comm` (duplicated; MPI must be initialised and outlive this object).
  explicit Renderer(MPI_Comm comm, const Options& options = {});
  // One process: no MPI calls at all (MPI need not be initialised).
  explicit Renderer(const Options& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  int rank() const;
  int ranks() const;

  // Collective. Validates and copies this rank's mesh into the renderer's prepared form (the
  // caller's arrays may change or go away afterwards), agrees on the global frame with the other
  // ranks and uploads it. Calling it again replaces the mesh and forgets every field.
  void setMesh(const MeshView& mesh);
  // Local. Copies one field's values (one per vertex of setMesh's points, caller's order). NaN and
  // infinite values are allowed and render transparent. Only a changed field is uploaded.
  void setField(const std::string& name, std::span<const float> values);
  // Collective: every rank calls it with the same name. Copies one field given per element (as
  // finite-volume solvers hold their unknowns), in setMesh's order: the tetrahedra, then the
  // pyramids, wedges and hexahedra. Each vertex gets the mean of the elements that use it, on
  // every rank (vertices shared between ranks are found by MeshView::globalIds when given, else
  // by their coordinates, bit for bit), as
  // one process holding the whole mesh would compute it (ParaView's Cell Data to Point Data): no
  // seam at the partition's borders. The result is held as a vertex field under `name`. A NaN
  // element makes its vertices NaN (transparent). The first call after setMesh also finds the
  // shared vertices; later calls exchange only their sums.
  void setCellField(const std::string& name, std::span<const float> values);
  // Collective. Renders and composites; the image on rank 0, an empty image elsewhere.
  Image render(const RenderSettings& settings);
  // The same into `into`, whose storage is reused: a simulation that renders every step allocates
  // its image once (a 3840 x 2160 frame is 127 MiB of floats), not once a frame. Rank 0 only;
  // `into` is emptied elsewhere.
  void render(const RenderSettings& settings, Image& into);

  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shellmarch::insitu
