// tb/scenes/gltf_builder.h - writes small (also deliberately broken) glTF files for the loader tests.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>
#include <vector>

namespace raycore::test {

inline std::string base64(const std::vector<uint8_t>& d) {
  static const char* tab = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < d.size(); i += 3) {
    const uint32_t n = uint32_t(d[i]) << 16 | (i + 1 < d.size() ? uint32_t(d[i + 1]) << 8 : 0) |
                       (i + 2 < d.size() ? uint32_t(d[i + 2]) : 0);
    out += tab[(n >> 18) & 63];
    out += tab[(n >> 12) & 63];
    out += i + 1 < d.size() ? tab[(n >> 6) & 63] : '=';
    out += i + 2 < d.size() ? tab[n & 63] : '=';
  }
  return out;
}

// A glTF document under construction: raw JSON plus one binary buffer, written as .gltf (data URI).
struct GltfDoc {
  nlohmann::json j = {{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;

  template <class T>
  int view(const std::vector<T>& values, int stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t off = bin.size();
    bin.resize(off + values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bin.data() + off, values.data(), values.size() * sizeof(T));
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", off}, {"byteLength", values.size() * sizeof(T)}};
    if (stride) v["byteStride"] = stride;
    j["bufferViews"].push_back(v);
    return int(j["bufferViews"].size()) - 1;
  }
  int accessor(int view_index, int component_type, size_t count, const char* type, size_t byte_offset = 0,
               bool normalized = false) {
    nlohmann::json a = {{"bufferView", view_index}, {"componentType", component_type}, {"count", count}, {"type", type}};
    if (byte_offset) a["byteOffset"] = byte_offset;
    if (normalized) a["normalized"] = true;
    j["accessors"].push_back(a);
    return int(j["accessors"].size()) - 1;
  }
  int positions(const std::vector<float>& xyz) { return accessor(view(xyz), 5126, xyz.size() / 3, "VEC3"); }
  int indices_u8(const std::vector<uint8_t>& v) { return accessor(view(v), 5121, v.size(), "SCALAR"); }
  int indices_u16(const std::vector<uint16_t>& v) { return accessor(view(v), 5123, v.size(), "SCALAR"); }
  int indices_u32(const std::vector<uint32_t>& v) { return accessor(view(v), 5125, v.size(), "SCALAR"); }
  // A mesh with one primitive; indices < 0: none; mode < 0: omitted (TRIANGLES).
  int mesh(int pos, int idx = -1, int mode = -1, const std::string& name = "") {
    nlohmann::json p = {{"attributes", {{"POSITION", pos}}}};
    if (idx >= 0) p["indices"] = idx;
    if (mode >= 0) p["mode"] = mode;
    nlohmann::json m = {{"primitives", nlohmann::json::array({p})}};
    if (!name.empty()) m["name"] = name;
    j["meshes"].push_back(m);
    return int(j["meshes"].size()) - 1;
  }
  int node(nlohmann::json n) {
    j["nodes"].push_back(std::move(n));
    return int(j["nodes"].size()) - 1;
  }
  void scene(std::vector<int> roots) { j["scenes"].push_back({{"nodes", roots}}); }

  std::string text() const {
    nlohmann::json out = j;
    if (!bin.empty() || out.contains("bufferViews"))
      out["buffers"] = nlohmann::json::array(
          {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    return out.dump(1);
  }
};

// A fresh file in a per-process temporary directory.
inline std::string temp_path(const std::string& name) {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/raycore_scenes_test_XXXXXX";
    const char* d = mkdtemp(tmpl);
    if (!d) return std::string("/tmp");
    static std::string made = d;
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(made, ec);
    });
    return made;
  }();
  return dir + "/" + name;
}

inline std::string write_file(const std::string& name, const std::string& bytes) {
  const std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return p;
}

}  // namespace raycore::test
