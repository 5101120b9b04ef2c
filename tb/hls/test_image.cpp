// tb/hls/test_image.cpp - memory image: node and triangle records, Wald constants, save/load and
// its errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

#include "hls/image.h"
#include "tb/hls/test_util.h"

namespace raycore::hls {
namespace {

using test::Rng;
using test::uni;

TEST(ImageNode, FieldPositions) {
  const Node n{0x3F0000u, 0x123456u, 2u};
  EXPECT_EQ(encode_node(n), 0x02123456003F0000ull);
  const Node leaf{7u, 0xABCDEFu, node_leaf_axis};
  EXPECT_EQ(encode_node(leaf), 0x03ABCDEF00000007ull);
  EXPECT_TRUE(node_is_leaf(encode_node(leaf)));
  EXPECT_FALSE(node_is_leaf(encode_node(n)));
  static_assert(decode_node(0x02123456003F0000ull).index == 0x123456u, "constexpr decode");
}

TEST(ImageNode, RoundTrip) {
  Rng r(1);
  for (int i = 0; i < 100000; ++i) {
    const Node n{uint32_t(r()), uint32_t(r()) & node_index_mask, uint32_t(r() % 4)};
    const uint64_t w = encode_node(n);
    ASSERT_EQ(w >> 58, 0u);
    const Node d = decode_node(w);
    ASSERT_EQ(d.split_or_count, n.split_or_count);
    ASSERT_EQ(d.index, n.index);
    ASSERT_EQ(d.axis, n.axis);
    ASSERT_EQ(encode_node(d), w);
  }
}

template <class F>
void tri_round_trip(IstKind kind) {
  Rng r(2);
  std::vector<uint8_t> buf(tri_record_bytes<F>(kind) + 8, 0xEE);
  for (int i = 0; i < 20000; ++i) {
    WaldTri<F> t;
    t.kind = kind;
    t.k = uint32_t(r() % 3);
    t.flags = (r() & 1) ? tri_flag_degenerate : 0u;
    for (int j = 0; j < t.count(); ++j) t.c[j] = uint32_t(r()) & F::mask;
    t.id = uint32_t(r());
    encode_tri<F>(t, buf.data());
    ASSERT_EQ(buf[tri_record_bytes<F>(kind)], 0xEE) << "wrote past the record";
    const WaldTri<F> d = decode_tri<F>(buf.data(), kind);
    ASSERT_TRUE(d == t) << "record " << i;
  }
}
TEST(ImageTri, RoundTripFp24) { tri_round_trip<FP24>(IstKind::wald); }
TEST(ImageTri, RoundTripFp32) { tri_round_trip<FP32>(IstKind::wald); }
TEST(ImageTri, RoundTripWatertightFp24) { tri_round_trip<FP24>(IstKind::watertight); }
TEST(ImageTri, RoundTripWatertightFp32) { tri_round_trip<FP32>(IstKind::watertight); }

// A watertight record: the plane of the stored triangle (n_u, n_v of its rounded vertices rounded
// once, n_d through its stored vertex A, watertight_nd), then the vertices rounded once; 48 bytes in
// FP24 with the id at 40; a shared vertex has the same bits in both triangles.
TEST(ImageTri, WatertightRecord) {
  const Tri a{Vec3{0.1, 0.2, 0.3}, Vec3{1.7, 0.25, 0.35}, Vec3{0.15, 1.9, 0.4}};
  const Tri b{a[1], a[2], Vec3{1.8, 2.0, 0.2}};
  const WaldTri<FP24> wa = make_wald<FP24, Rounding::rne>(a, 3, IstKind::watertight);
  const WaldTri<FP24> wb = make_wald<FP24, Rounding::rne>(b, 4, IstKind::watertight);
  Tri stored;
  for (size_t j = 0; j < 3; ++j)
    for (int x = 0; x < 3; ++x) stored[j][x] = to_double<FP24>(from_double<FP24, Rounding::rne>(a[j][x]));
  const WaldTri<FP24> wald = make_wald<FP24, Rounding::rne>(stored, 3);  // Wald's record of the stored triangle
  EXPECT_EQ(wa.kind, IstKind::watertight);
  EXPECT_EQ(wa.k, wald.k);
  for (int i = 0; i < 2; ++i) EXPECT_EQ(wa.c[i], wald.c[i]) << i;
  const int k = int(wa.k), u = (k + 1) % 3, v = (k + 2) % 3;
  const double nd = stored[0][k] + to_double<FP24>(wa.c[0]) * stored[0][u] + to_double<FP24>(wa.c[1]) * stored[0][v];
  EXPECT_EQ(wa.c[WaldTri<FP24>::ND], (watertight_nd<FP24, Rounding::rne>(wa)));
  EXPECT_LE(std::fabs(to_double<FP24>(wa.c[WaldTri<FP24>::ND]) - nd), std::ldexp(std::fabs(nd), -16));
  for (int j = 0; j < 3; ++j)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(wa.c[3 + 3 * j + x], (from_double<FP24, Rounding::rne>(a[size_t(j)][x])));
  for (int x = 0; x < 3; ++x) {
    EXPECT_EQ(wa.c[WaldTri<FP24>::VB + x], wb.c[WaldTri<FP24>::VA + x]);
    EXPECT_EQ(wa.c[WaldTri<FP24>::VC + x], wb.c[WaldTri<FP24>::VB + x]);
  }
  uint8_t rec[48];
  encode_tri<FP24>(wa, rec);
  EXPECT_EQ(rec[36], wa.k);
  EXPECT_EQ(rec[40], 3);
  EXPECT_TRUE(decode_tri<FP24>(rec, IstKind::watertight) == wa);
  // Degenerate (zero area): all-zero constants, the flag set.
  const Tri z{Vec3{1, 1, 1}, Vec3{2, 2, 2}, Vec3{3, 3, 3}};
  const WaldTri<FP24> wz = make_wald<FP24, Rounding::rtz>(z, 9, IstKind::watertight);
  EXPECT_TRUE(wz.degenerate());
  for (uint32_t c : wz.c) EXPECT_EQ(c, 0u);
}

TEST(ImageTri, ByteLayout) {
  WaldTri<FP24> t;
  t.k = 2;
  t.flags = tri_flag_degenerate;
  for (int i = 0; i < 9; ++i) t.c[i] = 0x010203u * uint32_t(i + 1) & FP24::mask;
  t.id = 0xA1B2C3D4u;
  uint8_t b[32];
  encode_tri<FP24>(t, b);
  EXPECT_EQ(b[0], 0x03);  // constant 0 = 0x010203, little endian
  EXPECT_EQ(b[1], 0x02);
  EXPECT_EQ(b[2], 0x01);
  EXPECT_EQ(b[27], 2 | 4);
  EXPECT_EQ(b[28], 0xD4);
  EXPECT_EQ(b[31], 0xA1);
  static_assert(tri_record_bytes<FP24>(IstKind::wald) == 32 && tri_record_bytes<FP32>(IstKind::wald) == 48, "sizes");
  WaldTri<FP32> f;
  f.k = 1;
  f.id = 0x01020304u;
  f.c[8] = 0xDEADBEEFu;
  uint8_t g[48];
  encode_tri<FP32>(f, g);
  EXPECT_EQ(g[32], 0xEF);
  EXPECT_EQ(g[35], 0xDE);
  EXPECT_EQ(g[36], 1);
  EXPECT_EQ(g[37] | g[38] | g[39], 0);
  EXPECT_EQ(g[40], 0x04);
  EXPECT_EQ(g[44] | g[45] | g[46] | g[47], 0);
}

// The constants evaluated (in double, from the rounded values) at points of the triangle give the
// barycentrics and the distance within the bound implied by rounding each constant once.
template <class F, Rounding R>
void wald_accuracy() {
  const double u = std::ldexp(1.0, R == Rounding::rtz ? -F::man_bits : -F::man_bits - 1);
  Rng r(3);
  double worst = 0;
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const double mag = std::pow(10.0, uni(r, 0, 4));
    const Tri t = test::random_tri(r, {uni(r, -mag, mag), uni(r, -mag, mag), uni(r, -mag, mag)},
                                   uni(r, 0.01, 1) * mag);
    const WaldTri<F> w = make_wald<F, R>(t, uint32_t(i));
    if (w.degenerate()) continue;
    ASSERT_EQ(w.id, uint32_t(i));
    double c[9];
    for (int j = 0; j < 9; ++j) c[j] = to_double<F>(w.c[j]);
    const int k = int(w.k), ku = (k + 1) % 3, kv = (k + 2) % 3;
    const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    ASSERT_GE(std::fabs(n[k]), std::fabs(n[ku]));
    ASSERT_GE(std::fabs(n[k]), std::fabs(n[kv]));
    for (int s = 0; s < 4; ++s) {
      double b = uni(r, 0, 1), g = uni(r, 0, 1);
      if (b + g > 1) b = 1 - b, g = 1 - g;
      const Vec3 p = t[0] + (t[1] - t[0]) * b + (t[2] - t[0]) * g;
      const double beta = c[3] * p[ku] + c[4] * p[kv] + c[5];
      const double gamma = c[6] * p[ku] + c[7] * p[kv] + c[8];
      const double slack = 1e-12 * (std::fabs(c[5]) + std::fabs(c[8]) + 1);
      const double bb =
          1.01 * u * (std::fabs(c[3] * p[ku]) + std::fabs(c[4] * p[kv]) + std::fabs(c[5])) + slack;
      const double bg =
          1.01 * u * (std::fabs(c[6] * p[ku]) + std::fabs(c[7] * p[kv]) + std::fabs(c[8])) + slack;
      ASSERT_LE(std::fabs(beta - b), bb) << "triangle " << i << " beta " << beta << " vs " << b;
      ASSERT_LE(std::fabs(gamma - g), bg) << "triangle " << i << " gamma " << gamma << " vs " << g;
      worst = std::max({worst, std::fabs(beta - b) / bb, std::fabs(gamma - g) / bg});
      // A ray from a random origin through p has t = 1.
      const Vec3 o{uni(r, -mag, mag), uni(r, -mag, mag), uni(r, -mag, mag)};
      const Vec3 d = p - o;
      const double num = c[2] - o[k] - c[0] * o[ku] - c[1] * o[kv];
      const double den = d[k] + c[0] * d[ku] + c[1] * d[kv];
      const double en = u * (std::fabs(c[2]) + std::fabs(c[0] * o[ku]) + std::fabs(c[1] * o[kv]));
      const double ed = u * (std::fabs(c[0] * d[ku]) + std::fabs(c[1] * d[kv]));
      if (std::fabs(den) <= 4 * ed) continue;  // grazing: t is ill-conditioned
      const double bt = 1.01 * (en + ed) / (std::fabs(den) - ed) + 1e-9;
      ASSERT_LE(std::fabs(num / den - 1.0), bt) << "triangle " << i << " t " << num / den;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50000);
  std::printf("worst barycentric error: %.3f of the bound\n", worst);
}
TEST(ImageWald, AccuracyFp24Rtz) { wald_accuracy<FP24, Rounding::rtz>(); }
TEST(ImageWald, AccuracyFp24Rne) { wald_accuracy<FP24, Rounding::rne>(); }
TEST(ImageWald, AccuracyFp32Rtz) { wald_accuracy<FP32, Rounding::rtz>(); }
TEST(ImageWald, AccuracyFp32Rne) { wald_accuracy<FP32, Rounding::rne>(); }

TEST(ImageWald, ExactConstantsUnitTriangle) {
  // A = (0,0,0), B = (1,0,0), C = (0,1,0): n = (0,0,1), k = 2, u = x, v = y; beta = x, gamma = y.
  const Tri t{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}};
  const WaldTri<FP24> w = make_wald<FP24, Rounding::rtz>(t, 5);
  using W = WaldTri<FP24>;
  EXPECT_EQ(w.k, 2u);
  EXPECT_EQ(w.flags, 0u);
  EXPECT_EQ(to_double<FP24>(w.c[W::NU]), 0.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::NV]), 0.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::ND]), 0.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::BNU]), 1.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::BNV]), 0.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::BD]), 0.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::CNU]), 0.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::CNV]), 1.0);
  EXPECT_EQ(to_double<FP24>(w.c[W::CD]), 0.0);
  // Shifted to z = 3 and x = 2: n_d = 3, beta = x - 2.
  const Tri s{Vec3{2, 0, 3}, Vec3{3, 0, 3}, Vec3{2, 1, 3}};
  const WaldTri<FP24> v = make_wald<FP24, Rounding::rtz>(s, 0);
  EXPECT_EQ(to_double<FP24>(v.c[W::ND]), 3.0);
  EXPECT_EQ(to_double<FP24>(v.c[W::BD]), -2.0);
  EXPECT_EQ(to_double<FP24>(v.c[W::CD]), 0.0);
}

