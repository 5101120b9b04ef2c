// sim/sweep/errormap.h - error maps (the paper's Figure 8 idea): a frame against the
// double-precision reference, every pixel classified as metrics.h defines the error metrics, drawn
// in colour over the dimmed frame, plus an enlarged crop of the window with the most errors.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hls/geom.h"
#include "sim/frame.h"

namespace raycore::sweep {

// Per pixel, the first that applies (the same order and definitions as compute_errors).
enum class PixelError : uint8_t {
  ok,
  primary,            // hit vs miss, miss vs hit, or distance > 1%
  false_shadow_self,  // false shadow from a self-intersection
  false_shadow,       // other false shadow (acne from a neighbour, or no shadow ray)
  light_leak,
  self_only,          // a self-intersection where the reference is shadowed too (no pixel error)
};

std::vector<PixelError> classify(const sim::Frame& test, const sim::Frame& ref);

// Colours: primary yellow, false shadow (self) red, false shadow (other) magenta, light leak
// cyan, self-intersection without a pixel error orange; other pixels grey at a third of the frame's
// shade.
std::vector<uint8_t> error_map_rgb(const sim::Frame& test, const std::vector<PixelError>& cls);

struct Window {
  int x = 0, y = 0, w = 0, h = 0;
  uint64_t errors = 0;
};
// The w x h window (clipped to the frame) with the most pixel errors (not self_only), top-left
// first on ties.
Window worst_window(const std::vector<PixelError>& cls, int width, int height, int w, int h);

// Writes rgb (width x height x 3) as PNG; with `zoom` > 1 only `win`, each pixel zoom x zoom.
void write_rgb_png(const std::string& path, const std::vector<uint8_t>& rgb, int width, int height);
std::vector<uint8_t> crop_zoom(const std::vector<uint8_t>& rgb, int width, const Window& win, int zoom);

nlohmann::json counts_json(const std::vector<PixelError>& cls);

}  // namespace raycore::sweep
