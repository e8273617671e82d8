// What `render` and `view` do alike before their first frame, on every rank: check the job, pick
// the field, its scalar range, the camera and the frame settings. Functions that take Collectives
// are collective: every rank calls them in the same order.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "comm/reductions.h"
#include "pipeline/rank_share.h"
#include "pipeline/render_options.h"
#include "render/render_settings.h"
#include "session/frame_request.h"
#include "vk/context.h"

namespace sm::app {

// The job's field, or rank 0's first point field when none was asked for (collective).
std::string resolveField(const RenderJob& job, const mesh::UnstructuredMesh& m,
                         comm::Communicator& comm);

// A file's fields as its XML headers give them, read by rank 0 for every rank (collective): its
// cell data (io::listCellData), and, where it has some, the point fields of its first piece, so
// that a name both hold can be told apart (it reads as point data). Both empty for a file without
// cell data or without such headers (legacy .vtk, .ugrid).
struct HeaderFields {
  std::vector<std::string> points, cells;  // cells: those that are not point data too
};
HeaderFields listHeaderFields(const std::string& path, const io::ReadOptions& read,
                              comm::Communicator& comm);

// The field a job without --field renders: rank 0's first point field once loaded, or, for a file
// of cell data alone, its first cell array (read as any --field NAME). Empty: the first point
// field (resolveField). Collective.
std::string defaultCellField(const RenderJob& job, comm::Communicator& comm);

// The number of time steps of `field` that every rank with points has (collective); 0 when none
// has points. Ranks whose pieces disagree are refused, naming `path`, a rank of each count and the
// counts, as one rank reading the same pieces refuses them (io::listFieldSteps): otherwise the
// outcome would depend on how many ranks share the pieces.
uint64_t agreedStepCount(const std::string& path, const std::string& field, uint64_t mine,
                         bool hasPoints, comm::Communicator& comm);

// The job's frame in the session layer's terms, and the data set it frames.
session::FrameRequest frameRequest(const RenderJob& job);
session::DataExtent dataExtent(const RenderJob& job, const RankShare& share);

// Settings for the job's first frame (session::makeRenderSettings): camera, transfer function
// over `range` of `field` (the one shown, for messages), sample step; throws SettingError naming
// the option when a value is unusable.
render::RenderSettings makeSettings(const RenderJob& job, const RankShare& share,
                                    const std::string& field, std::pair<double, double> range);

vk::ContextOptions contextOptions(const RenderJob& job);

}  // namespace sm::app