template <class F>
void expect_degenerate_record(const WaldTri<F>& w, const char* what) {
  using W = WaldTri<F>;
  EXPECT_TRUE(w.degenerate()) << what;
  for (int i = 0; i < 9; ++i) {
    const uint32_t want = i == W::BD ? neg<F>(F::one) : 0u;
    EXPECT_EQ(w.c[i], want) << what << " constant " << i;
  }
}

TEST(ImageWald, Degenerate) {
  const double nan = std::nan("");
  const std::vector<std::pair<const char*, Tri>> cases = {
      {"point", Tri{Vec3{1, 2, 3}, Vec3{1, 2, 3}, Vec3{1, 2, 3}}},
      {"repeated vertex", Tri{Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{0, 0, 0}}},
      {"collinear", Tri{Vec3{0, 0, 0}, Vec3{1, 2, 3}, Vec3{2, 4, 6}}},
      {"sliver beyond fp24 range", Tri{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0.5, 1e-21, 0}}},
      {"NaN vertex", Tri{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, nan, 0}}},
  };
  for (const auto& [name, t] : cases) {
    expect_degenerate_record(make_wald<FP24, Rounding::rtz>(t, 0), name);
    expect_degenerate_record(make_wald<FP24, Rounding::rne>(t, 0), name);
  }
  // The sliver is fine in FP32 (constants ~1e21 < 3.4e38).
  EXPECT_FALSE((make_wald<FP32, Rounding::rne>(cases[3].second, 0).degenerate()));
  for (int i = 0; i < 3; ++i) expect_degenerate_record(make_wald<FP32, Rounding::rtz>(cases[size_t(i)].second, 0), cases[size_t(i)].first);
}

