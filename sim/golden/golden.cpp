// sim/golden/golden.cpp - the golden tracer (see golden.h).
#include "sim/golden/golden.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

#include "hls/ist.h"
#include "hls/rgu.h"
#include "hls/trv.h"
#include "hls/vtu.h"

namespace raycore::sim {
namespace {

constexpr int kStackDepth = 64;  // pbrt's fixed kd-tree stack; the image's depth is checked

struct NodeD {
  uint32_t split_or_count, index, axis;
};

template <class A>
class Tracer {
  using F = typename A::Fmt;

 public:
  Tracer(const hls::Image& img, const hls::Margins& m) : m_(m) {
    const auto h = img.header();
    nodes_.resize(h.node_count);
    for (uint32_t i = 0; i < h.node_count; ++i) {
      const hls::Node n = hls::decode_node(img.node(i));
      nodes_[i] = {n.split_or_count, n.index, n.axis};
    }
    lists_.resize(h.list_count);
    for (uint32_t i = 0; i < h.list_count; ++i) lists_[i] = img.list(i);
    tris_.resize(h.tri_count);
    for (uint32_t i = 0; i < h.tri_count; ++i) tris_[i] = img.template wald<F>(i);
    img.box(lo_, hi_);
    if (depth() >= kStackDepth)
      throw std::runtime_error("kd-tree deeper than the traversal stack (" +
                               std::to_string(kStackDepth) + ")");
  }

  struct Hit {
    bool found = false;
    uint32_t t = 0;
    uint32_t tri = 0;  // index into the triangle array
    uint32_t den = 0;
    uint32_t tk = 0;   // t as the closest-hit key (hls::KeyFormat): what the compares see
  };

  // Closest hit in (r.tmin, r.tmax), skipping triangle id skip_id; with any_hit, the closest hit
  // of the first leaf that has one (the walk ends there).
  Hit trace(const hls::Ray& r, uint32_t skip_id, TraceStats& st, bool any_hit = false) const {
    Hit best;
    uint32_t tnear, tfar;
    if (nodes_.empty() || !hls::trv_clip_box<A>(lo_, hi_, r, tnear, tfar, m_.widen_ulps)) return best;
    struct Entry {
      uint32_t node, tnear, tfar;
    };
    std::array<Entry, kStackDepth> stack;
    int sp = 0;
    uint32_t tmax = hls::t_key<F>(r.tmax);  // a key: the ray's tmax, then the best hit's
    uint32_t node = 0;
    for (;;) {
      const NodeD& nd = nodes_[node];
      if (nd.axis != 3) {
        ++st.inner_steps;
        const hls::SplitStep s = hls::trv_split<A>(nd.split_or_count, nd.axis, r, tnear, tfar,
                                                           m_.widen_ulps);
        const uint32_t first = s.below_first ? node + 1 : nd.index;
        const uint32_t second = s.below_first ? nd.index : node + 1;
        if (s.visit == hls::Visit::first) {
          node = first;
        } else if (s.visit == hls::Visit::second) {
          node = second;
        } else {
          stack[size_t(sp++)] = {second, s.tsplit, tfar};
          node = first;
          tfar = s.tsplit;
        }
        continue;
      }
      ++st.leaf_visits;
      for (uint32_t i = 0; i < nd.split_or_count; ++i) {
        const uint32_t ti = lists_[nd.index + i];
        const auto& tri = tris_[ti];
        if (tri.id == skip_id) continue;
        ++st.tri_tests;
        const hls::IstOut o = hls::ist_test_key<A>(tri, r.o, r.d, r.tmin, tmax, m_);
        if (o.exit == hls::IstExit::hit) {
          best = {true, o.t, ti, o.den, o.tk};
          tmax = o.tk;
        }
      }
      if (best.found && (any_hit || !hls::key_lt<F>(hls::t_key<F>(tfar), best.tk))) break;  // the hit lies in this cell
      for (;;) {
        if (sp == 0) return best;
        const Entry e = stack[size_t(--sp)];
        if (best.found && hls::key_lt<F>(best.tk, hls::t_key<F>(e.tnear))) continue;  // beyond the hit: skip
        node = e.node;
        tnear = e.tnear;
        tfar = e.tfar;
        break;
      }
    }
    return best;
  }

