// sim/errors.h - the error metrics of a hardware frame, split into what storage costs and what the
// datapath costs (issue 15).
//
// Two double-precision references judge every frame:
// - the scene (total error; the report's `errors` block): the scene's double vertices, camera and
//   light, as every tracer starts from;
// - the stored scene (arithmetic error; `errors_stored`): the geometry exactly as the memory image
//   stores it - each triangle recovered from its record's Wald constants taken as exact numbers
//   (the plane and the two edge functions meet in the three vertices: a 2 x 2 solve in long
//   double, ~1e-19 relative, far below any format's ulp), and the camera and light as the host's
//   registers hold them (rounded once to the format). With --store anchored, relative to the
//   anchor (so storage error shrinks with the coordinates the image holds). Nothing the datapath computes is in it, so
//   what remains against it is the datapath's own error (the VTU included), and
//   storage = total - arithmetic (`errors_storage`, per count).
// The primary rays are scenes::primary_direction's in both (the reference's own rays).
#pragma once

#include <nlohmann/json.hpp>

#include "hls/image.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/reference/metrics.h"

namespace raycore::sim {

// The scene as the image stores it (triangle i = the record of scene triangle i; a degenerate
// record, or one whose edge functions are singular, becomes a zero-area triangle at the scene's
// first vertex of it, which no ray hits). The image must be in world space (VTU not applied) and
// hold one record per scene triangle.
// `anchor` (--store anchored) is the point the image is stored relative to: added back to every
// recovered vertex (in double), and the registers are rounded relative to it.
scenes::Scene stored_scene(const scenes::Scene& scene, const hls::Image& image, const hls::Vec3& anchor = {});

struct FrameErrors {
  reference::ErrorMetrics total;   // against the scene
  reference::ErrorMetrics stored;  // against the stored scene (arithmetic)
  double reference_seconds = 0;    // both references
};

// Renders both references at the frame's size and compares. `threads` as the tracers' (0: all).
FrameErrors measure_errors(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                           const hls::Vec3& anchor, int threads);

// Adds `errors` (total), `errors_stored` (arithmetic, the same keys) and `errors_storage`
// (total - arithmetic for every count key) to a report.
void add_errors_json(nlohmann::json& j, const FrameErrors& e, bool any_hit);

// The report's two `errors` lines on stdout: total (against the scene) and arithmetic (against the
// stored scene).
void print_errors(const FrameErrors& e, bool any_hit);

}  // namespace raycore::sim