// ---- the whole image ------------------------------------------------------------------------------

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "raycore_image_" + std::to_string(::getpid()) + "_" + name;
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& b) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

// load() must fail with a message naming the file and containing `expect`.
void expect_load_error(const std::string& path, const std::string& expect) {
  try {
    Image::load(path);
    ADD_FAILURE() << "loading " << path << " succeeded; expected an error with '" << expect << "'";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(expect), std::string::npos) << "got: " << msg;
  }
}

TEST(ImageFile, HeaderAndLayout) {
  const auto tris = test::random_scene(7, 500);
  TreeStats st;
  const Image img = build_image(tris, FormatId::fp24, Rounding::rtz, {}, &st);
  const ImageHeader h = img.header();
  EXPECT_EQ(std::string(h.magic, 8), "RCIMAGE1");
  EXPECT_EQ(h.version, 1);
  EXPECT_EQ(h.exp_bits, 7);
  EXPECT_EQ(h.man_bits, 16);
  EXPECT_EQ(h.rounding, 0);
  EXPECT_EQ(h.tri_bytes, 32);
  EXPECT_EQ(h.node_offset, 64u);
  EXPECT_EQ(h.list_offset % 64, 0u);
  EXPECT_EQ(h.tri_offset % 64, 0u);
  EXPECT_GE(h.list_offset, h.node_offset + 8 * h.node_count);
  EXPECT_GE(h.tri_offset, h.list_offset + 4 * h.list_count);
  EXPECT_EQ(img.bytes.size(), h.tri_offset + 32ull * h.tri_count);
  EXPECT_EQ(h.tri_count, tris.size());
  EXPECT_EQ(h.node_count, st.nodes);
  EXPECT_EQ(h.list_count, st.refs);
  EXPECT_EQ(img.format(), FormatId::fp24);
  EXPECT_EQ(img.rounding(), Rounding::rtz);
  // Record i is scene triangle i, exactly make_wald's.
  for (uint32_t i = 0; i < h.tri_count; ++i)
    ASSERT_TRUE(img.wald<FP24>(i) == (make_wald<FP24, Rounding::rtz>(tris[i], i))) << i;
  // The box contains every vertex (rounded outward) and is tight to one ulp.
  Box sb;
  for (const Tri& t : tris)
    for (const Vec3& v : t) sb.extend(v);
  for (int a = 0; a < 3; ++a) {
    const double lo = to_double<FP24>(h.box_lo[a]), hi = to_double<FP24>(h.box_hi[a]);
    EXPECT_LE(lo, sb.lo[a]);
    EXPECT_GE(hi, sb.hi[a]);
    EXPECT_GT(to_double<FP24>(next_up<FP24>(h.box_lo[a])), sb.lo[a]);
    EXPECT_LT(to_double<FP24>(next_down<FP24>(h.box_hi[a])), sb.hi[a]);
  }
  EXPECT_NO_THROW(img.check("built image"));
  const Image b32 = build_image(tris, FormatId::fp32, Rounding::rne);
  EXPECT_EQ(b32.header().tri_bytes, 48);
  EXPECT_EQ(b32.format(), FormatId::fp32);
  EXPECT_EQ(b32.rounding(), Rounding::rne);
  EXPECT_NO_THROW(b32.check("built fp32 image"));
}

