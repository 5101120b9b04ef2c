// hls/vtu.h - the viewport transfer unit (VTU): translate the scene by -c (c = the camera position
// in the format) as data comes off the memory bus, exactly the operations the hardware unit
// performs, through hls::Arith<F, R> only.
//
// Every translated value is one sop (hls/fp.h: a + b + x1*y1 + x2*y2, each product exact, the sum
// in a window of 3M+7 bits, rounded once), the unit's only operator:
//   node      inner: split' = sop(split, -c[axis], -0*0, -0*0); leaves pass through unchanged
//   triangle  n_d' = sop(n_d, -c_k, -n_u * c_u, -n_v * c_v)
//             b_d' = sop(b_d, -0, b_nu * c_u, b_nv * c_v)
//             c_d' = sop(c_d, -0, c_nu * c_u, c_nv * c_v)
//             n_u, n_v, b_nu, b_nv, c_nu, c_nv, k, flags and id unchanged
//   watertight each vertex coordinate x' = sop(x, -c[axis], -0*0, -0*0) (9 shifts), then the plane
//   record     through the shifted A: n_d' = sop(A'_k, -0, n_u * A'_u, n_v * A'_v) (hls/wald.h,
//              watertight_nd: the builder's n_d on the translated vertices; a second sop after
//              A's shifts, which vtu.v does not have: it refuses watertight records); n_u, n_v,
//              k, flags and id unchanged (a shared vertex shifts to the same bits in every
//              triangle: the translated mesh stays closed)
//   box/light x' = sop(x, -c, -0*0, -0*0)   (box_outward: one more step outward, see below)
// (-0 and -0*0 are absent terms: they leave an all-zero sum's sign to the others.) For rtz and
// rne a two-term sop is sub(x, c) bit for bit (tb/fp/test_fp_sop.cpp, Sop.*TwoTermsAreAdd); for
// raycore it is the exact difference truncated once (the VTU is this project's unit, not
// RayCore's).
// Per triangle: 3 sops (6 exact products, no intermediate rounding); per node one (rtl/units/vtu.v
// translates four nodes per cycle: three through its sops, one through a subtractor, which is the
// two-term sop bit for bit under every policy: raycore's sop truncates as rtz's sub does).
//
// Why one rounding: in world coordinates far from the origin the terms of n_d' are large and
// cancel (far at 10^5: products near 7 * 10^4, where the FP24 ulp is 1), so a rounded product or
// partial sum loses the small offset that remains; here the offsets err by their own final
// rounding plus at most 2^-(3M+3) of the largest term (hls/fp.h, sop). docs/image.md derives the
// bound against constants computed in double from pre-translated vertices.
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

  // x - cam through the unit's operator: sop(x, -cam, -0*0, -0*0).
  static uint32_t shift(uint32_t x, uint32_t cam) {
    return A::sop(x, A::neg(cam), F::sign_mask, 0, F::sign_mask, 0);
  }

  uint64_t node(uint64_t raw) const {
    Node n = decode_node(raw);
    if (n.leaf()) return raw;
    n.split_or_count = shift(n.split_or_count, c[n.axis]);
    return (raw & ~uint64_t(0xFFFFFFFFu)) | n.split_or_count;
  }

  WaldTri<F> tri(const WaldTri<F>& t) const {
    using W = WaldTri<F>;
    const uint32_t k = t.k;
    const uint32_t u = k == 2 ? 0 : k + 1, v = k == 0 ? 2 : k - 1;
    WaldTri<F> o = t;
    const uint32_t cu = c[u], cv = c[v];
    constexpr uint32_t absent = F::sign_mask;  // -0
    if (t.kind == IstKind::watertight) {
      for (int i = W::VA; i < W::VA + 9; ++i) o.c[i] = shift(t.c[i], c[i % 3]);
      o.c[W::ND] = watertight_nd<F, R>(o);  // the plane through the shifted vertex A
      return o;
    }
    o.c[W::ND] = A::sop(t.c[W::ND], A::neg(c[k]), A::neg(t.c[W::NU]), cu, A::neg(t.c[W::NV]), cv);
    o.c[W::BD] = A::sop(t.c[W::BD], absent, t.c[W::BNU], cu, t.c[W::BNV], cv);
    o.c[W::CD] = A::sop(t.c[W::CD], absent, t.c[W::CNU], cu, t.c[W::CNV], cv);
    return o;
  }

  // A record of the given kind in place, as the fill path sees it (bytes in, bytes out).
  void tri_record(uint8_t* rec, IstKind kind) const { encode_tri<F>(tri(decode_tri<F>(rec, kind)), rec); }

  // The scene box, in place: x' = x - c (shift).
  void box(uint32_t lo[3], uint32_t hi[3]) const {
    for (int i = 0; i < 3; ++i) {
      lo[i] = shift(lo[i], c[i]);
      hi[i] = shift(hi[i], c[i]);
    }
  }
  // The same, then one step outward (next_down / next_up: an incrementer on the bit pattern), so
  // the translated box still contains everything the exact translation would: the two-term sop is
  // the exact difference rounded once (any policy), within one ulp, on the right side after the step.
  void box_outward(uint32_t lo[3], uint32_t hi[3]) const {
    box(lo, hi);
    for (int i = 0; i < 3; ++i) {
      lo[i] = A::next_down(lo[i]);
      hi[i] = A::next_up(hi[i]);
    }
  }

  // A point (the light), in place: p' = p - c (shift).
  void point(uint32_t p[3]) const {
    for (int i = 0; i < 3; ++i) p[i] = shift(p[i], c[i]);
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
    vtu.tri_record(p + h.tri_offset + size_t(i) * h.tri_bytes, img.ist_kind());
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
