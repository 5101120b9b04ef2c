// scenes/gltf.cpp - glTF 2.0 loader (on tinygltf) and writer (own GLB/JSON encoder).
//
// The loader trusts nothing tinygltf hands back: every index, offset, stride and count is checked
// here before any byte is read, so a malformed file is a SceneError, never a crash (this is what
// tb/fuzz/ exercises).
#include "scenes/gltf.h"

#include <tiny_gltf.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace raycore::scenes {
namespace {

// ---------------------------------------------------------------------------------------------
// 4x4 matrices, column-major like glTF: m[col * 4 + row].
using Mat4 = std::array<double, 16>;

Mat4 identity() {
  Mat4 m{};
  m[0] = m[5] = m[10] = m[15] = 1;
  return m;
}

Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

Vec3 transform_point(const Mat4& m, Vec3 p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

Vec3 column(const Mat4& m, int c) { return {m[c * 4 + 0], m[c * 4 + 1], m[c * 4 + 2]}; }

std::string quote(const std::string& s) { return "'" + s + "'"; }

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string stem_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = base.find_last_of('.');
  if (dot != std::string::npos && dot > 0) base = base.substr(0, dot);
  return base;
}

std::string dir_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash == 0 ? 1 : slash);
}

const char* mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return "unknown";
  }
}

size_t component_size(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

const char* component_name(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown";
  }
}

size_t num_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
  }
}

// One component at p, as a double (glTF's normalised-integer rules when `normalized`).
double decode(const uint8_t* p, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return double(f);
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(double(v) / 127.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? double(p[0]) / 255.0 : double(p[0]);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? double(v) / 65535.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
    default: return 0;
  }
}

// ---------------------------------------------------------------------------------------------
// File-system callbacks: no path expansion, no writing, and no external files at all when loading
// from memory without a base directory.
struct FsPolicy {
  bool allow_external = false;
};

bool fs_exists(const std::string& path, void* ud) {
  return static_cast<FsPolicy*>(ud)->allow_external && tinygltf::FileExists(path, nullptr);
}
std::string fs_expand(const std::string& path, void*) { return path; }
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* ud) {
  if (!static_cast<FsPolicy*>(ud)->allow_external) {
    if (err) *err += "external file '" + path + "' refused (loading from memory)\n";
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, path, nullptr);
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing refused\n";
  return false;
}

// Images are never needed: skip decoding them (faster, and no image decoder on untrusted bytes).
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
                int, void*) {
  return true;
}

// ---------------------------------------------------------------------------------------------
class Loader {
 public:
  Loader(const tinygltf::Model& model, std::string file, Scene& out) : m_(model), file_(std::move(file)), out_(out) {}

