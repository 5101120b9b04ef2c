// hls/vtu.h - the viewport transfer unit (VTU): translate the scene by -c (c = the camera position
// in the format) as data comes off the memory bus, exactly the operations the hardware unit
// performs, through hls::Arith<F, R> only.
//
//   node      inner: split' = sub(split, c[axis]); leaves pass through unchanged
//   triangle  n_d' = sub(n_d, add3(c_k, mul(n_u, c_u), mul(n_v, c_v)))
//             b_d' = add3(b_d, mul(b_nu, c_u), mul(b_nv, c_v))
//             c_d' = add3(c_d, mul(c_nu, c_u), mul(c_nv, c_v))
//             n_u, n_v, b_nu, b_nv, c_nu, c_nv, k, flags and id unchanged
//   box/light x' = sub(x, c)   (box_outward: one more step outward, see below)
// Per triangle: 6 multipliers, 3 three-input adders, 1 two-input adder; per node one adder.
//
// Error against constants computed in double from pre-translated vertices (docs/image.md derives
// it): for each translated constant, |x' - exact| <= K ulp(m) + the stored constants' own
// rounding, where m is the largest magnitude among the terms of its sum.
#pragma once

#include <cstdint>
#include <stdexcept>

#include "hls/fp.h"
#include "hls/image.h"

namespace raycore::hls {

template <class F, Rounding R>
struct Vtu {
  using A = Arith<F, R>;
  uint32_t c[3] = {0, 0, 0};  // the camera position in the format

  // c = the camera position rounded once with the policy (rays then start at 0).
  static Vtu from_camera(const Vec3& cam) {
    Vtu v;
    for (int i = 0; i < 3; ++i) v.c[i] = A::from_double(cam[i]);
    return v;
  }

  uint64_t node(uint64_t raw) const {
    Node n = decode_node(raw);
    if (n.leaf()) return raw;
    n.split_or_count = A::sub(n.split_or_count, c[n.axis]);
    return (raw & ~uint64_t(0xFFFFFFFFu)) | n.split_or_count;
  }

  WaldTri<F> tri(const WaldTri<F>& t) const {
    using W = WaldTri<F>;
    const uint32_t k = t.k;
    const uint32_t u = k == 2 ? 0 : k + 1, v = k == 0 ? 2 : k - 1;
    WaldTri<F> o = t;
    const uint32_t cu = c[u], cv = c[v];
    o.c[W::ND] = A::sub(t.c[W::ND], A::add3(c[k], A::mul(t.c[W::NU], cu), A::mul(t.c[W::NV], cv)));
    o.c[W::BD] = A::add3(t.c[W::BD], A::mul(t.c[W::BNU], cu), A::mul(t.c[W::BNV], cv));
    o.c[W::CD] = A::add3(t.c[W::CD], A::mul(t.c[W::CNU], cu), A::mul(t.c[W::CNV], cv));
    return o;
  }

  // A record in place, as the fill path sees it (bytes in, bytes out).
  void tri_record(uint8_t* rec) const { encode_tri<F>(tri(decode_tri<F>(rec)), rec); }

  // The scene box, in place: x' = sub(x, c).
  void box(uint32_t lo[3], uint32_t hi[3]) const {
    for (int i = 0; i < 3; ++i) {
      lo[i] = A::sub(lo[i], c[i]);
      hi[i] = A::sub(hi[i], c[i]);
    }
  }
  // The same, then one step outward (next_down / next_up: an incrementer on the bit pattern), so
  // the translated box still contains everything the exact translation would: a correctly rounded
  // sub (either policy) is within one ulp, on the right side after the step.
  void box_outward(uint32_t lo[3], uint32_t hi[3]) const {
    box(lo, hi);
    for (int i = 0; i < 3; ++i) {
      lo[i] = A::next_down(lo[i]);
      hi[i] = A::next_up(hi[i]);
    }
  }

  // A point (the light), in place: p' = sub(p, c).
  void point(uint32_t p[3]) const {
    for (int i = 0; i < 3; ++i) p[i] = A::sub(p[i], c[i]);
  }
};

// The whole image translated: every node, every triangle record and the header's box (with
// box_outward(): a plain sub could pull a bound in by an ulp and clip geometry off the box; the
// hardware's box registers take the same outward step). Sets image_flag_vtu.
// Throws std::invalid_argument if the image's format or policy differs from the VTU's.
template <class F, Rounding R>
Image transform_image(const Image& img, const Vtu<F, R>& vtu) {
  if (img.format() != format_id<F>() || img.rounding() != R)
    throw std::invalid_argument("transform_image: the image is " +
                                std::string(format_name(img.format())) + "/" +
                                rounding_name(img.rounding()) + ", the VTU " +
                                format_name(format_id<F>()) + "/" + rounding_name(R));
  Image out = img;
  const ImageHeader h = img.header();
  uint8_t* p = out.bytes.data();
  for (uint32_t i = 0; i < h.node_count; ++i)
    detail::put_le(p + h.node_offset + size_t(i) * 8, vtu.node(img.node(i)), 8);
  for (uint32_t i = 0; i < h.tri_count; ++i)
    vtu.tri_record(p + h.tri_offset + size_t(i) * tri_record_bytes<F>());
  ImageHeader nh = h;
  vtu.box_outward(nh.box_lo, nh.box_hi);
  nh.flags = uint8_t(nh.flags | image_flag_vtu);
  nh.write(p);
  return out;
}

// The host's set-up registers of a frame, formed once for every consumer (golden tracer, cycle
// model, analyses): the camera and the light rounded once with the policy; with the VTU on, the
// light translated by the VTU and rays starting at 0, else rays starting at the camera.
// `light_stored` is the light before the VTU, in the memory image's coordinates (relative to the
// anchor): what a VTU at pin level or in RTL is given to translate at set-up, so that every view
// starts from the same register.
// `anchor` (--store anchored; 0 = world) is the point the memory image is stored relative to: the
// camera and the light are taken relative to it in double on the host, then rounded, so the VTU
// translates by camera - anchor and its hardware is unchanged.
// `offset` is what adds a datapath position back into world space (anchor + the camera, or anchor).
template <class F, Rounding R>
struct FrameSetup {
  using A = Arith<F, R>;
  Vtu<F, R> vtu;  // c = the camera in the format (relative to the anchor)
  bool vtu_on = false;
  uint32_t origin[3] = {0, 0, 0};
  uint32_t light[3] = {0, 0, 0};
  uint32_t light_stored[3] = {0, 0, 0};
  double offset[3] = {0, 0, 0};

  static FrameSetup make(const Vec3& camera, const Vec3& light_pos, bool vtu_on, const Vec3& anchor = {}) {
    FrameSetup s;
    s.vtu = Vtu<F, R>::from_camera(camera - anchor);
    s.vtu_on = vtu_on;
    for (int i = 0; i < 3; ++i) {
      s.light_stored[i] = A::from_double(light_pos[i] - anchor[i]);
      s.light[i] = s.light_stored[i];
      s.origin[i] = vtu_on ? A::zero : s.vtu.c[i];
      s.offset[i] = anchor[i] + (vtu_on ? A::to_double(s.vtu.c[i]) : 0.0);
    }
    if (vtu_on) s.vtu.point(s.light);
    return s;
  }
};

// The same, with the VTU made from a camera position in double (rounded with the image's policy).
Image transform_image(const Image& img, const Vec3& camera);

}  // namespace raycore::hls
