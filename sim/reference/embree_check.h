// sim/reference/embree_check.h - an independent check of the reference's primary hits: the same
// camera rays traced by Embree 3 (single precision, RTC_SCENE_FLAG_ROBUST, rtcIntersect1) on the
// same triangles converted to float, compared pixel by pixel with the reference.
//
// A pixel agrees when both miss, both hit the same triangle, or both hit different triangles at
// distances within rel_tol of each other (a tie on a shared edge or a coplanar overlap). Every
// disagreement is classified:
//   embree_miss          - the reference hits, Embree misses;
//   embree_extra_hit     - Embree hits, the reference misses;
//   different_surface    - both hit, different triangles, distances differ by more than rel_tol.
// and, across those, explained where possible:
//   near_edge      - the ray passes within `edge_tol` (relative barycentric margin) of an edge of
//                    the reference's or Embree's triangle (a silhouette decided by rounding);
//   float_inputs   - Embree's answer is the exact answer for its float inputs: the watertight
//                    double test, run on the two triangles with vertices rounded to float and on
//                    the ray with origin and direction rounded to float, decides between them as
//                    Embree did (so the difference comes from rounding the scene and the ray to
//                    FP32, not from either tracer's arithmetic).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenes/scene.h"
#include "sim/frame.h"

namespace raycore::reference {

struct EmbreeDisagreement {
  int x = 0, y = 0;
  std::string cause;        // embree_miss, embree_extra_hit, different_surface
  bool near_edge = false;     // explained by an edge graze (see above)
  bool float_inputs = false;  // explained by rounding the inputs to float (see above)
  int32_t ref_tri = -1;
  double ref_t = 0;
  double ref_edge_margin = 0;     // min barycentric of the reference's hit (0 = on an edge)
  int32_t embree_tri = -1;
  double embree_t = 0;
  double embree_edge_margin = 0;  // min barycentric of Embree's triangle under the double ray
                                  // (negative: the exact ray misses it by that much)
};

struct EmbreeAgreement {
  uint64_t pixels = 0;
  uint64_t agree = 0;
  uint64_t agree_both_miss = 0, agree_same_tri = 0, agree_tie = 0;
  uint64_t disagree = 0;
  uint64_t embree_miss = 0, embree_extra_hit = 0, different_surface = 0;
  uint64_t disagree_near_edge = 0;     // disagreements explained by an edge graze
  uint64_t disagree_float_inputs = 0;  // disagreements explained by the float inputs
  double agreement_pct = 0;
  std::vector<EmbreeDisagreement> examples;  // the first max_examples, row-major order
};

struct EmbreeCheckOptions {
  int threads = 1;
  double rel_tol = 1e-4;   // relative distance tolerance of a tie
  double edge_tol = 1e-5;  // barycentric margin counted as "near an edge"
  size_t max_examples = 20;
};

// True when the library was built with Embree (else embree_check throws std::runtime_error).
bool embree_available();

// Traces the reference's primary rays (computed here) and Embree's.
EmbreeAgreement embree_check(const scenes::Scene& scene, int width, int height,
                             const EmbreeCheckOptions& opt = {});
// The same against an existing reference frame of this scene and size.
EmbreeAgreement embree_check(const scenes::Scene& scene, const sim::Frame& ref,
                             const EmbreeCheckOptions& opt = {});

nlohmann::json to_json(const EmbreeAgreement& a);

}  // namespace raycore::reference
