// sim/golden/golden.h - the golden tracer: the untimed reference for the hardware, bit for bit.
//
// It reads only the memory image plus camera and light, and computes only through the hls/ unit
// datapaths (rgu, trv, ist, hit, vtu), so the cycle model (systemc/) must produce the same frame.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "hls/fp.h"
#include "hls/hit.h"
#include "hls/image.h"
#include "hls/margins.h"
#include "hls/trace.h"
#include "scenes/scene.h"
#include "sim/frame.h"

namespace raycore::sim {

// Work done, for comparison with the cycle model and for the report.
struct TraceStats {
  uint64_t primary_rays = 0, shadow_rays = 0;
  uint64_t inner_steps = 0;  // inner-node traversal steps
  uint64_t leaf_visits = 0;
  uint64_t tri_tests = 0;
  uint64_t primary_hits = 0;
  double seconds = 0;
};

// The frame configuration and the registers derived from it live in hls/trace.h (below the cycle
// model too); their names here.
using hls::default_spawn_ulps;
using hls::frame_margins;
using hls::resolved_spawn;
using hls::spawn_uses_ulps;
using hls::TraceConfig;

Frame trace_golden(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                   const TraceConfig& cfg, TraceStats* stats = nullptr);

// The rays the hardware traced for one pixel of a golden (or cycle-model) frame, as exact numbers
// in world space: each bit pattern of the format converted exactly to double, positions moved back
// by hls::FrameSetup's offset (anchor + the camera register with the VTU on, the anchor without;
// exact in double when the anchor is 0: a sum of two format numbers fits double's 53 bits unless
// their exponents differ by more than 53 - (M + 1); with --store anchored, within 2^-53 relative).
// t along each ray is in units of its direction (as the datapath's), the interval is the ray's.
struct PixelRays {
  bool hit = false;           // the primary ray hit (frame pixel's tri >= 0)
  hls::Vec3 org, dir;         // primary ray (the rgu's)
  double tmin = 0, tmax = 0;  //   its interval (t_min register, the format's largest number)
  bool front = false;         // the hit unit's light-side decision
  bool shadow = false;        // a shadow ray was spawned (then the fields below)
  hls::Vec3 shadow_org, shadow_dir;
  double shadow_tmin = 0, shadow_tmax = 0;
  int32_t shadow_skip = -1;   // the triangle (scene index) the shadow ray skips, -1 none
};

// The ist's test of one triangle for a pixel's primary ray (HardwareRays::test): whether it hits,
// and the plane's t where the ray's interval holds it (phase 1 passed; NaN if not).
struct IstVerdict {
  bool hit = false;
  double t = std::numeric_limits<double>::quiet_NaN();
};

// Replays the rgu and the hit unit of a frame that trace_golden made from the same arguments: per
// pixel, the primary ray, and from the frame's hit (triangle, t bits) the ist's n.d and the hit
// unit's shadow ray, through the same hls/ functions (FrameSetup, rgu_primary, ist_wald,
// hit_shadow), so the rays are the golden tracer's and the cycle model's bit for bit.
class HardwareRays {
 public:
  HardwareRays(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
               const TraceConfig& cfg);
  ~HardwareRays();
  HardwareRays(const HardwareRays&) = delete;
  HardwareRays& operator=(const HardwareRays&) = delete;
  // Pixel (x, y); p is that pixel of the frame. Throws std::runtime_error if the frame's hit cannot
  // be the golden tracer's (the ist gives another t for that triangle, or the hit unit another
  // spawn decision).
  PixelRays pixel(int x, int y, const PixelResult& p) const;
  // The ist's test of triangle tri (scene index) for pixel (x, y)'s primary ray, in the hardware's
  // arithmetic (the record the datapath sees, VTU-translated with the VTU on).
  IstVerdict test(int x, int y, int32_t tri) const;

  struct Impl;

 private:
  Impl* impl_ = nullptr;
};

std::string to_string(hls::Spawn s);
hls::Spawn spawn_from_string(const std::string& s);  // throws std::invalid_argument
std::string spawn_choices();  // "none, skip-origin, ..." (every --spawn value)

}  // namespace raycore::sim