  void run() {
    const std::vector<int> roots = root_nodes();
    std::vector<char> visited(m_.nodes.size(), 0);
    struct Item {
      int node;
      Mat4 parent;
      std::string parent_label;
    };
    std::vector<Item> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, identity(), ""});
    while (!stack.empty()) {
      Item item = std::move(stack.back());
      stack.pop_back();
      if (item.node < 0 || size_t(item.node) >= m_.nodes.size())
        fail((item.parent_label.empty() ? std::string("the scene") : item.parent_label) + " refers to node " +
             std::to_string(item.node) + ", which does not exist (" + std::to_string(m_.nodes.size()) +
             " nodes)");
      if (visited[size_t(item.node)])
        fail(node_label(item.node) + " is reached twice: the node hierarchy is not a tree");
      visited[size_t(item.node)] = 1;
      const tinygltf::Node& n = m_.nodes[size_t(item.node)];
      const Mat4 world = mul(item.parent, local_matrix(item.node));
      for (double v : world)
        if (!std::isfinite(v)) fail(node_label(item.node) + ": its world transform is not finite");
      if (n.mesh >= 0 || n.mesh < -1) add_mesh(item.node, world);
      if (n.camera != -1) add_camera(item.node, world);
      add_light(item.node, world);
      const std::string label = node_label(item.node);
      for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world, label});
    }
    if (skipped_ > 0) {
      std::string modes;
      for (const auto& [mode, count] : skipped_modes_)
        modes += (modes.empty() ? "" : ", ") + std::string(mode_name(mode)) + " x" + std::to_string(count);
      warn("skipped " + std::to_string(skipped_) + " non-triangle primitive(s) (" + modes + ")");
    }
    out_.stats.skipped_primitives = skipped_;
    if (out_.tris.empty())
      fail("no triangles" +
           (skipped_ ? " (" + std::to_string(skipped_) + " non-triangle primitive(s) skipped)" : std::string()));
    out_.stats.degenerate_triangles = count_degenerate(out_.tris);
  }

  void warn(const std::string& w) { out_.stats.warnings.push_back(w); }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw SceneError(file_ + ": " + what); }

  std::string node_label(int i) const {
    std::string s = "node " + std::to_string(i);
    if (i >= 0 && size_t(i) < m_.nodes.size() && !m_.nodes[size_t(i)].name.empty())
      s += " " + quote(m_.nodes[size_t(i)].name);
    return s;
  }
  std::string mesh_label(int i) const {
    std::string s = "mesh " + std::to_string(i);
    if (i >= 0 && size_t(i) < m_.meshes.size() && !m_.meshes[size_t(i)].name.empty())
      s += " " + quote(m_.meshes[size_t(i)].name);
    return s;
  }

  std::vector<int> root_nodes() const {
    if (!m_.scenes.empty()) {
      int s = m_.defaultScene;
      if (s >= int(m_.scenes.size()))
        fail("default scene " + std::to_string(s) + " does not exist (" + std::to_string(m_.scenes.size()) +
             " scenes)");
      if (s < 0) s = 0;
      return m_.scenes[size_t(s)].nodes;
    }
    // No scenes: every node that is nobody's child.
    std::vector<char> is_child(m_.nodes.size(), 0);
    for (const auto& n : m_.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < m_.nodes.size()) is_child[size_t(c)] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < m_.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(int(i));
    return roots;
  }

  Mat4 local_matrix(int i) const {
    const tinygltf::Node& n = m_.nodes[size_t(i)];
    auto check = [&](const std::vector<double>& v, size_t want, const char* what) {
      if (!v.empty() && v.size() != want)
        fail(node_label(i) + ": '" + what + "' has " + std::to_string(v.size()) + " numbers, expected " +
             std::to_string(want));
      for (double x : v)
        if (!std::isfinite(x)) fail(node_label(i) + ": '" + what + "' is not finite");
    };
    check(n.matrix, 16, "matrix");
    check(n.translation, 3, "translation");
    check(n.rotation, 4, "rotation");
    check(n.scale, 3, "scale");
    if (n.matrix.size() == 16) {
      Mat4 m;
      for (size_t k = 0; k < 16; ++k) m[k] = n.matrix[k];
      return m;
    }
    Mat4 t = identity(), r = identity(), s = identity();
    if (n.translation.size() == 3) {
      t[12] = n.translation[0];
      t[13] = n.translation[1];
      t[14] = n.translation[2];
    }
    if (n.rotation.size() == 4) {
      double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
      const double len = std::sqrt(x * x + y * y + z * z + w * w);
      if (!(len > 0) || !std::isfinite(len)) fail(node_label(i) + ": rotation quaternion has zero length");
      x /= len, y /= len, z /= len, w /= len;
      r[0] = 1 - 2 * (y * y + z * z);
      r[1] = 2 * (x * y + z * w);
      r[2] = 2 * (x * z - y * w);
      r[4] = 2 * (x * y - z * w);
      r[5] = 1 - 2 * (x * x + z * z);
      r[6] = 2 * (y * z + x * w);
      r[8] = 2 * (x * z + y * w);
      r[9] = 2 * (y * z - x * w);
      r[10] = 1 - 2 * (x * x + y * y);
    }
    if (n.scale.size() == 3) {
      s[0] = n.scale[0];
      s[5] = n.scale[1];
      s[10] = n.scale[2];
    }
    return mul(t, mul(r, s));
  }

  // The bytes [ptr, ptr + size) of buffer view `bv`, checked against its buffer.
  std::pair<const uint8_t*, size_t> view_bytes(int bv, const std::string& what) const {
    if (bv < 0 || size_t(bv) >= m_.bufferViews.size())
      fail(what + ": buffer view " + std::to_string(bv) + " does not exist");
    const tinygltf::BufferView& v = m_.bufferViews[size_t(bv)];
    if (v.buffer < 0 || size_t(v.buffer) >= m_.buffers.size())
      fail(what + ": buffer view " + std::to_string(bv) + " refers to buffer " + std::to_string(v.buffer) +
           ", which does not exist");
    const std::vector<unsigned char>& data = m_.buffers[size_t(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
      fail(what + ": buffer view " + std::to_string(bv) + " (offset " + std::to_string(v.byteOffset) +
           ", length " + std::to_string(v.byteLength) + ") exceeds buffer " + std::to_string(v.buffer) + " (" +
           std::to_string(data.size()) + " bytes)");
    return {data.data() + v.byteOffset, v.byteLength};
  }

  // All components of accessor `ai` as doubles (count * components), after checking its type.
  std::vector<double> read_accessor(int ai, int want_type, const std::vector<int>& allowed_ct,
                                    const std::string& what) const {
    if (ai < 0 || size_t(ai) >= m_.accessors.size())
      fail(what + ": accessor " + std::to_string(ai) + " does not exist");
    const tinygltf::Accessor& a = m_.accessors[size_t(ai)];
    const std::string label = what + ": accessor " + std::to_string(ai);
    if (a.type != want_type)
      fail(label + " has type " + type_name(a.type) + ", expected " + type_name(want_type));
    bool ok = false;
    for (int ct : allowed_ct) ok = ok || a.componentType == ct;
    if (!ok) {
      std::string list;
      for (int ct : allowed_ct) list += (list.empty() ? "" : ", ") + std::string(component_name(ct));
      fail(label + " has component type " + component_name(a.componentType) + " (" +
           std::to_string(a.componentType) + "), expected one of " + list);
    }
    const size_t nc = num_components(a.type), cs = component_size(a.componentType), elem = nc * cs;
    const size_t count = a.count;
    const bool normalized = a.normalized && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
    std::vector<double> out;
    if (a.bufferView < 0) {
      // No buffer view: zeros (glTF), possibly replaced by sparse values below.
      if (!a.sparse.isSparse) fail(label + " has neither a buffer view nor sparse values");
      if (count > (size_t(1) << 24)) fail(label + " has no buffer view and a too large count");
      out.assign(count * nc, 0.0);
    } else {
      const auto [p, n] = view_bytes(a.bufferView, label);
      const tinygltf::BufferView& v = m_.bufferViews[size_t(a.bufferView)];
      const size_t stride = v.byteStride ? v.byteStride : elem;
      if (stride < elem)
        fail(label + ": byte stride " + std::to_string(stride) + " is smaller than an element (" +
             std::to_string(elem) + " bytes)");
      if (count > 0) {
        if (a.byteOffset > n || (count - 1) > (n - a.byteOffset) / stride ||
            (count - 1) * stride + elem > n - a.byteOffset)
          fail(label + " (" + std::to_string(count) + " elements, offset " + std::to_string(a.byteOffset) +
               ", stride " + std::to_string(stride) + ") exceeds its buffer view (" + std::to_string(n) + " bytes)");
      }
      out.resize(count * nc);
      for (size_t i = 0; i < count; ++i)
        for (size_t c = 0; c < nc; ++c)
          out[i * nc + c] = decode(p + a.byteOffset + i * stride + c * cs, a.componentType, normalized);
    }
    if (a.sparse.isSparse) {
      const auto& sp = a.sparse;
      if (sp.count < 0 || size_t(sp.count) > count)
        fail(label + ": sparse count " + std::to_string(sp.count) + " out of range");
      const size_t sc = size_t(sp.count);
      const int ict = sp.indices.componentType;
      const size_t ics = component_size(ict);
      if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(label + ": sparse indices have component type " + std::to_string(ict));
      const auto [ip, in] = view_bytes(sp.indices.bufferView, label + " sparse indices");
      const auto [vp, vn] = view_bytes(sp.values.bufferView, label + " sparse values");
      if (sp.indices.byteOffset < 0 || size_t(sp.indices.byteOffset) > in ||
          sc > (in - size_t(sp.indices.byteOffset)) / ics)
        fail(label + ": sparse indices exceed their buffer view");
      if (sp.values.byteOffset < 0 || size_t(sp.values.byteOffset) > vn ||
          sc > (vn - size_t(sp.values.byteOffset)) / elem)
        fail(label + ": sparse values exceed their buffer view");
      for (size_t k = 0; k < sc; ++k) {
        const double di = decode(ip + size_t(sp.indices.byteOffset) + k * ics, ict, false);
        if (!(di >= 0 && di < double(count)))
          fail(label + ": sparse index " + std::to_string(uint64_t(di)) + " out of range (" + std::to_string(count) +
               " elements)");
        const size_t idx = size_t(di);
        for (size_t c = 0; c < nc; ++c)
          out[idx * nc + c] =
              decode(vp + size_t(sp.values.byteOffset) + k * elem + c * cs, a.componentType, normalized);
      }
    }
    return out;
  }

  void add_mesh(int node, const Mat4& world) {
    const tinygltf::Node& n = m_.nodes[size_t(node)];
    if (n.mesh < 0 || size_t(n.mesh) >= m_.meshes.size())
      fail(node_label(node) + " refers to mesh " + std::to_string(n.mesh) + ", which does not exist");
    const tinygltf::Mesh& mesh = m_.meshes[size_t(n.mesh)];
    MeshRange range;
    range.name = mesh.name.empty() ? "mesh " + std::to_string(n.mesh) : mesh.name;
    range.node = n.name.empty() ? "node " + std::to_string(node) : n.name;
    range.first = out_.tris.size();
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const tinygltf::Primitive& prim = mesh.primitives[pi];
      const std::string what = mesh_label(n.mesh) + " primitive " + std::to_string(pi) + " (" + node_label(node) + ")";
      const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES) {
        ++skipped_;
        ++skipped_modes_[mode];
        continue;
      }
      const auto pos_it = prim.attributes.find("POSITION");
      if (pos_it == prim.attributes.end()) fail(what + " has no POSITION attribute");
      const std::vector<double> pos =
          read_accessor(pos_it->second, TINYGLTF_TYPE_VEC3,
                        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                         TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                        what + " POSITION");
      const size_t nv = pos.size() / 3;
      std::vector<Vec3> wv(nv);
      for (size_t i = 0; i < nv; ++i) {
        const Vec3 p{pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
        if (!hls::is_finite(p)) fail(what + ": vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
        wv[i] = transform_point(world, p);
        if (!hls::is_finite(wv[i]))
          fail(what + ": vertex " + std::to_string(i) + " is not finite after the node transform");
      }
      if (prim.indices >= 0 || prim.indices < -1) {
        const std::vector<double> idx =
            read_accessor(prim.indices, TINYGLTF_TYPE_SCALAR,
                          {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                          what + " indices");
        if (idx.size() % 3 != 0)
          fail(what + ": " + std::to_string(idx.size()) + " indices, not a multiple of 3");
        for (size_t k = 0; k < idx.size(); ++k)
          if (!(idx[k] < double(nv)))
            fail(what + ": index " + std::to_string(k) + " is " + std::to_string(uint64_t(idx[k])) +
                 ", out of range (" + std::to_string(nv) + " vertices)");
        out_.tris.reserve(out_.tris.size() + idx.size() / 3);
        for (size_t k = 0; k < idx.size(); k += 3)
          out_.tris.push_back({wv[size_t(idx[k])], wv[size_t(idx[k + 1])], wv[size_t(idx[k + 2])]});
      } else {
        if (nv % 3 != 0)
          fail(what + ": " + std::to_string(nv) + " vertices without indices, not a multiple of 3");
        for (size_t k = 0; k < nv; k += 3) out_.tris.push_back({wv[k], wv[k + 1], wv[k + 2]});
      }
    }
    range.count = out_.tris.size() - range.first;
    if (range.count > 0) out_.meshes.push_back(range);
  }

  void add_camera(int node, const Mat4& world) {
    const tinygltf::Node& n = m_.nodes[size_t(node)];
    if (n.camera < 0 || size_t(n.camera) >= m_.cameras.size())
      fail(node_label(node) + " refers to camera " + std::to_string(n.camera) + ", which does not exist");
    if (out_.camera.present) return;  // the first one counts
    const tinygltf::Camera& c = m_.cameras[size_t(n.camera)];
    const std::string label = "camera " + std::to_string(n.camera) + (c.name.empty() ? "" : " " + quote(c.name)) +
                              " (" + node_label(node) + ")";
    if (c.type != "perspective") {
      warn(label + " ignored: type '" + c.type + "', only perspective cameras are used");
      return;
    }
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0 && yfov < M_PI)) fail(label + ": yfov " + number(yfov) + " is not in (0, pi)");
    const Vec3 y = column(world, 1), z = column(world, 2);
    const double lz = hls::length(z);
    if (!(lz > 0) || !std::isfinite(lz)) fail(label + ": the node transform has no -Z direction");
    Camera cam;
    cam.present = true;
    cam.position = column(world, 3);
    cam.forward = -z * (1.0 / lz);
    const Vec3 u = y - cam.forward * hls::dot(y, cam.forward);
    const double lu = hls::length(u);
    if (!(lu > 0) || !std::isfinite(lu) || lu < 1e-12 * hls::length(y))
      fail(label + ": the node transform's Y axis is parallel to its Z axis (or zero)");
    cam.up = u * (1.0 / lu);
    cam.right = hls::cross(cam.forward, cam.up);
    cam.yfov = yfov;
    if (c.perspective.aspectRatio > 0 && std::isfinite(c.perspective.aspectRatio))
      cam.aspect = c.perspective.aspectRatio;
    out_.camera = cam;
  }

  void add_light(int node, const Mat4& world) {
    const tinygltf::Node& n = m_.nodes[size_t(node)];
    const auto it = n.extensions.find("KHR_lights_punctual");
    if (it == n.extensions.end()) return;
    const tinygltf::Value& v = it->second;
    if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber())
      fail(node_label(node) + ": KHR_lights_punctual without a light index");
    const double li = v.Get("light").GetNumberAsDouble();
    if (!(li >= 0 && li < double(m_.lights.size())) || li != std::floor(li))
      fail(node_label(node) + " refers to light " + number(li) + ", which does not exist (" +
           std::to_string(m_.lights.size()) + " lights)");
    const tinygltf::Light& l = m_.lights[size_t(li)];
    const std::string label = "light " + std::to_string(size_t(li)) + (l.name.empty() ? "" : " " + quote(l.name)) +
                              " (" + node_label(node) + ")";
    if (l.type != "point") {
      warn(label + " ignored: type '" + l.type + "', only point lights are used");
      return;
    }
    if (out_.light.present) return;
    if (!std::isfinite(l.intensity)) fail(label + ": intensity is not finite");
    out_.light.present = true;
    out_.light.position = column(world, 3);
    out_.light.intensity = l.intensity;
  }

  const tinygltf::Model& m_;
  std::string file_;
  Scene& out_;
  uint64_t skipped_ = 0;
  std::map<int, uint64_t> skipped_modes_;
};