  const hls::WaldTri<F>& tri(uint32_t i) const { return tris_[i]; }

 private:
  int depth() const {
    int maxd = 0;
    std::vector<std::pair<uint32_t, int>> pending{{0u, 0}};
    if (nodes_.empty()) return 0;
    while (!pending.empty()) {
      const auto [n, d] = pending.back();
      pending.pop_back();
      maxd = std::max(maxd, d);
      if (nodes_[n].axis != 3) {
        pending.push_back({n + 1, d + 1});
        pending.push_back({nodes_[n].index, d + 1});
      }
    }
    return maxd;
  }

  hls::Margins m_;
  std::vector<NodeD> nodes_;
  std::vector<uint32_t> lists_;
  std::vector<hls::WaldTri<F>> tris_;
  uint32_t lo_[3], hi_[3];
};

template <class A>
Frame trace_t(const hls::Image& image_in, const scenes::Camera& cam, const scenes::Light& light,
              const TraceConfig& cfg, TraceStats* stats_out) {
  using F = typename A::Fmt;
  constexpr hls::Rounding R = A::rounding;
  const auto t0 = std::chrono::steady_clock::now();
  const auto setup = hls::FrameSetup<F, R>::make(cam.position, light.position, cfg.vtu, cfg.anchor);
  const uint32_t* origin = setup.origin;
  const uint32_t* l = setup.light;
  const double* offset = setup.offset;
  const hls::Image* img = &image_in;
  hls::Image moved;
  if (cfg.vtu) {
    moved = hls::transform_image(image_in, setup.vtu);
    img = &moved;
  }
  const Tracer<A> tracer(*img, frame_margins<A>(cfg));
  const uint32_t tmin = A::from_double(cfg.tmin);
  const hls::SpawnParams sp = resolved_spawn(cfg);
  const hls::RguCamera rgu_cam =
      hls::rgu_camera<A>(origin, cam.forward, cam.right, cam.up, cam.yfov, cfg.width, cfg.height);

  Frame f;
  f.width = cfg.width;
  f.height = cfg.height;
  f.px.resize(size_t(cfg.width) * size_t(cfg.height));
  int nthreads = cfg.threads > 0 ? cfg.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  nthreads = std::min(nthreads, cfg.height);
  std::vector<TraceStats> st(static_cast<size_t>(nthreads));

  auto work = [&](int tid) {
    TraceStats& s = st[size_t(tid)];
    for (int y = tid; y < cfg.height; y += nthreads) {
      for (int x = 0; x < cfg.width; ++x) {
        const hls::Ray pr = hls::rgu_primary<A>(rgu_cam, uint32_t(x), uint32_t(y), tmin);
        ++s.primary_rays;
        PixelResult& p = f.px[size_t(y) * size_t(cfg.width) + size_t(x)];
        const auto h = tracer.trace(pr, ~0u, s);
        if (!h.found) {
          p.shade = shade_pixel(false, false, 0);
          continue;
        }
        ++s.primary_hits;
        const auto& tri = tracer.tri(h.tri);
        p.tri = int32_t(tri.id);
        p.t_bits = h.t;
        p.t = A::to_double(h.t);
        const hls::HitTri ht{tri.id, tri.k, tri.c[hls::kNU], tri.c[hls::kNV], tri.c[hls::kND], h.den};
        const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, h.t, ht, l, tmin, sp);
        p.hit = {A::to_double(ss.h[0]) + offset[0], A::to_double(ss.h[1]) + offset[1],
                 A::to_double(ss.h[2]) + offset[2]};
        double cosl = 0;
        p.front = ss.front;
        if (ss.spawn) {
          ++s.shadow_rays;
          p.shadow_ray = true;
          const auto sh = tracer.trace(ss.ray, ss.skip_id, s, sp.any_hit);
          p.lit = ss.front && !sh.found;
          p.shadow_tri = sh.found ? int32_t(tracer.tri(sh.tri).id) : -1;
          const double nu = A::to_double(tri.c[hls::kNU]), nv = A::to_double(tri.c[hls::kNV]);
          double l2 = 0;
          for (int i = 0; i < 3; ++i) l2 += A::to_double(ss.ray.d[i]) * A::to_double(ss.ray.d[i]);
          cosl = std::fabs(A::to_double(ss.dens)) / std::sqrt((1 + nu * nu + nv * nv) * l2);
        }
        p.shade = shade_pixel(true, p.lit, cosl);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < nthreads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  if (stats_out) {
    TraceStats tot;
    for (const auto& s : st) {
      tot.primary_rays += s.primary_rays;
      tot.shadow_rays += s.shadow_rays;
      tot.inner_steps += s.inner_steps;
      tot.leaf_visits += s.leaf_visits;
      tot.tri_tests += s.tri_tests;
      tot.primary_hits += s.primary_hits;
    }
    tot.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *stats_out = tot;
  }
  return f;
}

}  // namespace

struct HardwareRays::Impl {
  virtual ~Impl() = default;
  virtual PixelRays pixel(int x, int y, const PixelResult& p) const = 0;
  virtual IstVerdict test(int x, int y, int32_t tri) const = 0;
};

namespace {

template <class A>
class RaysT final : public HardwareRays::Impl {
  using F = typename A::Fmt;
  static constexpr hls::Rounding R = A::rounding;

 public:
  RaysT(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light, const TraceConfig& cfg)
      : setup_(hls::FrameSetup<F, R>::make(cam.position, light.position, cfg.vtu, cfg.anchor)),
        margins_(frame_margins<A>(cfg)),
        tmin_(A::from_double(cfg.tmin)),
        sp_(resolved_spawn(cfg)),
        cam_(hls::rgu_camera<A>(setup_.origin, cam.forward, cam.right, cam.up, cam.yfov, cfg.width, cfg.height)) {
    // The records as the datapath sees them (VTU-translated as trace_t does), by scene index.
    const hls::Image moved = cfg.vtu ? hls::transform_image(image, setup_.vtu) : hls::Image{};
    const hls::Image& img = cfg.vtu ? moved : image;
    const uint32_t n = img.tri_count();
    for (uint32_t i = 0; i < n; ++i) {
      const hls::WaldTri<F> w = img.template wald<F>(i);
      if (w.id >= tris_.size()) tris_.resize(size_t(w.id) + 1);
      tris_[w.id] = w;
    }
  }

  PixelRays pixel(int x, int y, const PixelResult& p) const override {
    PixelRays out;
    const hls::Ray pr = hls::rgu_primary<A>(cam_, uint32_t(x), uint32_t(y), tmin_);
    world_ray(pr, out.org, out.dir, out.tmin, out.tmax);
    if (p.tri < 0) return out;
    out.hit = true;
    if (size_t(p.tri) >= tris_.size())
      throw std::runtime_error("hardware rays: pixel's triangle " + std::to_string(p.tri) + " has no record");
    const hls::WaldTri<F>& tri = tris_[size_t(p.tri)];
    const hls::IstOut o = hls::ist_test<A>(tri, pr.o, pr.d, pr.tmin, pr.tmax, margins_);
    if (o.t != p.t_bits)
      throw std::runtime_error("hardware rays: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                               "): the ist gives another t for its triangle than the frame holds");
    const hls::HitTri ht{tri.id, tri.k, tri.c[hls::kNU], tri.c[hls::kNV], tri.c[hls::kND], o.den};
    const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, o.t, ht, setup_.light, tmin_, sp_);
    if (ss.spawn != p.shadow_ray || ss.front != p.front)
      throw std::runtime_error("hardware rays: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                               "): the hit unit decides another spawn than the frame holds");
    out.front = ss.front;
    out.shadow = ss.spawn;
    if (!ss.spawn) return out;
    world_ray(ss.ray, out.shadow_org, out.shadow_dir, out.shadow_tmin, out.shadow_tmax);
    out.shadow_skip = ss.skip_id == ~0u ? -1 : int32_t(ss.skip_id);
    return out;
  }

  IstVerdict test(int x, int y, int32_t tri) const override {
    if (tri < 0 || size_t(tri) >= tris_.size())
      throw std::runtime_error("hardware rays: triangle " + std::to_string(tri) + " has no record");
    const hls::Ray pr = hls::rgu_primary<A>(cam_, uint32_t(x), uint32_t(y), tmin_);
    const hls::IstOut o = hls::ist_test<A>(tris_[size_t(tri)], pr.o, pr.d, pr.tmin, pr.tmax, margins_);
    IstVerdict v;
    v.hit = o.exit == hls::IstExit::hit;
    if (o.exit != hls::IstExit::distance) v.t = hls::to_double<hls::KeyFormat<F>>(o.tk);  // as compared
    return v;
  }

 private:
  void world_ray(const hls::Ray& r, hls::Vec3& org, hls::Vec3& dir, double& tmin, double& tmax) const {
    for (int i = 0; i < 3; ++i) {
      org[i] = A::to_double(r.o[i]) + setup_.offset[i];
      dir[i] = A::to_double(r.d[i]);
    }
    tmin = A::to_double(r.tmin);
    tmax = A::to_double(r.tmax);
  }

  hls::FrameSetup<F, R> setup_;
  hls::Margins margins_;
  uint32_t tmin_;
  hls::SpawnParams sp_;
  hls::RguCamera cam_;
  std::vector<hls::WaldTri<F>> tris_;
};

}  // namespace

HardwareRays::HardwareRays(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                           const TraceConfig& cfg) {
  if (image.format() != cfg.format || image.rounding() != cfg.rounding)
    throw std::invalid_argument("hardware rays: memory image format/rounding differ from the configuration");
  if (image.vtu_applied()) throw std::invalid_argument("hardware rays: the image is VTU-translated already");
  impl_ = hls::visit_format(cfg.format, cfg.rounding, [&](auto f, auto r) -> Impl* {
    using A = hls::Arith<decltype(f), decltype(r)::value>;
    return new RaysT<A>(image, cam, light, cfg);
  });
}

HardwareRays::~HardwareRays() { delete impl_; }

PixelRays HardwareRays::pixel(int x, int y, const PixelResult& p) const { return impl_->pixel(x, y, p); }
IstVerdict HardwareRays::test(int x, int y, int32_t tri) const { return impl_->test(x, y, tri); }

std::string to_string(hls::Spawn s) {
  switch (s) {
    case hls::Spawn::none: return "none";
    case hls::Spawn::skip_origin: return "skip-origin";
    case hls::Spawn::ulp_offset: return "ulp-offset";
    case hls::Spawn::error_bound: return "error-bound";
    case hls::Spawn::skip_offset: return "skip-offset";
    case hls::Spawn::skip_slab: return "skip-slab";
    case hls::Spawn::skip_back: return "skip-back";
  }
  return "?";
}

hls::Spawn spawn_from_string(const std::string& s) {
  if (s == "none") return hls::Spawn::none;
  if (s == "skip-origin") return hls::Spawn::skip_origin;
  if (s == "ulp-offset") return hls::Spawn::ulp_offset;
  if (s == "error-bound") return hls::Spawn::error_bound;
  if (s == "skip-offset") return hls::Spawn::skip_offset;
  if (s == "skip-slab") return hls::Spawn::skip_slab;
  if (s == "skip-back") return hls::Spawn::skip_back;
  throw std::invalid_argument("unknown spawn strategy '" + s + "' (" + spawn_choices() + ")");
}

std::string spawn_choices() {
  return "none, skip-origin, ulp-offset, error-bound, skip-offset, skip-slab, skip-back";
}

Frame trace_golden(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                   const TraceConfig& cfg, TraceStats* stats) {
  using R = hls::Rounding;
  if (cfg.width <= 0 || cfg.height <= 0) throw std::invalid_argument("image size must be positive");
  if (image.format() != cfg.format || image.rounding() != cfg.rounding)
    throw std::invalid_argument("memory image format/rounding differ from the trace configuration");
  if (cfg.format == hls::FormatId::fp24) {
    if (cfg.rounding == R::rtz) return trace_t<hls::Arith<hls::FP24, R::rtz>>(image, cam, light, cfg, stats);
    if (cfg.rounding == R::raycore)
      return trace_t<hls::Arith<hls::FP24, R::raycore>>(image, cam, light, cfg, stats);
    return trace_t<hls::Arith<hls::FP24, R::rne>>(image, cam, light, cfg, stats);
  }
  hls::check_format_rounding(cfg.format, cfg.rounding);  // fp32 + raycore: refused
  if (cfg.rounding == R::rtz) return trace_t<hls::Arith<hls::FP32, R::rtz>>(image, cam, light, cfg, stats);
  return trace_t<hls::Arith<hls::FP32, R::rne>>(image, cam, light, cfg, stats);
}

}  // namespace raycore::sim