// Rounding mode raycore: header code 2, constants and splits truncated as rtz's (its conversions
// are rtz's), so the image differs from the rtz one in byte 12 alone; fp32 + raycore is refused.
TEST(ImageFile, RaycoreRounding) {
  const auto tris = test::random_scene(10, 300);
  const Image rc = build_image(tris, FormatId::fp24, Rounding::raycore);
  EXPECT_EQ(rc.bytes[12], 2u);
  EXPECT_EQ(rc.rounding(), Rounding::raycore);
  EXPECT_NO_THROW(rc.check("raycore image"));
  Image rz = build_image(tris, FormatId::fp24, Rounding::rtz);
  ASSERT_EQ(rz.bytes.size(), rc.bytes.size());
  rz.bytes[12] = 2;
  EXPECT_EQ(rz.bytes, rc.bytes);
  EXPECT_THROW(build_image(tris, FormatId::fp32, Rounding::raycore), std::invalid_argument);
  EXPECT_EQ(std::string(rounding_name(Rounding::raycore)), "raycore");
  EXPECT_EQ(rounding_from_string("raycore"), Rounding::raycore);
  Image bad = build_image(tris, FormatId::fp32, Rounding::rtz);
  bad.bytes[12] = 2;
  EXPECT_ANY_THROW(bad.check("fp32 with code 2"));
  bad.bytes[12] = 3;
  EXPECT_ANY_THROW(bad.check("code 3"));
}

