// tb/fuzz/fuzz_loader.cpp - libFuzzer target for the glTF loader (scenes/gltf.cpp on tinygltf).
// Built with clang by scripts/fuzz.sh (not part of the CMake build). Any input must load or give a
// SceneError: every other exception, crash, sanitizer report, hang or memory blow-up is a finding.
#include <cstddef>
#include <cstdint>

#include "scenes/gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const raycore::scenes::Scene s = raycore::scenes::load_gltf_memory(data, size, "fuzz-input");
    // Touch the results (bounds, degenerate count) like a consumer would.
    (void)s.bounds();
    (void)raycore::scenes::count_degenerate(s.tris);
  } catch (const raycore::scenes::SceneError&) {
  }
  return 0;
}
