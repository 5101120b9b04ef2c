// hls/trace.h - the configuration of a frame that every hardware model shares (the golden tracer,
// the cycle model): number format, VTU, store, spawn, margins, size; and the spawn and margin
// registers derived from it. Below sim/ and systemc/, which both use it.
#pragma once

#include <cstdint>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/hit.h"
#include "hls/image.h"
#include "hls/margins.h"

namespace raycore::hls {

struct TraceConfig {
  FormatId format = FormatId::fp24;
  Rounding rounding = Rounding::rtz;
  bool vtu = false;
  // --store: the point the memory image is stored relative to (world: 0; anchored: the scene's box
  // centre, chosen on the host in double by sim::prepare). See hls::FrameSetup.
  bool anchored = false;
  Vec3 anchor;
  SpawnParams spawn;     // strategy and (ulp_offset) its ulps
  double tmin = 1.0 / 4096;   // 2^-12, RayCore's
  // Watertightness margins (hls/margins.h; --bary-margin, --trv-widen): the ist accepts beta,
  // gamma >= -bary_margin and beta + gamma <= 1 + bary_margin; the trv widens its intervals by
  // trv_widen ulps. 0 and 0: none (today's frames bit for bit).
  double bary_margin = 0;
  int32_t trv_widen = 0;
  // --ist: the intersection test and so the image's triangle records (hls/wald.h, hls/ist.h):
  // Wald's (with the margins above), or the watertight test (no margins: it needs none).
  IstKind ist = IstKind::wald;
  int width = 800, height = 480;
  int threads = 0;            // 0: all hardware threads
};

// Default ulps for ulp_offset when SpawnParams::ulps is 0: Waechter & Binder's 256 FP32 ulps,
// scaled to the format's precision (2 ulps for FP24).
inline int32_t default_spawn_ulps(FormatId f) {
  // 256 FP32 ulps = 256 * 2^-23 relative = 2 * 2^-16: two FP24 ulps.
  return f == FormatId::fp24 ? 2 : 256;
}

// The default ulps of a strategy when SpawnParams::ulps is 0: default_spawn_ulps(f) for
// ulp_offset and skip_offset, 4 for skip_slab (a slab of 4 ulps of the hit point in any format),
// 1 for skip_back (the back-off), 0 for the others (unused).
inline int32_t default_spawn_ulps(FormatId f, Spawn s) {
  switch (s) {
    case Spawn::ulp_offset:
    case Spawn::skip_offset:
      return default_spawn_ulps(f);
    case Spawn::skip_slab:
      return 4;
    case Spawn::skip_back:
      return 1;  // ulps of the hit point: the format's own rounding, whatever the precision
    default:
      return 0;
  }
}

// Whether a strategy reads SpawnParams::ulps (ulp_offset, skip_offset, skip_slab, skip_back).
inline bool spawn_uses_ulps(Spawn s) {
  return s == Spawn::ulp_offset || s == Spawn::skip_offset || s == Spawn::skip_slab || s == Spawn::skip_back;
}

// The ist / trv margin registers of cfg for the arithmetic A (make_margins; throws
// std::invalid_argument on a negative or non-finite margin or a widening outside 0..64).
template <class A>
Margins frame_margins(const TraceConfig& cfg) {
  return make_margins<A>(cfg.bary_margin, cfg.trv_widen);
}

// cfg.spawn with the default ulps filled in (the spawn parameters every model uses).
inline SpawnParams resolved_spawn(const TraceConfig& cfg) {
  SpawnParams sp = cfg.spawn;
  if (sp.ulps == 0) sp.ulps = default_spawn_ulps(cfg.format, sp.spawn);
  return sp;
}

}  // namespace raycore::hls
