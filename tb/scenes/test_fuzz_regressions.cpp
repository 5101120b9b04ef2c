// tb/scenes/test_fuzz_regressions.cpp - inputs that crashed or could crash the loader (found by
// the fuzzer in tb/fuzz/ or by hand while building it), pinned as literal cases: each must give a
// SceneError naming the input (or load), never crash or hang.
#include <gtest/gtest.h>

#include <string>

#include "scenes/gltf.h"

namespace raycore::scenes {
namespace {

// Loads `bytes`; returns the SceneError message ("" if it loaded).
std::string load_error(const std::string& bytes, const std::string& name) {
  try {
    const Scene s = load_gltf_memory(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), name);
    EXPECT_FALSE(s.tris.empty()) << name;
    return "";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(name), std::string::npos) << m;
    return m;
  }
}

std::string nest(int depth, const std::string& open, const std::string& inner, const std::string& close) {
  std::string s;
  for (int i = 0; i < depth; ++i) s += open;
  s += inner;
  for (int i = 0; i < depth; ++i) s += close;
  return s;
}

// tinygltf turns extras / extensions into its Value type recursively: 10^5 nested arrays crashed
// the process with a stack overflow (segmentation fault), in asset.extras, a mesh's extras, and a
// root extension alike. Now refused before tinygltf parses the text.
TEST(FuzzRegressions, DeeplyNestedJsonIsRefused) {
  const int d = 100000;
  const std::string docs[] = {
      R"({"asset":{"version":"2.0","extras":{"a":)" + nest(d, "[", "", "]") + "}}}",
      R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}],"extras":)" +
          nest(d, "[", "", "]") + "}]}",
      R"({"asset":{"version":"2.0"},"extensions":{"X":)" + nest(d, "{\"a\":", "1", "}") + "}}",
  };
  for (const std::string& doc : docs) EXPECT_NE(load_error(doc, "deep.gltf").find("nested deeper"), std::string::npos);
  // The same inside a .glb's JSON chunk.
  std::string json = docs[0];
  while (json.size() % 4) json += ' ';
  std::string glb = "glTF";
  auto u32 = [&glb](uint32_t v) {
    for (int i = 0; i < 4; ++i) glb += char((v >> (8 * i)) & 0xFF);
  };
  u32(2);
  u32(uint32_t(20 + json.size()));
  u32(uint32_t(json.size()));
  u32(0x4E4F534Au);
  glb += json;
  EXPECT_NE(load_error(glb, "deep.glb").find("nested deeper"), std::string::npos);
  // Brackets inside strings do not count.
  EXPECT_EQ(load_error(R"({"asset":{"version":"2.0","extras":{"s":")" + std::string(1000, '[') + R"("}}})", "str.gltf")
                .find("nested deeper"),
            std::string::npos);
}

}  // namespace
}  // namespace raycore::scenes