TEST(ImageFile, SaveLoadRoundTrip) {
  const auto tris = test::random_scene(8, 300);
  for (FormatId f : {FormatId::fp24, FormatId::fp32}) {
    const Image img = build_image(tris, f, Rounding::rne);
    const std::string p = temp_path(std::string("rt_") + format_name(f));
    img.save(p);
    const Image back = Image::load(p);
    EXPECT_EQ(back.bytes, img.bytes);
    std::remove(p.c_str());
  }
}

TEST(ImageFile, EmptyScene) {
  const Image img = build_image({}, FormatId::fp24, Rounding::rtz);
  EXPECT_EQ(img.node_count(), 1u);
  EXPECT_TRUE(node_is_leaf(img.node(0)));
  EXPECT_EQ(decode_node(img.node(0)).split_or_count, 0u);
  EXPECT_NO_THROW(img.check("empty"));
}

TEST(ImageFile, LoadErrors) {
  const auto tris = test::random_scene(9, 200);
  const Image good = build_image(tris, FormatId::fp24, Rounding::rtz);
  const ImageHeader h = good.header();
  const std::string p = temp_path("bad");

  expect_load_error(temp_path("does_not_exist"), "cannot open");

  write_bytes(p, std::vector<uint8_t>(good.bytes.begin(), good.bytes.begin() + 10));
  expect_load_error(p, "truncated");

  write_bytes(p, std::vector<uint8_t>(good.bytes.begin(), good.bytes.end() - 1));
  expect_load_error(p, "truncated");

  auto b = good.bytes;
  b.push_back(0);
  write_bytes(p, b);
  expect_load_error(p, "trailing bytes");

  b = good.bytes;
  b[0] = 'X';
  write_bytes(p, b);
  expect_load_error(p, "bad magic");

  b = good.bytes;
  b[11] = 10;  // man_bits
  write_bytes(p, b);
  expect_load_error(p, "unsupported number format");

  b = good.bytes;
  b[28] = 128;  // node offset
  write_bytes(p, b);
  expect_load_error(p, "offsets");

  // A list entry naming a triangle that does not exist.
  b = good.bytes;
  detail::put_le(b.data() + h.list_offset, h.tri_count, 4);
  write_bytes(p, b);
  expect_load_error(p, "list entry 0");

  // The root's right child out of range, then a leaf list running past the list.
  ASSERT_FALSE(node_is_leaf(good.node(0)));
  b = good.bytes;
  Node root = decode_node(good.node(0));
  root.index = h.node_count;
  detail::put_le(b.data() + 64, encode_node(root), 8);
  write_bytes(p, b);
  expect_load_error(p, "right child");

  uint32_t leaf = 0;
  while (!node_is_leaf(good.node(leaf))) ++leaf;
  b = good.bytes;
  Node ln = decode_node(good.node(leaf));
  ln.split_or_count = h.list_count + 1;
  detail::put_le(b.data() + 64 + 8 * leaf, encode_node(ln), 8);
  write_bytes(p, b);
  expect_load_error(p, "leaf list");

  // An inner node turned into a leaf leaves its subtree unreachable.
  b = good.bytes;
  detail::put_le(b.data() + 64, encode_node(Node{0, 0, node_leaf_axis}), 8);
  write_bytes(p, b);
  expect_load_error(p, "not reachable");

  // Reserved node bits, and a triangle record with k = 3.
  b = good.bytes;
  b[64 + 7] |= 0x80;
  write_bytes(p, b);
  expect_load_error(p, "reserved bits");

  b = good.bytes;
  b[h.tri_offset + 27] = 3;
  write_bytes(p, b);
  expect_load_error(p, "k = 3");

  std::remove(p.c_str());
}

TEST(ImageFile, FormatNames) {
  EXPECT_EQ(format_from_string("fp24"), FormatId::fp24);
  EXPECT_EQ(format_from_string("fp32"), FormatId::fp32);
  EXPECT_STREQ(format_name(FormatId::fp32), "fp32");
  EXPECT_THROW(format_from_string("fp16"), std::invalid_argument);
  EXPECT_EQ(rounding_from_string("rne"), Rounding::rne);
  EXPECT_STREQ(rounding_name(Rounding::rtz), "rtz");
  EXPECT_THROW(rounding_from_string("up"), std::invalid_argument);
}

}  // namespace
}  // namespace raycore::hls