// tinygltf converts `extras` and `extensions` to its Value type recursively, so deeply nested JSON
// overflows the stack (found with [[[[...]]]] 10^5 deep). glTF itself nests about 6 levels; reject
// documents nested deeper than this before tinygltf sees them.
constexpr int kMaxJsonDepth = 256;

int json_depth(const uint8_t* p, size_t n) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t c = p[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

}  // namespace

uint64_t count_degenerate(const std::vector<Tri>& tris) {
  uint64_t n = 0;
  for (const Tri& t : tris) {
    const Vec3 c = hls::cross(t[1] - t[0], t[2] - t[0]);
    if (c.x == 0 && c.y == 0 && c.z == 0) ++n;
  }
  return n;
}

Scene load_gltf_memory(const uint8_t* data, size_t size, const std::string& name, const std::string& base_dir,
                       bool print_warnings) {
  if (size > std::numeric_limits<unsigned int>::max()) throw SceneError(name + ": file too large for glTF (4 GiB)");
  if (size == 0) throw SceneError(name + ": empty file");
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  FsPolicy policy{!base_dir.empty()};
  gltf.SetFsCallbacks(tinygltf::FsCallbacks{fs_exists, fs_expand, fs_read, fs_write, &policy});
  gltf.SetImageLoader(skip_image, nullptr);
  gltf.SetStoreOriginalJSONForExtrasAndExtensions(true);
  std::string err, warn;
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  {
    // The JSON text: the whole file, or a .glb's first chunk (never the binary chunk).
    const uint8_t* json = data;
    size_t json_size = size;
    if (binary) {
      uint32_t len = 0;
      if (size >= 20) std::memcpy(&len, data + 12, 4);
      json = data + std::min<size_t>(20, size);
      json_size = std::min<size_t>(len, size - std::min<size_t>(20, size));
    }
    if (json_depth(json, json_size) > kMaxJsonDepth)
      throw SceneError(name + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                       " levels (refused: tinygltf parses nesting recursively)");
  }
  bool ok;
  if (binary)
    ok = gltf.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned int>(size), base_dir);
  else
    ok = gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data),
                                  static_cast<unsigned int>(size), base_dir);
  auto first_line = [](std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const size_t nl = s.find('\n');
    if (nl != std::string::npos) s = s.substr(0, nl) + " (...)";
    return s;
  };
  if (!ok)
    throw SceneError(name + ": not a valid glTF " + (binary ? "binary (.glb)" : "file (JSON)") + ": " +
                     (err.empty() ? "tinygltf gave no reason" : first_line(err)));
  Scene scene;
  scene.name = stem_of(name);
  scene.source = name;
  if (!warn.empty()) scene.stats.warnings.push_back("glTF: " + first_line(warn));
  if (!err.empty()) scene.stats.warnings.push_back("glTF: " + first_line(err));
  Loader loader(model, name, scene);
  loader.run();
  // asset.extras, kept as JSON text (generator notes).
  if (model.asset.extras.IsObject() && !model.asset.extras_json_string.empty())
    scene.extras = model.asset.extras_json_string;
  if (print_warnings)
    for (const std::string& w : scene.stats.warnings) std::fprintf(stderr, "warning: %s: %s\n", name.c_str(), w.c_str());
  return scene;
}

