// sim/frame.h - the frame of every tracer (hls/frame.h) under the names sim/ uses.
#pragma once

#include "hls/frame.h"

namespace raycore::sim {

using hls::Frame;
using hls::PixelResult;
using hls::shade_pixel;

}  // namespace raycore::sim
