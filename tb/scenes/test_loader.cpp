// tb/scenes/test_loader.cpp - glTF loader: errors on bad input, hierarchy, camera, light, writer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scenes/gltf.h"
#include "tb/scenes/gltf_builder.h"

namespace raycore::scenes {
namespace {

using test::GltfDoc;
using test::write_file;

// Loading `path` must throw a SceneError whose message holds every one of `parts`.
void expect_error(const std::string& path, const std::vector<std::string>& parts) {
  try {
    const Scene s = load_gltf(path, false);
    ADD_FAILURE() << path << ": loaded " << s.tris.size() << " triangles, expected an error";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    for (const std::string& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "message lacks '" << p << "': " << msg;
  }
}

void expect_vec(Vec3 got, Vec3 want, const std::string& what) {
  EXPECT_EQ(got.x, want.x) << what;
  EXPECT_EQ(got.y, want.y) << what;
  EXPECT_EQ(got.z, want.z) << what;
}

const std::vector<float> kTri = {0, 0, 0, 1, 0, 0, 0, 1, 0};

GltfDoc one_triangle(std::vector<float> pos = kTri) {
  GltfDoc d;
  const int m = d.mesh(d.positions(pos), -1, -1, "tri");
  d.scene({d.node({{"mesh", m}, {"name", "n0"}})});
  return d;
}

TEST(Loader, MissingFile) { expect_error("/nonexistent/dir/x.glb", {"/nonexistent/dir/x.glb", "cannot open"}); }

TEST(Loader, DirectoryInsteadOfFile) { expect_error("/tmp", {"/tmp", "is a directory"}); }

TEST(Loader, EmptyFile) { expect_error(write_file("empty.gltf", ""), {"empty.gltf", "empty"}); }

TEST(Loader, GarbageBytes) {
  std::string g;
  for (int i = 0; i < 300; ++i) g += char((i * 37 + 11) & 0xFF);
  expect_error(write_file("garbage.gltf", g), {"garbage.gltf", "not a valid glTF"});
}

TEST(Loader, TruncatedGlb) {
  std::string g = "glTF";
  g += std::string("\x02\0\0\0\x40\0\0\0\x20\0\0\0JSON", 16);
  g += "{\"asset\":";
  expect_error(write_file("trunc.glb", g), {"trunc.glb", "not a valid glTF binary"});
}

TEST(Loader, MalformedJson) {
  expect_error(write_file("bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ "), {"bad.gltf", "not a valid glTF"});
}

TEST(Loader, NoMeshes) { expect_error(write_file("nomesh.gltf", "{\"asset\":{\"version\":\"2.0\"}}"), {"nomesh.gltf", "no triangles"}); }

TEST(Loader, PointsOnlyIsNoTriangles) {
  GltfDoc d;
  const int m = d.mesh(d.positions(kTri), -1, 0 /*POINTS*/);
  d.scene({d.node({{"mesh", m}})});
  expect_error(write_file("points.gltf", d.text()), {"points.gltf", "no triangles", "1 non-triangle"});
}

TEST(Loader, NonTrianglePrimitivesSkippedAndCounted) {
  GltfDoc d;
  const int pos = d.positions(kTri);
  d.mesh(pos, -1, 1 /*LINES*/);
  d.j["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 4}});
  d.j["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 5}});
  d.scene({d.node({{"mesh", 0}})});
  const Scene s = load_gltf(write_file("mixed.gltf", d.text()), false);
  EXPECT_EQ(s.tris.size(), 1u);
  EXPECT_EQ(s.stats.skipped_primitives, 2u);
  ASSERT_EQ(s.stats.warnings.size(), 1u);
  EXPECT_NE(s.stats.warnings[0].find("skipped 2 non-triangle primitive(s) (LINES x1, TRIANGLE_STRIP x1)"), std::string::npos)
      << s.stats.warnings[0];
}

TEST(Loader, NaNCoordinate) {
  GltfDoc d = one_triangle({0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 0, 0, 1, 0});
  expect_error(write_file("nan.gltf", d.text()), {"nan.gltf", "mesh 0 'tri' primitive 0", "node 0 'n0'", "vertex 1", "NaN"});
}

TEST(Loader, InfiniteAfterTransform) {
  GltfDoc d;
  const int m = d.mesh(d.positions({0, 0, 0, 1e30f, 0, 0, 0, 1, 0}), -1, -1, "big");
  d.scene({d.node({{"mesh", m}, {"scale", {1e300, 1, 1}}})});
  expect_error(write_file("inf.gltf", d.text()), {"inf.gltf", "mesh 0 'big'", "vertex 1", "not finite after the node transform"});
}

TEST(Loader, IndexOutOfRange) {
  GltfDoc d;
  const int m = d.mesh(d.positions(kTri), d.indices_u16({0, 1, 5}), -1, "q");
  d.scene({d.node({{"mesh", m}})});
  expect_error(write_file("oor.gltf", d.text()), {"oor.gltf", "mesh 0 'q' primitive 0", "index 2 is 5", "3 vertices"});
}

TEST(Loader, IndexCountNotMultipleOfThree) {
  GltfDoc d;
  const int m = d.mesh(d.positions(kTri), d.indices_u8({0, 1, 2, 0}));
  d.scene({d.node({{"mesh", m}})});
  expect_error(write_file("idx4.gltf", d.text()), {"idx4.gltf", "4 indices, not a multiple of 3"});
}

TEST(Loader, WrongAccessorTypes) {
  {
    GltfDoc d;
    const int pos = d.accessor(d.view(kTri), 5126, 4, "VEC2");
    d.scene({d.node({{"mesh", d.mesh(pos)}})});
    expect_error(write_file("vec2.gltf", d.text()), {"vec2.gltf", "POSITION", "type VEC2, expected VEC3"});
  }
  {
    GltfDoc d;
    const int idx = d.accessor(d.view(std::vector<float>{0, 1, 2}), 5126, 3, "SCALAR");
    d.scene({d.node({{"mesh", d.mesh(d.positions(kTri), idx)}})});
    expect_error(write_file("fidx.gltf", d.text()), {"fidx.gltf", "indices", "component type FLOAT"});
  }
  {
    GltfDoc d;
    const int pos = d.accessor(d.view(std::vector<uint32_t>(9, 1)), 5125, 3, "VEC3");
    d.scene({d.node({{"mesh", d.mesh(pos)}})});
    expect_error(write_file("upos.gltf", d.text()), {"upos.gltf", "POSITION", "component type UNSIGNED_INT"});
  }
}

TEST(Loader, AccessorBeyondBufferView) {
  GltfDoc d;
  const int pos = d.accessor(d.view(kTri), 5126, 6, "VEC3");  // 6 vertices, 3 stored
  d.scene({d.node({{"mesh", d.mesh(pos, -1, -1, "short")}})});
  expect_error(write_file("short.gltf", d.text()), {"short.gltf", "mesh 0 'short'", "exceeds its buffer view"});
}

TEST(Loader, MissingPosition) {
  GltfDoc d = one_triangle();
  d.j["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
  expect_error(write_file("nopos.gltf", d.text()), {"nopos.gltf", "no POSITION"});
}

TEST(Loader, NodeCycle) {
  GltfDoc d;
  const int m = d.mesh(d.positions(kTri));
  d.node({{"mesh", m}, {"children", {1}}});
  d.node({{"children", {0}}});
  d.scene({0});
  expect_error(write_file("cycle.gltf", d.text()), {"cycle.gltf", "reached twice"});
}

TEST(Loader, NonIndexedAndAllIndexTypes) {
  const std::vector<float> quad = {0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 3, 0};
  const std::vector<float> flat = {0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 0, 0, 2, 3, 0, 0, 3, 0};
  std::vector<Scene> scenes;
  {
    GltfDoc d = one_triangle(flat);
    scenes.push_back(load_gltf(write_file("flat.gltf", d.text()), false));
  }
  for (int type : {5121, 5123, 5125}) {
    GltfDoc d;
    const int pos = d.positions(quad);
    int idx = -1;
    if (type == 5121) idx = d.indices_u8({0, 1, 2, 0, 2, 3});
    if (type == 5123) idx = d.indices_u16({0, 1, 2, 0, 2, 3});
    if (type == 5125) idx = d.indices_u32({0, 1, 2, 0, 2, 3});
    d.scene({d.node({{"mesh", d.mesh(pos, idx)}})});
    scenes.push_back(load_gltf(write_file("idx" + std::to_string(type) + ".gltf", d.text()), false));
  }
  for (const Scene& s : scenes) {
    ASSERT_EQ(s.tris.size(), 2u) << s.source;
    expect_vec(s.tris[0][1], {2, 0, 0}, s.source);
    expect_vec(s.tris[1][1], {2, 3, 0}, s.source);
    expect_vec(s.tris[1][2], {0, 3, 0}, s.source);
    EXPECT_EQ(s.stats.degenerate_triangles, 0u);
    EXPECT_FALSE(s.camera.present);
    EXPECT_FALSE(s.light.present);
  }
}

TEST(Loader, StridedNormalizedAndSparsePositions) {
  // Interleaved: 4 floats per vertex (x, y, z, pad), byteStride 16.
  GltfDoc d;
  const int v = d.view(std::vector<float>{0, 0, 0, 9, 1, 0, 0, 9, 0, 1, 0, 9}, 16);
  const int pos = d.accessor(v, 5126, 3, "VEC3");
  // Normalised unsigned shorts: 65535 = 1.0.
  const int v2 = d.view(std::vector<uint16_t>{0, 0, 0, 65535, 0, 0, 0, 65535, 0});
  const int pos2 = d.accessor(v2, 5123, 3, "VEC3", 0, true);
  // Sparse: base triangle with vertex 2 replaced by (5, 6, 7).
  const int pos3 = d.accessor(d.view(kTri), 5126, 3, "VEC3");
  d.j["accessors"][size_t(pos3)]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", d.view(std::vector<uint8_t>{2})}, {"componentType", 5121}}},
      {"values", {{"bufferView", d.view(std::vector<float>{5, 6, 7})}}}};
  d.mesh(pos);
  d.mesh(pos2);
  d.mesh(pos3);
  d.scene({d.node({{"mesh", 0}}), d.node({{"mesh", 1}}), d.node({{"mesh", 2}})});
  const Scene s = load_gltf(write_file("layouts.gltf", d.text()), false);
  ASSERT_EQ(s.tris.size(), 3u);
  for (int k = 0; k < 2; ++k) {
    expect_vec(s.tris[size_t(k)][0], {0, 0, 0}, "tri " + std::to_string(k));
    expect_vec(s.tris[size_t(k)][1], {1, 0, 0}, "tri " + std::to_string(k));
    expect_vec(s.tris[size_t(k)][2], {0, 1, 0}, "tri " + std::to_string(k));
  }
  expect_vec(s.tris[2][2], {5, 6, 7}, "sparse");
}

// Parent: translation (10, 20, 30), rotation 180 degrees about Y, scale 2 -> (10 - 2x, 20 + 2y, 30 - 2z).
// Child: matrix = 90 degrees about Z plus translation (1, 2, 3) -> (1 - y, 2 + x, 3 + z).
TEST(Loader, NodeHierarchyTrsAndMatrix) {
  GltfDoc d;
  const int m = d.mesh(d.positions({1, 0, 0, 0, 1, 0, 0, 0, 1}), -1, -1, "unit");
  const int child = 1;
  d.node({{"name", "parent"}, {"mesh", m}, {"translation", {10, 20, 30}}, {"rotation", {0, 1, 0, 0}},
          {"scale", {2, 2, 2}}, {"children", {child}}});
  d.node({{"name", "child"}, {"mesh", m}, {"matrix", {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1}}});
  d.scene({0});
  const Scene s = load_gltf(write_file("hier.gltf", d.text()), false);
  ASSERT_EQ(s.tris.size(), 2u);
  expect_vec(s.tris[0][0], {8, 20, 30}, "parent v0");
  expect_vec(s.tris[0][1], {10, 22, 30}, "parent v1");
  expect_vec(s.tris[0][2], {10, 20, 28}, "parent v2");
  expect_vec(s.tris[1][0], {8, 26, 24}, "child v0");
  expect_vec(s.tris[1][1], {10, 24, 24}, "child v1");
  expect_vec(s.tris[1][2], {8, 24, 22}, "child v2");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[1].name, "unit");
  EXPECT_EQ(s.meshes[1].node, "child");
  EXPECT_EQ(s.describe_triangle(1), "triangle 1 (mesh 'unit', node 'child')");
}

TEST(Loader, SceneSelection) {
  GltfDoc d;
  const int m = d.mesh(d.positions(kTri));
  d.node({{"mesh", m}});
  d.node({{"mesh", m}, {"translation", {0, 0, 5}}});
  d.node({{"mesh", m}, {"translation", {0, 0, 7}}, {"children", {1}}});
  // No scenes: all root nodes (0 and 2; node 1 is a child of 2).
  {
    const Scene s = load_gltf(write_file("noscene.gltf", d.text()), false);
    ASSERT_EQ(s.tris.size(), 3u);
    EXPECT_EQ(s.tris[1][0].z, 7);
    EXPECT_EQ(s.tris[2][0].z, 12);
  }
  d.scene({0});
  d.scene({2});
  {
    const Scene s = load_gltf(write_file("scene0.gltf", d.text()), false);
    ASSERT_EQ(s.tris.size(), 1u);
    EXPECT_EQ(s.tris[0][0].z, 0);
  }
  d.j["scene"] = 1;
  {
    const Scene s = load_gltf(write_file("scene1.gltf", d.text()), false);
    ASSERT_EQ(s.tris.size(), 2u);
    EXPECT_EQ(s.tris[0][0].z, 7);
  }
}

TEST(Loader, CameraBasisFromRotatedNodes) {
  GltfDoc d = one_triangle();
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}};
  d.node({{"name", "cam"}, {"camera", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, 1, 0, 0}}});
  d.j["scenes"][0]["nodes"].push_back(1);
  {
    const Scene s = load_gltf(write_file("cam1.gltf", d.text()), false);
    ASSERT_TRUE(s.camera.present);
    expect_vec(s.camera.position, {1, 2, 3}, "position");
    expect_vec(s.camera.forward, {0, 0, 1}, "forward");
    expect_vec(s.camera.up, {0, 1, 0}, "up");
    expect_vec(s.camera.right, {-1, 0, 0}, "right");
    EXPECT_EQ(s.camera.yfov, 0.5);
    EXPECT_EQ(s.camera.aspect, 2.0);
  }
  // Under a non-uniformly scaled parent, turned 90 degrees about X: looks up (+Y), up is +Z.
  GltfDoc e = one_triangle();
  e.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
  e.node({{"scale", {2, 3, 4}}, {"translation", {0, 0, -1}}, {"children", {2}}});
  e.node({{"camera", 0}, {"matrix", {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 5, 0, 1}}});
  e.j["scenes"][0]["nodes"].push_back(1);
  {
    const Scene s = load_gltf(write_file("cam2.gltf", e.text()), false);
    ASSERT_TRUE(s.camera.present);
    expect_vec(s.camera.position, {0, 15, -1}, "position");
    expect_vec(s.camera.forward, {0, 1, 0}, "forward");
    expect_vec(s.camera.up, {0, 0, 1}, "up");
    expect_vec(s.camera.right, {1, 0, 0}, "right");
    EXPECT_EQ(s.camera.aspect, 800.0 / 480.0) << "default aspect when the file has none";
  }
}

TEST(Loader, OrthographicCameraIgnoredBadYfovRejected) {
  GltfDoc d = one_triangle();
  d.j["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"zfar", 10}, {"znear", 0.1}}}}};
  d.node({{"camera", 0}});
  d.j["scenes"][0]["nodes"].push_back(1);
  const Scene s = load_gltf(write_file("ortho.gltf", d.text()), false);
  EXPECT_FALSE(s.camera.present);
  ASSERT_EQ(s.stats.warnings.size(), 1u);
  EXPECT_NE(s.stats.warnings[0].find("orthographic"), std::string::npos);
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 4.0}, {"znear", 0.1}}}}};
  expect_error(write_file("yfov.gltf", d.text()), {"yfov.gltf", "camera 0", "node 1", "yfov"});
}

