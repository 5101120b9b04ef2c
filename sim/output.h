// sim/output.h - what a run writes: the PNG image and the JSON report's common parts.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "sim/frame.h"

namespace raycore::sim {

// Writes the frame's grey levels as an 8-bit PNG; throws on failure (naming the path).
void write_png(const Frame& f, const std::string& path);

// Writes a JSON document (pretty, trailing newline); throws on failure.
void write_json(const nlohmann::json& j, const std::string& path);

}  // namespace raycore::sim
