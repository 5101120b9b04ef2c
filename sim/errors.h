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

#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hls/image.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/golden/golden.h"
#include "sim/reference/metrics.h"
#include "sim/reference/reference.h"

namespace raycore::sim {

// The scene as the image stores it (triangle i = the record of scene triangle i; a degenerate
// record, or one whose edge functions are singular, becomes a zero-area triangle at the scene's
// first vertex of it, which no ray hits). The image must be in world space (VTU not applied) and
// hold one record per scene triangle.
// `anchor` (--store anchored) is the point the image is stored relative to: added back to every
// recovered vertex (in double), and the registers are rounded relative to it.
scenes::Scene stored_scene(const scenes::Scene& scene, const hls::Image& image, const hls::Vec3& anchor = {});

// The geometry as the datapath holds it, in world space: with the VTU on, the records translated by
// the VTU (hls::transform_image) taken as exact numbers plus FrameSetup's offset, the camera at the
// rays' origin plus the offset, the light register (translated) plus the offset; with it off, the
// stored scene. The budget traces the hardware's rays exactly against it to tell how much of
// traversal_intersection the VTU's rounding of the geometry is.
scenes::Scene datapath_scene(const scenes::Scene& scene, const hls::Image& image, const TraceConfig& cfg);

// ---- error budget by stage (issue 27) -----------------------------------------------------------
//
// Every error pixel of the total (`errors`: primary_errors + shadow_errors against the scene) is
// charged to the first stage of the pipeline at which the hardware's result departs from the exact
// one. Per pixel, partial pipelines P1..P5 take the hardware's stages up to one point and exact
// ones after it; each is judged against the exact frame P0 with the same per-pixel metric as the
// totals (reference::classify_pixel: miss/hit, 1% distance, lit/shadowed where the surface agrees):
//   P0  the reference: the ideal ray (scenes::primary_direction from the camera) traced exactly
//       against the scene, the exact shadow test from its exact hit point (the `errors` reference).
//   P1  the same against the stored scene (stored_scene: the records' constants, the camera and
//       light registers as exact numbers; the `errors_stored` reference).
//   P2  the hardware's primary ray (the rgu's origin and direction bit patterns as exact numbers,
//       its interval t_min .. the format's largest number; sim::HardwareRays) traced exactly
//       against the stored scene, with the exact shadow test from its exact hit point.
//   P3  the hardware's primary hit (triangle, t); its shadow by the exact test from the point
//       where the hardware's primary ray meets that triangle's stored plane (= P2's when the
//       triangle is P2's).
//   P4  the hardware's primary hit and light-side decision; its shadow ray as the hit unit spawned
//       it (origin, direction, interval, skipped triangle) traced exactly against the stored
//       scene: lit iff the hardware says the light is in front and no triangle is hit.
//   P5  the hardware frame.
// The pixel is charged to the first k in 1..5 whose P_k is an error (any kind) against P0:
//   1 storage, 2 ray_generation, 3 traversal_intersection (the primary ray's), 4 spawn,
//   5 traversal_intersection (the shadow ray's),
// and counted as a primary or a shadow error by its kind in the hardware frame. P5 is the
// hardware frame, so every error pixel is charged exactly once: per kind, the stages sum to the
// totals. A primary error is always charged at stage 3 or before (P3 has the hardware's primary
// result). The VTU is not a stage of its own: its rounding of the geometry shows in
// traversal_intersection (the hardware's hit against the exact trace of its ray on the untranslated
// stored scene; StageBudget::traversal_vtu_* say how much of it), its rounding of the light in
// spawn (the shadow ray's direction and length).
//
// Why double is wide enough for the "exact" traces: every input is exact in double (format
// numbers, and their sums with the offset when the anchor is 0; the stored vertices recovered in
// long double and rounded once, 2^-53 relative), and the reference decides hits with exactly
// signed edge functions on the sheared vertices and the light side with exact orient3d (the
// plane point of P3 is solved in long double). What is rounded is the vertices' translation to
// the ray origin and the shear, a few units of 2^-53 relative to the coordinates, against the
// format's rounding that the stages measure, 2^-17 (FP24) or 2^-24 (FP32) relative: 2^34 / 2^27
// times finer. So only a ray passing within a few 2^-53 of the coordinates' magnitude of an edge
// can be decided otherwise than in exact arithmetic (exactly on an edge counts as a hit, for the
// stored and the hardware's rays alike). The reference's shadow test (P0..P3) ignores occluders
// within twice its hit point's error bound (reference.h: ~1e-15 relative; by 1/|cos| more at
// grazing light); P4 traces the hardware's shadow ray with its own interval only.
enum class Stage : uint8_t { none = 0, storage, ray_generation, traversal_primary, spawn, traversal_shadow };

// What the hardware's primary hit got wrong, for an error charged to traversal_intersection by the
// primary ray (Stage::traversal_primary), against the exact trace of the same ray (P2: triangle A,
// or none) and the hardware's (B, or none), with the exact ray's hit points on them (long double):
// tol = kEdgeUlps ulps of the format at the largest coordinate of the hit point and the ray's
// origin in the hardware's frame (relative to the camera with the VTU on): the size of the
// rounding of the point o + t d the ist decides. First the hardware's own test of A for the same
// ray (HardwareRays::test): where it hits A, the error is order (at a t no smaller than B's, the
// exact ray meeting B too), silhouette (the same, but the exact ray passes outside B) or deep (A's
// leaf not tested); where it misses A, the edge cases below decide.
//   crack       A's exact hit lies within tol of an edge that A shares with another triangle N of
//               the scene (the same two vertices) that continues the surface across the edge as the
//               ray sees it (its exact plane point on N lies outside N by at most tol, or on its
//               edge: the mirror of A's, just inside), and the hardware hit neither A nor N: the ray
//               went through the seam (the lever: a watertight test, which decides a shared edge
//               once for both triangles);
//   silhouette  A's exact hit lies within tol of an edge that no other triangle shares, or whose
//               neighbours do not continue the surface for this ray (a fold: the ray meets the
//               neighbour inside too, or far outside), or B's exact plane point lies outside B by
//               at most tol or on its edge, or the hardware's test hits A at a t no smaller than
//               its t for B while the exact ray passes outside B (at any distance; since
//               2026-12-07, an order before): an outline decided at the format's precision (a
//               watertight test does not change it; exact or wider arithmetic near edges would);
//   order       the hardware's test hits A as well, at a t no smaller than its t for B, and the
//               exact ray meets B (inside or on its edges): the
//               rounding of t (to the format: a t ulp as wide as the gap between the two surfaces,
//               or the t of a plane rounded by several ulps) put B first (the lever: t precision);
//               before 2026-12-07 this was judged from the exact points (B inside, behind A by at
//               most kEdgeUlps ulps of t) after the edge cases, which took the pairs sharing an
//               edge for silhouettes or cracks;
//   deep        the rest: the hardware's test hits A before B but A's leaf was not tested (the
//               traversal's interval), or A missed / B hit farther than tol from an edge: the
//               test's rounding amplified by the triangle's shape (a sliver's edge constants scale
//               with 1 / its width) or the VTU's rounding of the geometry (with it on);
//   same        the hardware's triangle is A (the error is in t or what follows from it).
enum class TraversalKind : uint8_t { crack = 0, silhouette, order, deep, same };
inline constexpr int kTraversalKinds = 5;
inline constexpr double kEdgeUlps = 16;

// One error pixel of the budget (StageBudget::error_pixels; `raycore render|simulate --error-pixels
// FILE` writes them as CSV): where, its kind in the hardware frame, the stage charged, and what the
// primary ray's hits were. A: the exact trace of the hardware's primary ray on the stored scene (P2;
// not traced for a pixel charged to storage), B: the hardware's hit. For Stage::traversal_primary
// also the TraversalKind, t_a_hw (the hardware's own test of A for the ray: its t where it hits A)
// and the exact ray's points on A's and B's stored planes: t_b_exact (where
// the exact ray meets B's plane), edge_a / edge_b (the signed distance of those points to the
// nearest edge of A / B, world units, negative: outside) and tol (kEdgeUlps ulps at the hit point).
// NaN where not measured.
struct ErrorPixel {
  int x = 0, y = 0;
  bool primary = false;  // a primary error (else a shadow error)
  Stage stage = Stage::none;
  TraversalKind kind = TraversalKind::same;  // Stage::traversal_primary only
  bool vtu = false;                          // traversal: the VTU's geometry departs too
  int32_t tri_a = -1, tri_b = -1;
  double t_a = std::numeric_limits<double>::quiet_NaN(), t_b = std::numeric_limits<double>::quiet_NaN();
  double t_a_hw = std::numeric_limits<double>::quiet_NaN();  // the hardware's test of A: its t if it hits
  double t_b_exact = std::numeric_limits<double>::quiet_NaN();
  double edge_a = std::numeric_limits<double>::quiet_NaN(), edge_b = std::numeric_limits<double>::quiet_NaN();
  double tol = std::numeric_limits<double>::quiet_NaN();
};

struct StageCount {
  uint64_t primary = 0, shadow = 0;
  uint64_t total() const { return primary + shadow; }
};

struct StageBudget {
  StageCount storage, ray_generation, traversal_intersection, spawn;
  // traversal_intersection's shadow errors split by the ray whose hit departed (informative).
  uint64_t traversal_shadow_by_primary_ray = 0, traversal_shadow_by_shadow_ray = 0;
  // Of traversal_intersection's primary / shadow errors, those where the exact trace of the same
  // hardware ray against the datapath's geometry (datapath_scene: the VTU's translated records)
  // already departs: the VTU's rounding of the geometry, not the trv's or ist's (0 with the VTU off).
  uint64_t traversal_vtu_primary = 0, traversal_vtu_shadow = 0;
  // The errors charged to traversal_intersection by the primary ray (its primary errors and
  // traversal_shadow_by_primary_ray), by TraversalKind: crack, silhouette, order, deep, same.
  uint64_t traversal_kind[kTraversalKinds] = {};
  uint64_t primary_errors = 0, shadow_errors = 0;  // = the totals' (errors.primary_errors, shadow_errors)
  std::vector<Stage> pixel;                        // per pixel (row-major): the stage charged, none if no error
  std::vector<ErrorPixel> error_pixels;            // every error pixel, row-major
  double seconds = 0;                              // wall time (measure_errors: with the datapath scene's BVH)
};

// The budget of a hardware frame f (trace_golden's, or the cycle model's when it matches it) made
// from `image` with `cfg`, given the two reference frames (P0: the scene's, P1: the stored
// scene's), a reference built on the stored scene and (VTU on; else nullptr) one on
// datapath_scene. Throws if a pixel's hit cannot be the hardware's (HardwareRays).
StageBudget stage_budget(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                         const TraceConfig& cfg, const Frame& ref, const Frame& ref_stored,
                         const reference::Reference& stored, const reference::Reference* datapath = nullptr);

struct FrameErrors {
  reference::ErrorMetrics total;   // against the scene
  reference::ErrorMetrics stored;  // against the stored scene (arithmetic)
  bool has_stages = false;
  StageBudget stages;              // error pixels by stage (with the configuration only)
  std::string stages_note;         // why there is no budget (the frame is not the golden tracer's)
  double reference_seconds = 0;    // both references and the budget
};

// Renders both references at the frame's size and compares. `threads` as the tracers' (0: all).
FrameErrors measure_errors(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                           const hls::Vec3& anchor, int threads);
// The same and the budget by stage: f must be the frame trace_golden(image, scene.camera,
// scene.light, cfg) makes (the cycle model's when it matches).
FrameErrors measure_errors(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                           const TraceConfig& cfg);

// Adds `errors` (total), `errors_stored` (arithmetic, the same keys) and `errors_storage`
// (total - arithmetic for every count key) to a report, and `errors_by_stage` when measured:
// {"storage"|"ray_generation"|"traversal_intersection"|"spawn": {"primary", "shadow", "total"},
// traversal_intersection also "shadow_by_primary_ray", "shadow_by_shadow_ray", "vtu_primary" and
// "vtu_shadow", "primary_errors", "shadow_errors", "error_pixels", "order" (the stage names in
// pipeline order), "wall_seconds"}; {"error": why} when the frame is not the golden tracer's.
void add_errors_json(nlohmann::json& j, const FrameErrors& e, bool any_hit);
// The budget's error pixels as CSV (a header line, one line per pixel: x, y, error (primary or
// shadow), stage, kind, vtu, tri_a, t_a, tri_b, t_b, t_b_exact, edge_a, edge_b, tol; empty fields
// where not measured). Throws std::runtime_error if the file cannot be written.
void write_error_pixels(const StageBudget& b, const std::string& path);
// The same for a measured frame; throws std::runtime_error saying why when it has no budget (no
// reference: no scene triangles; a cycle-model frame that is not the golden tracer's).
void write_error_pixels(const FrameErrors& e, bool have_reference, const std::string& path);
nlohmann::json stages_json(const StageBudget& b);

// The report's two `errors` lines on stdout: total (against the scene) and arithmetic (against the
// stored scene), and the budget by stage when measured.
void print_errors(const FrameErrors& e, bool any_hit);

}  // namespace raycore::sim
