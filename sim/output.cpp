// sim/output.cpp - PNG (stb_image_write) and JSON output.
#include "sim/output.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace raycore::sim {

void write_png(const Frame& f, const std::string& path) {
  std::vector<unsigned char> g(f.px.size());
  for (size_t i = 0; i < f.px.size(); ++i) g[i] = f.px[i].shade;
  if (!stbi_write_png(path.c_str(), f.width, f.height, 1, g.data(), f.width))
    throw std::runtime_error("cannot write PNG '" + path + "'");
}

void make_parent(const std::string& path) {
  const auto d = std::filesystem::path(path).parent_path();
  if (!d.empty()) std::filesystem::create_directories(d);
}

void write_text(const std::string& path, const std::string& text) {
  make_parent(path);
  std::ofstream os(path);
  if (!(os << text)) throw std::runtime_error("cannot write '" + path + "'");
}

void write_doc_section(const std::string& path, const std::string& name, const std::string& body) {
  std::string doc;
  if (std::ifstream is(path); is) doc.assign(std::istreambuf_iterator<char>(is), {});
  const std::string begin = "<!-- " + name + ":begin -->", end = "<!-- " + name + ":end -->";
  const std::string sec = begin + "\n" + body + end;
  const size_t b = doc.find(begin), e = doc.find(end);
  if (b != std::string::npos && e != std::string::npos && e > b)
    doc.replace(b, e + end.size() - b, sec);
  else
    doc += "\n" + sec + "\n";
  write_text(path, doc);
}

void write_json(const nlohmann::json& j, const std::string& path) {
  std::ofstream os(path);
  if (!os) throw std::runtime_error("cannot write '" + path + "'");
  os << j.dump(2) << "\n";
  if (!os) throw std::runtime_error("error writing '" + path + "'");
}

}  // namespace raycore::sim
