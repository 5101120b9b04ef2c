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

// Creates the folder that will hold `path` (nothing when it has none).
void make_parent(const std::string& path);

// Writes a text file, creating its folder; throws on failure (naming the path).
void write_text(const std::string& path, const std::string& text);

// Puts `body` into the markdown file `path` between the lines <!-- NAME:begin --> and
// <!-- NAME:end --> (replacing what was there; appended with the marks when they are missing, the
// file created when it does not exist); throws on failure.
void write_doc_section(const std::string& path, const std::string& name, const std::string& body);

}  // namespace raycore::sim
