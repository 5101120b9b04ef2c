// sim/sweep/errormap.cpp - see errormap.h.
#include "sim/sweep/errormap.h"

#include <cmath>
#include <stdexcept>

#include <stb/stb_image_write.h>

#include "sim/reference/metrics.h"

namespace raycore::sweep {

std::vector<PixelError> classify(const sim::Frame& test, const sim::Frame& ref) {
  if (test.width != ref.width || test.height != ref.height || test.px.size() != ref.px.size())
    throw std::invalid_argument("error map: test and reference frames differ in size");
  std::vector<PixelError> c(test.px.size(), PixelError::ok);
  for (size_t i = 0; i < c.size(); ++i) {
    const auto& a = test.px[i];
    const auto& r = ref.px[i];
    const bool self = a.shadow_ray && a.tri >= 0 && a.shadow_tri == a.tri;
    if ((a.tri >= 0) != (r.tri >= 0)) {
      c[i] = PixelError::primary;
      continue;
    }
    if (a.tri < 0) continue;
    if (!(std::fabs(a.t - r.t) <= reference::kPrimaryDistanceTolerance * r.t)) {
      c[i] = PixelError::primary;
      continue;
    }
    const bool la = a.shadow_ray && a.lit, lr = r.shadow_ray && r.lit;
    if (!la && lr)
      c[i] = self ? PixelError::false_shadow_self : PixelError::false_shadow;
    else if (la && !lr)
      c[i] = PixelError::light_leak;
    else if (self)
      c[i] = PixelError::self_only;
  }
  return c;
}

std::vector<uint8_t> error_map_rgb(const sim::Frame& f, const std::vector<PixelError>& cls) {
  std::vector<uint8_t> rgb(cls.size() * 3);
  for (size_t i = 0; i < cls.size(); ++i) {
    uint8_t c[3];
    const uint8_t g = uint8_t(f.px[i].shade / 3);
    switch (cls[i]) {
      case PixelError::primary: c[0] = 255, c[1] = 230, c[2] = 0; break;
      case PixelError::false_shadow_self: c[0] = 255, c[1] = 0, c[2] = 0; break;
      case PixelError::false_shadow: c[0] = 255, c[1] = 0, c[2] = 255; break;
      case PixelError::light_leak: c[0] = 0, c[1] = 220, c[2] = 255; break;
      case PixelError::self_only: c[0] = 255, c[1] = 140, c[2] = 0; break;
      default: c[0] = c[1] = c[2] = g; break;
    }
    for (int k = 0; k < 3; ++k) rgb[i * 3 + size_t(k)] = c[k];
  }
  return rgb;
}

Window worst_window(const std::vector<PixelError>& cls, int width, int height, int w, int h) {
  w = std::min(w, width);
  h = std::min(h, height);
  // Summed-area table of error pixels.
  std::vector<uint64_t> s(size_t(width + 1) * size_t(height + 1), 0);
  auto S = [&](int x, int y) -> uint64_t& { return s[size_t(y) * size_t(width + 1) + size_t(x)]; };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelError e = cls[size_t(y) * size_t(width) + size_t(x)];
      const uint64_t v = e != PixelError::ok && e != PixelError::self_only ? 1 : 0;
      S(x + 1, y + 1) = v + S(x, y + 1) + S(x + 1, y) - S(x, y);
    }
  Window best{0, 0, w, h, 0};
  for (int y = 0; y + h <= height; ++y)
    for (int x = 0; x + w <= width; ++x) {
      const uint64_t n = S(x + w, y + h) - S(x, y + h) - S(x + w, y) + S(x, y);
      if (n > best.errors) best = {x, y, w, h, n};
    }
  return best;
}

void write_rgb_png(const std::string& path, const std::vector<uint8_t>& rgb, int width, int height) {
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    throw std::runtime_error("cannot write PNG '" + path + "'");
}

std::vector<uint8_t> crop_zoom(const std::vector<uint8_t>& rgb, int width, const Window& win, int zoom) {
  const int W = win.w * zoom, H = win.h * zoom;
  std::vector<uint8_t> out(size_t(W) * size_t(H) * 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t src = (size_t(win.y + y / zoom) * size_t(width) + size_t(win.x + x / zoom)) * 3;
      const size_t dst = (size_t(y) * size_t(W) + size_t(x)) * 3;
      for (int k = 0; k < 3; ++k) out[dst + size_t(k)] = rgb[src + size_t(k)];
    }
  return out;
}

nlohmann::json counts_json(const std::vector<PixelError>& cls) {
  uint64_t n[6] = {0, 0, 0, 0, 0, 0};
  for (auto c : cls) ++n[size_t(c)];
  return {{"primary", n[1]},        {"false_shadow_self", n[2]}, {"false_shadow_other", n[3]},
          {"light_leak", n[4]},     {"self_intersection_no_error", n[5]},
          {"error_pixels", n[1] + n[2] + n[3] + n[4]}};
}

}  // namespace raycore::sweep
