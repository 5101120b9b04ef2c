// tb/scenes/test_fuzz_regressions.cpp - inputs found by the loader fuzzer (tb/fuzz/), pinned as
// literal cases: each must give a SceneError (or load), never crash or hang.
#include <gtest/gtest.h>

#include <string>

#include "scenes/gltf.h"

namespace raycore::scenes {
namespace {

void expect_clean(const std::string& bytes, const std::string& name) {
  try {
    const Scene s = load_gltf_memory(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), name);
    EXPECT_FALSE(s.tris.empty()) << name;
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
}

TEST(FuzzRegressions, Placeholder) { expect_clean("{}", "empty-object.gltf"); }

}  // namespace
}  // namespace raycore::scenes