Scene load_gltf(const std::string& path, bool print_warnings) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(path + ": is a directory, not a glTF file");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SceneError(path + ": cannot open: " + std::strerror(errno));
  std::vector<uint8_t> bytes;
  try {
    bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {
    throw SceneError(path + ": read error: " + e.what());
  }
  if (f.bad()) throw SceneError(path + ": read error");
  return load_gltf_memory(bytes.data(), bytes.size(), path, dir_of(path), print_warnings);
}

void check_range(const Scene& scene, double max_abs, const std::string& format_name) {
  auto bad = [&](Vec3 p) {
    return !(std::fabs(p.x) <= max_abs && std::fabs(p.y) <= max_abs && std::fabs(p.z) <= max_abs);
  };
  auto fmt = [](Vec3 p) {
    char b[160];
    std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
    return std::string(b);
  };
  char lim[64];
  std::snprintf(lim, sizeof lim, "%.6g", max_abs);
  const std::string why = " beyond the range usable with " + format_name + " (|coordinate| <= " + lim + ")";
  for (size_t i = 0; i < scene.tris.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (bad(scene.tris[i][size_t(k)]))
        throw SceneError(scene.source + ": " + scene.describe_triangle(i) + " vertex " + std::to_string(k) + " " +
                         fmt(scene.tris[i][size_t(k)]) + " is" + why);
  if (scene.camera.present && bad(scene.camera.position))
    throw SceneError(scene.source + ": camera position " + fmt(scene.camera.position) + " is" + why);
  if (scene.light.present && bad(scene.light.position))
    throw SceneError(scene.source + ": light position " + fmt(scene.light.position) + " is" + why);
}

// ---------------------------------------------------------------------------------------------
// Writer.
namespace {

using ojson = nlohmann::ordered_json;

void put_u32(std::vector<uint8_t>& b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(uint8_t(v >> (8 * i)));
}

void align4(std::vector<uint8_t>& b, uint8_t fill) {
  while (b.size() % 4) b.push_back(fill);
}

// The glTF document (without buffer uri) and its binary buffer.
std::pair<ojson, std::vector<uint8_t>> encode(const Scene& s) {
  if (s.tris.empty()) throw SceneError("write_gltf: scene '" + s.name + "' has no triangles");
  for (size_t i = 0; i < s.tris.size(); ++i)
    for (const Vec3& v : s.tris[i])
      if (!hls::is_finite(v)) throw SceneError("write_gltf: " + s.describe_triangle(i) + " is not finite");
  const Box b = s.bounds();
  Vec3 origin{0, 0, 0};
  const double far = 16384;
  if (std::max({std::fabs(b.lo.x), std::fabs(b.lo.y), std::fabs(b.lo.z), std::fabs(b.hi.x), std::fabs(b.hi.y),
                std::fabs(b.hi.z)}) > far)
    for (int k = 0; k < 3; ++k) origin[k] = std::nearbyint(0.5 * (b.lo[k] + b.hi[k]));

  // Mesh ranges: the scene's own when they tile the triangles in order, else one mesh.
  std::vector<MeshRange> ranges;
  {
    size_t next = 0;
    bool tiles = !s.meshes.empty();
    for (const MeshRange& r : s.meshes) {
      if (r.first != next || r.count > s.tris.size() - next) tiles = false;
      next = r.first + r.count;
    }
    if (tiles && next == s.tris.size()) ranges = s.meshes;
    else ranges = {MeshRange{s.name.empty() ? "mesh" : s.name, "", 0, s.tris.size()}};
  }

  ojson doc = ojson::object();
  ojson asset = {{"version", "2.0"}, {"generator", "raycore scenes/gltf.cpp"}};
  if (!s.extras.empty()) {
    ojson ex = ojson::parse(s.extras, nullptr, false);
    if (ex.is_discarded() || !ex.is_object()) throw SceneError("write_gltf: Scene::extras is not a JSON object");
    asset["extras"] = ex;
  }
  doc["asset"] = asset;
  std::vector<uint8_t> bin;
  ojson accessors = ojson::array(), views = ojson::array(), meshes = ojson::array(), nodes = ojson::array();
  ojson children = ojson::array();
  nodes.push_back(ojson::object());  // node 0: the root "model", filled below

  struct Key {
    uint32_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = k.x * 0x9E3779B97F4A7C15ull ^ (uint64_t(k.y) << 21) ^ (uint64_t(k.z) << 42) ^ k.z;
      h ^= h >> 29;
      return size_t(h * 0xBF58476D1CE4E5B9ull);
    }
  };
  for (const MeshRange& r : ranges) {
    if (r.count == 0) continue;
    std::unordered_map<Key, uint32_t, KeyHash> ids;
    std::vector<float> pos;
    std::vector<uint32_t> idx;
    idx.reserve(3 * r.count);
    for (size_t t = r.first; t < r.first + r.count; ++t)
      for (const Vec3& v : s.tris[t]) {
        const float f[3] = {float(v.x - origin.x), float(v.y - origin.y), float(v.z - origin.z)};
        Key k;
        std::memcpy(&k.x, &f[0], 4);
        std::memcpy(&k.y, &f[1], 4);
        std::memcpy(&k.z, &f[2], 4);
        const auto [it, fresh] = ids.try_emplace(k, uint32_t(pos.size() / 3));
        if (fresh) pos.insert(pos.end(), f, f + 3);
        idx.push_back(it->second);
      }
    const size_t nv = pos.size() / 3;
    float lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = hi[k] = pos[size_t(k)];
      for (size_t i = 0; i < nv; ++i) {
        lo[k] = std::min(lo[k], pos[3 * i + size_t(k)]);
        hi[k] = std::max(hi[k], pos[3 * i + size_t(k)]);
      }
    }
    // Positions.
    align4(bin, 0);
    const size_t pos_off = bin.size();
    for (float f : pos) {
      uint32_t u;
      std::memcpy(&u, &f, 4);
      put_u32(bin, u);
    }
    views.push_back({{"buffer", 0}, {"byteOffset", pos_off}, {"byteLength", bin.size() - pos_off}, {"target", 34962}});
    accessors.push_back({{"bufferView", views.size() - 1},
                         {"componentType", TINYGLTF_COMPONENT_TYPE_FLOAT},
                         {"count", nv},
                         {"type", "VEC3"},
                         {"min", {double(lo[0]), double(lo[1]), double(lo[2])}},
                         {"max", {double(hi[0]), double(hi[1]), double(hi[2])}}});
    const size_t pos_acc = accessors.size() - 1;
    // Indices (16 bit when the vertex count allows; 65535 is reserved as the restart value).
    const bool small = nv <= 65535;
    const size_t idx_off = bin.size();
    for (uint32_t i : idx) {
      if (small) {
        bin.push_back(uint8_t(i));
        bin.push_back(uint8_t(i >> 8));
      } else {
        put_u32(bin, i);
      }
    }
    views.push_back({{"buffer", 0}, {"byteOffset", idx_off}, {"byteLength", bin.size() - idx_off}, {"target", 34963}});
    align4(bin, 0);
    accessors.push_back({{"bufferView", views.size() - 1},
                         {"componentType", small ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                         {"count", idx.size()},
                         {"type", "SCALAR"}});
    meshes.push_back({{"name", r.name},
                      {"primitives", ojson::array({{{"attributes", {{"POSITION", pos_acc}}},
                                                   {"indices", accessors.size() - 1},
                                                   {"mode", TINYGLTF_MODE_TRIANGLES}}})}});
    nodes.push_back({{"name", r.node.empty() ? r.name : r.node}, {"mesh", meshes.size() - 1}});
    children.push_back(nodes.size() - 1);
  }
  ojson root = {{"name", "model"}, {"children", children}};
  if (origin.x != 0 || origin.y != 0 || origin.z != 0) root["translation"] = {origin.x, origin.y, origin.z};
  nodes[0] = root;
  ojson scene_nodes = ojson::array({0});
  if (s.camera.present) {
    const Camera& c = s.camera;
    doc["cameras"] = ojson::array(
        {{{"name", "camera"},
          {"type", "perspective"},
          {"perspective", {{"aspectRatio", c.aspect}, {"yfov", c.yfov}, {"znear", 0.01}}}}});
    nodes.push_back({{"name", "camera"},
                     {"camera", 0},
                     {"matrix",
                      {c.right.x, c.right.y, c.right.z, 0.0, c.up.x, c.up.y, c.up.z, 0.0, -c.forward.x, -c.forward.y,
                       -c.forward.z, 0.0, c.position.x, c.position.y, c.position.z, 1.0}}});
    scene_nodes.push_back(nodes.size() - 1);
  }
  if (s.light.present) {
    doc["extensionsUsed"] = ojson::array({"KHR_lights_punctual"});
    doc["extensions"] = {
        {"KHR_lights_punctual",
         {{"lights", ojson::array({{{"name", "light"},
                                    {"type", "point"},
                                    {"color", {1.0, 1.0, 1.0}},
                                    {"intensity", s.light.intensity}}})}}}};
    nodes.push_back({{"name", "light"},
                     {"translation", {s.light.position.x, s.light.position.y, s.light.position.z}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    scene_nodes.push_back(nodes.size() - 1);
  }
  doc["scene"] = 0;
  doc["scenes"] = ojson::array({{{"name", s.name}, {"nodes", scene_nodes}}});
  doc["nodes"] = nodes;
  doc["meshes"] = meshes;
  doc["accessors"] = accessors;
  doc["bufferViews"] = views;
  doc["buffers"] = ojson::array({{{"byteLength", bin.size()}}});
  return {doc, bin};
}

std::string base64(const std::vector<uint8_t>& d) {
  static const char* tab = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((d.size() + 2) / 3 * 4);
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

}  // namespace

std::vector<uint8_t> encode_glb(const Scene& scene) {
  auto [doc, bin] = encode(scene);
  std::string json = doc.dump();
  while (json.size() % 4) json += ' ';
  align4(bin, 0);
  std::vector<uint8_t> out;
  out.reserve(28 + json.size() + bin.size());
  put_u32(out, 0x46546C67u);  // "glTF"
  put_u32(out, 2);
  put_u32(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  put_u32(out, uint32_t(json.size()));
  put_u32(out, 0x4E4F534Au);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  put_u32(out, uint32_t(bin.size()));
  put_u32(out, 0x004E4942u);  // "BIN\0"
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

std::string encode_gltf_json(const Scene& scene) {
  auto [doc, bin] = encode(scene);
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
  return doc.dump(1) + "\n";
}

void write_gltf(const Scene& scene, const std::string& path) {
  const bool glb = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw SceneError(path + ": cannot write: " + std::strerror(errno));
  if (glb) {
    const std::vector<uint8_t> bytes = encode_glb(scene);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  } else {
    const std::string text = encode_gltf_json(scene);
    f.write(text.data(), std::streamsize(text.size()));
  }
  f.close();
  if (!f) throw SceneError(path + ": write error");
}

}  // namespace raycore::scenes