TEST(Loader, KhrPointLight) {
  GltfDoc d = one_triangle();
  d.j["extensionsUsed"] = {"KHR_lights_punctual"};
  d.j["extensions"] = {{"KHR_lights_punctual",
                        {{"lights", {{{"type", "spot"}, {"spot", nlohmann::json::object()}},
                                     {{"type", "point"}, {"intensity", 5.0}, {"name", "bulb"}}}}}}};
  d.node({{"translation", {1, 1, 1}}, {"children", {2, 3}}});
  d.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  d.node({{"translation", {5, 6, 7}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  d.j["scenes"][0]["nodes"].push_back(1);
  const Scene s = load_gltf(write_file("light.gltf", d.text()), false);
  ASSERT_TRUE(s.light.present);
  expect_vec(s.light.position, {6, 7, 8}, "light position");
  EXPECT_EQ(s.light.intensity, 5.0);
  ASSERT_EQ(s.stats.warnings.size(), 1u);
  EXPECT_NE(s.stats.warnings[0].find("spot"), std::string::npos) << s.stats.warnings[0];
  d.j["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = 7;
  expect_error(write_file("light7.gltf", d.text()), {"light7.gltf", "node 3", "light 7"});
}

TEST(Loader, DegenerateTrianglesKeptAndCounted) {
  GltfDoc d = one_triangle({0, 0, 0, 1, 0, 0, 0, 1, 0,     // fine
                            1, 1, 1, 1, 1, 1, 2, 0, 0,     // repeated vertex
                            0, 0, 0, 1, 1, 1, 2, 2, 2});  // collinear
  const Scene s = load_gltf(write_file("degen.gltf", d.text()), false);
  EXPECT_EQ(s.tris.size(), 3u);
  EXPECT_EQ(s.stats.degenerate_triangles, 2u);
}

TEST(Loader, ExternalBufferRefusedFromMemoryAllowedFromFile) {
  std::vector<float> tri = kTri;
  std::string raw(reinterpret_cast<const char*>(tri.data()), tri.size() * 4);
  write_file("tri.bin", raw);
  const std::string text =
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"tri.bin"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  const std::string path = write_file("ext.gltf", text);
  EXPECT_EQ(load_gltf(path, false).tris.size(), 1u);
  EXPECT_THROW(load_gltf_memory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "mem.gltf"), SceneError);
}

TEST(Writer, GlbAndGltfRoundTrip) {
  Scene s;
  s.name = "rt";
  s.tris = {{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
            {Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0.1, 1, 0}},
            {Vec3{5, 5, 5}, Vec3{5, 5, 5}, Vec3{6, 5, 5}}};
  s.meshes = {{"a", "", 0, 2}, {"b", "nodeb", 2, 1}};
  s.camera.present = true;
  s.camera.position = {1, 2, 3};
  s.camera.forward = {0, 0, 1};
  s.camera.up = {0, 1, 0};
  s.camera.right = {-1, 0, 0};
  s.camera.yfov = 0.9;
  s.light = {true, {4, 5, 6}, 2.5};
  s.extras = R"({"note":"hello","parameters":{"k":1}})";
  for (const char* ext : {".glb", ".gltf"}) {
    const std::string path = test::temp_path(std::string("rt") + ext);
    write_gltf(s, path);
    const Scene r = load_gltf(path, false);
    ASSERT_EQ(r.tris.size(), 3u) << ext;
    for (size_t t = 0; t < 3; ++t)
      for (size_t k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(r.tris[t][k][c], double(float(s.tris[t][k][c]))) << ext << " tri " << t << " vertex " << k;
    EXPECT_EQ(r.stats.degenerate_triangles, 1u);
    ASSERT_EQ(r.meshes.size(), 2u);
    EXPECT_EQ(r.meshes[1].name, "b");
    EXPECT_EQ(r.meshes[1].node, "nodeb");
    ASSERT_TRUE(r.camera.present);
    expect_vec(r.camera.position, {1, 2, 3}, ext);
    expect_vec(r.camera.forward, {0, 0, 1}, ext);
    expect_vec(r.camera.right, {-1, 0, 0}, ext);
    EXPECT_EQ(r.camera.yfov, 0.9);
    ASSERT_TRUE(r.light.present);
    expect_vec(r.light.position, {4, 5, 6}, ext);
    EXPECT_EQ(r.light.intensity, 2.5);
    EXPECT_NE(r.extras.find("\"note\":\"hello\""), std::string::npos) << r.extras;
  }
  EXPECT_EQ(encode_glb(s), encode_glb(s)) << "the writer must be deterministic";
}

TEST(Writer, FarSceneKeepsPrecisionThroughRootTranslation) {
  Scene s;
  s.name = "farrt";
  const double o = 123456;
  s.tris = {{Vec3{o + 0.125, o, o}, Vec3{o + 1.0625, o, o}, Vec3{o, o + 1, o - 0.03125}}};
  const std::vector<uint8_t> glb = encode_glb(s);
  const Scene r = load_gltf_memory(glb.data(), glb.size(), "farrt.glb");
  for (size_t k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(r.tris[0][k][c], s.tris[0][k][c]) << "vertex " << k;
}

TEST(CheckRange, NamesTriangleAndMesh) {
  Scene s;
  s.source = "range.glb";
  s.tris = {{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}, {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, -5e19, 0}}};
  s.meshes = {{"ok", "", 0, 1}, {"huge", "n1", 1, 1}};
  EXPECT_NO_THROW(check_range(s, 1e20, "fp24"));
  try {
    check_range(s, 3.6e19, "fp24");
    ADD_FAILURE() << "expected a range error";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("range.glb"), std::string::npos) << m;
    EXPECT_NE(m.find("triangle 1 (mesh 'huge', node 'n1') vertex 2"), std::string::npos) << m;
    EXPECT_NE(m.find("fp24"), std::string::npos) << m;
  }
  s.tris.pop_back();
  s.camera.present = true;
  s.camera.position = {0, 0, 1e21};
  EXPECT_THROW(check_range(s, 3.6e19, "fp24"), SceneError);
  s.camera.position = {0, 0, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(check_range(s, 3.6e19, "fp24"), SceneError);
}

}  // namespace
}  // namespace raycore::scenes
