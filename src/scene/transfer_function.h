// Transfer function: scalar -> colour and opacity, shared by the GPU renderer and the CPU
// reference.
//
// Model (docs/ARCHITECTURE.md, "Rendering model"):
//   x = clamp((s - lo) / (hi - lo), 0, 1), or on a log scale clamp(log(s / lo) / log(hi / lo), 0,
//   1) (0 < lo, values <= 0 below the range); the table (N >= 256 RGBA entries) is interpolated
//   linearly at x * (N - 1). NaN or infinite scalars are transparent. The scalar is interpolated
//   in the cells before it is mapped, on either scale (as ParaView's log colour mapping does).
//   Opacity is per unit length: extinction sigma(s) = opacity(s) * opacityScale / unitDistance,
//   so a sample taken every dt has alpha = 1 - exp(-sigma * dt) (opacity corrected for dt), and a
//   homogeneous slab of thickness L has opacity 1 - exp(-sigma * L) whatever dt is.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace sm::scene {

// How scalars map onto the table: linearly over [lo, hi], or by their logarithm (for fields that
// span decades: density, pressure, vorticity magnitude).
enum class ScalarScale { Linear, Log };

struct TransferFunction {
  std::vector<glm::vec4> table;  // rgb + opacity in [0, 1]
  double lo = 0.0, hi = 1.0;
  ScalarScale scale = ScalarScale::Linear;
  double opacityScale = 1.0;
  double unitDistance = 1.0;
  // NaN and infinite values: this colour at this opacity (per unitDistance, as the table's).
  // Opacity 0, the default, leaves them transparent; a ParaView map gives the colour (NanColor)
  // and, where it has one, the opacity (NanOpacity); --nan-color gives both.
  glm::vec3 nanColor{1.0f, 1.0f, 0.0f};
  float nanOpacity = 0.0f;

  glm::dvec4 lookup(double s) const;  // rgb + table opacity; (nanColor, nanOpacity) off-finite
  double extinction(double s) const;  // sigma(s), per world unit
  // Where a finite s falls in the table, in [0, 1] (0.5 for an empty range).
  double coordinate(double s) const;
  // The data value at table coordinate x in [0, 1]: the inverse of coordinate() inside the range.
  double valueAt(double x) const;
};

// Throws SettingError "log-scale" when the range cannot take the scale: a log scale needs
// 0 < lo <= hi.
void checkScale(const TransferFunction& tf);

// Names accepted by --colormap besides a .json file.
std::vector<std::string> builtinColormapNames();

// A transfer function from a built-in colour map name ("viridis", "cool-to-warm", "inferno",
// "plasma", "grayscale", "jet", "turbo"), one of ParaView's preset names ("Cool to Warm",
// "Viridis (matplotlib)", ...; paraview_presets.h; case ignored), or a ParaView colour-map JSON
// file (FILE.json:NAME picks a map of a preset file by its "Name"), with `entries` table
// entries. Opacity is a linear ramp 0..1 unless the JSON gives "Points". Throws sm::Error naming
// the option or file; an unknown name's error suggests the closest names.
TransferFunction makeTransferFunction(const std::string& colormap, int entries = 256);

// An opacity control point in data values (`--opacity`), as ParaView's opacity editor sets them.
struct OpacityPoint {
  double value, opacity;
};
// Replaces the table's opacity by the points' piecewise-linear interpolation, evaluated at each
// entry's data value over [tf.lo, tf.hi]: the first point's opacity below it, the last's above.
// Points must be sorted by value; equal values make a step (the later point holds from there
// on). Throws SettingError "opacity" for no points, unsorted or non-finite values, or an
// opacity outside [0, 1].
void setOpacityPoints(TransferFunction& tf, std::span<const OpacityPoint> points);

// Parses a ParaView colour map (an object, or an array of them as ParaView exports presets: the
// one whose "Name" is `preset`, or without one the first, warning when there are others) with
// "RGBPoints" (x r g b ...), optional "Points" (x opacity midpoint sharpness ...; an opacity,
// midpoint or sharpness outside [0, 1] is an error), "ColorSpace" (RGB, Lab, HSV, Diverging, Step,
// Prolab), "HSVWrap" and "NanColor". Control points are rescaled to [0, 1] and evaluated as VTK
// evaluates them (control_points.h).
TransferFunction parseParaViewColormap(const std::string& jsonText, const std::string& sourceName,
                                       int entries = 256, const std::string& preset = "");

}  // namespace sm::scene
