// hls/rgu.h - ray generation: primary rays from the camera as the hardware holds it, in tiles.
//
// The camera is a set of registers in the format, written once per frame by the host (rgu_camera:
// computed in double from the camera basis and rounded once each):
//   o     the rays' origin: the camera position (VTU off) or 0 (VTU on: the camera is the origin)
//   d00   the un-normalised direction to pixel (0, 0)'s centre: forward + right sx(0) + up sy(0)
//   dx    the step per pixel to the right: right * 2 tan(yfov/2) / h
//   dy    the step per pixel down:         -up * 2 tan(yfov/2) / h
// so that in exact arithmetic d00 + x dx + y dy is scenes::primary_direction's direction before
// its normalisation. The unit computes each ray in the format (rgu_primary): the pixel's integer
// coordinates converted exactly, p = sop(d00, -0, x, dx, y, dy) per component (d00 + x dx + y dy,
// the products exact, one rounding; until issue 27 part 4 add3(d00, mul(x, dx), mul(y, dy)),
// three roundings: sponza-paper's ray-generation errors 37 -> 25 pixels, FP24 rtz), then the
// same normalisation as the hit unit's unit shadow ray (hls/hit.h): len = sqrt(add3(p.p)),
// d = p * rcp(len), and inv = rcp(d). Normalised so that t is in world units: t_min (2^-12) and
// the reference's hit-distance metric mean the same for primary and shadow rays, and the trv's box
// clip and the ist see directions of the same magnitude as before.
//
// The tile walk (RguTiles): tiles of T x T pixels in row-major order, tile i of the frame to RTU
// i mod N, row-major within a tile, pixels outside the frame skipped. The cycle model's rgu
// (systemc/rgu.h) issues its primary rays in this order; rtl/units/rgu_walk.v is its twin.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/ray.h"

namespace raycore::hls {

// The camera registers of the rgu (numbers of the format).
struct RguCamera {
  uint32_t o[3] = {0, 0, 0};
  uint32_t d00[3] = {0, 0, 0};
  uint32_t dx[3] = {0, 0, 0};
  uint32_t dy[3] = {0, 0, 0};
};

// A pixel coordinate (a non-negative integer) in the format: exact below 2^(M+1) (frames up to
// 131072 pixels wide in FP24); rgu_camera refuses larger frames.
template <class A>
constexpr uint32_t rgu_coord(uint32_t n) {
  using F = typename A::Fmt;
  return n == 0 ? 0u : round_pack<F, A::rounding>(false, 0, uint64_t(n), false);
}

// The host's set-up, once per frame: scenes::primary_direction's camera (forward, right, up, the
// full vertical field of view yfov) for a w x h image, origin = the rays' origin in the format.
template <class A>
inline RguCamera rgu_camera(const uint32_t origin[3], const Vec3& forward, const Vec3& right,
                            const Vec3& up, double yfov, int w, int h) {
  using F = typename A::Fmt;
  if (w < 1 || h < 1 || uint64_t(w) > (uint64_t(1) << (F::man_bits + 1)) ||
      uint64_t(h) > (uint64_t(1) << (F::man_bits + 1)))
    throw std::invalid_argument("rgu: frame size must be 1 .. 2^(M+1) pixels per side");
  const double t = std::tan(yfov * 0.5);
  const double step = 2.0 * t / double(h);            // per pixel, both axes
  const double sx0 = t * double(1 - w) / double(h);   // sx at the centre of column 0
  const double sy0 = t * double(h - 1) / double(h);   // sy at the centre of row 0
  const Vec3 d00 = forward + right * sx0 + up * sy0;
  const Vec3 dx = right * step, dy = up * (-step);
  RguCamera c;
  for (int i = 0; i < 3; ++i) {
    c.o[i] = origin[i];
    c.d00[i] = A::from_double(d00[i]);
    c.dx[i] = A::from_double(dx[i]);
    c.dy[i] = A::from_double(dy[i]);
  }
  return c;
}

// A primary ray's interval: tmin (the host's register) to the format's largest number.
template <class A>
constexpr void rgu_interval(Ray& r, uint32_t tmin) {
  r.tmin = tmin;
  r.tmax = A::Fmt::max_mag;
}

// The unit's datapath: the primary ray through the centre of pixel (x, y). 3 sop, 6 mul, 1 add3,
// 1 sqrt, 4 rcp, in eight levels: the sops (two levels), squares, their sum, sqrt, rcp, the
// normalised direction, its reciprocals (rtl/units/rgu_ray.v).
template <class A>
constexpr Ray rgu_primary(const RguCamera& c, uint32_t x, uint32_t y, uint32_t tmin) {
  const uint32_t fx = rgu_coord<A>(x), fy = rgu_coord<A>(y);
  uint32_t p[3] = {0, 0, 0};
  // p = d00 + x dx + y dy with one rounding (hls::sop: the products exact; -0 an absent addend).
  for (int i = 0; i < 3; ++i)
    p[i] = A::sop(c.d00[i], uint32_t(A::Fmt::sign_mask), fx, c.dx[i], fy, c.dy[i]);
  const uint32_t len = A::sqrt(A::add3(A::mul(p[0], p[0]), A::mul(p[1], p[1]), A::mul(p[2], p[2])));
  const uint32_t rl = A::rcp(len);
  Ray r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = c.o[i];
    r.d[i] = A::mul(p[i], rl);
    r.inv[i] = A::rcp(r.d[i]);
  }
  rgu_interval<A>(r, tmin);
  return r;
}

// The tile walk of one RTU: rtu (0 .. rtus-1) of rtus, tiles of tile x tile pixels.
class RguTiles {
 public:
  RguTiles(int width, int height, int tile, int rtu, int rtus)
      : w_(width), h_(height), tile_(tile), rtu_(rtu), rtus_(rtus), tile_idx_(rtu) {
    tiles_x_ = (w_ + tile_ - 1) / tile_;
    tiles_ = tiles_x_ * ((h_ + tile_ - 1) / tile_);
    advance_to_valid();
  }
  bool done() const { return tile_idx_ >= tiles_; }
  // The walk's start-up in rtl/units/rgu_walk.v: with start in cycle 0, the first pixel is at the
  // walk's output (the datapath's input) in this cycle: start is sampled at the end of cycle 0,
  // then one cycle per subtraction dividing rtu and rtus by the tile columns, then one cycle
  // loading the first tile. The unit's first ray comes rgu_ray.v's 15 x STAGES cycles later.
  int startup() const { return std::max(rtu_, rtus_) / tiles_x_ + 2; }
  int x() const { return (tile_idx_ % tiles_x_) * tile_ + px_; }
  int y() const { return (tile_idx_ / tiles_x_) * tile_ + py_; }
  uint32_t pixel() const { return uint32_t(y()) * uint32_t(w_) + uint32_t(x()); }
  void next() {
    step();
    advance_to_valid();
  }

 private:
  bool pixel_ok() const { return x() < w_ && y() < h_; }
  void step() {
    if (++px_ == tile_) {
      px_ = 0;
      if (++py_ == tile_) {
        py_ = 0;
        tile_idx_ += rtus_;
      }
    }
  }
  void advance_to_valid() {
    while (!done() && !pixel_ok()) step();
  }

  int w_, h_, tile_, rtu_, rtus_;
  int tiles_x_ = 0, tiles_ = 0, tile_idx_ = 0, px_ = 0, py_ = 0;
};

}  // namespace raycore::hls
