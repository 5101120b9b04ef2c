// sim/analysis.cpp - see analysis.h.
#include "sim/analysis.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hls/vtu.h"

namespace raycore::sim {

HitSideStats hit_side_stats(const Frame& f, const hls::Image& image, const scenes::Camera& cam,
                            const scenes::Light& light, const TraceConfig& cfg) {
  return hls::visit_format(cfg.format, cfg.rounding, [&](auto fmt, auto rnd) {
    using F = decltype(fmt);
    constexpr hls::Rounding R = decltype(rnd)::value;
    using A = hls::Arith<F, R>;
    HitSideStats s;
    const auto setup = hls::FrameSetup<F, R>::make(cam.position, light.position, cfg.vtu, cfg.anchor);
    const uint32_t* l = setup.light;
    const double* off = setup.offset;
    hls::Image moved;
    const hls::Image* img = &image;
    if (cfg.vtu) {
      moved = hls::transform_image(image, setup.vtu);
      img = &moved;
    }
    std::vector<double> dist;
    for (const PixelResult& p : f.px) {
      if (!p.shadow_ray) continue;
      ++s.shadow_rays;
      const hls::WaldTri<F> t = img->template wald<F>(uint32_t(p.tri));
      const int k = int(t.k), u = hls::axis_u(t.k), v = hls::axis_v(t.k);
      const long double h[3] = {(long double)p.hit.x - off[0], (long double)p.hit.y - off[1],
                                (long double)p.hit.z - off[2]};
      const long double nu = A::to_double(t.c[hls::kNU]), nv = A::to_double(t.c[hls::kNV]);
      const long double fh = h[k] + nu * h[u] + nv * h[v] - (long double)A::to_double(t.c[hls::kND]);
      long double dl[3];
      for (int i = 0; i < 3; ++i) dl[i] = (long double)A::to_double(l[i]) - h[i];
      const long double dens = dl[k] + nu * dl[u] + nv * dl[v];
      const bool behind = fh * dens < 0, self = p.shadow_tri == p.tri;
      s.behind += behind;
      s.on_plane += fh == 0;
      s.self_intersections += self;
      s.self_behind += self && behind;
      const double hmax = double(std::max({std::fabs(h[0]), std::fabs(h[1]), std::fabs(h[2])}));
      if (hmax > 0) {
        int e;
        std::frexp(hmax, &e);
        dist.push_back(double(std::fabs(fh)) / std::ldexp(1.0, e - 1 - F::man_bits));
      }
    }
    if (!dist.empty()) {
      std::nth_element(dist.begin(), dist.begin() + long(dist.size() / 2), dist.end());
      s.median_plane_distance_ulps = dist[dist.size() / 2];
    }
    return s;
  });
}

nlohmann::json to_json(const HitSideStats& s) {
  return {{"shadow_rays", s.shadow_rays},
          {"hit_behind_plane", s.behind},
          {"hit_on_plane", s.on_plane},
          {"self_intersections", s.self_intersections},
          {"self_intersections_hit_behind", s.self_behind},
          {"median_plane_distance_ulps", s.median_plane_distance_ulps}};
}

}  // namespace raycore::sim
