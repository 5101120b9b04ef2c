// `raycore image info FILE`: validate a dumped memory image and print its header, address map and
// tree statistics (docs/image.md).
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>

#include "hls/image.h"
#include "sim/cli.h"

namespace raycore::cli {
namespace {

struct ImageArgs {
  std::string file;
  int nodes = 0;
  int tris = 0;
};

template <class F>
void print_tris(const hls::Image& img, int n) {
  using W = hls::WaldTri<F>;
  static const char* wald[9] = {"n_u", "n_v", "n_d", "b_nu", "b_nv", "b_d", "c_nu", "c_nv", "c_d"};
  static const char* watertight[12] = {"n_u", "n_v", "n_d", "A_x", "A_y", "A_z",
                                       "B_x", "B_y", "B_z", "C_x", "C_y", "C_z"};
  const char* const* names = img.ist_kind() == hls::IstKind::wald ? wald : watertight;
  for (uint32_t i = 0; i < img.tri_count() && i < uint32_t(n); ++i) {
    const W w = img.wald<F>(i);
    std::printf("  tri %" PRIu32 ": id %" PRIu32 " k %" PRIu32 "%s\n", i, w.id, w.k,
                w.degenerate() ? " degenerate" : "");
    for (int j = 0; j < w.count(); ++j)
      std::printf("    %-5s 0x%0*" PRIX32 "  %.9g\n", names[j], (F::width + 3) / 4, w.c[j],
                  hls::to_double<F>(w.c[j]));
  }
}

void info(const ImageArgs& a) {
  hls::Image img;
  try {
    img = hls::Image::load(a.file);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  const hls::ImageHeader h = img.header();
  const bool fp24 = img.format() == hls::FormatId::fp24;
  auto value = [&](uint32_t b) { return fp24 ? hls::to_double<hls::FP24>(b) : hls::to_double<hls::FP32>(b); };
  std::printf("%s: memory image version %u, %s (%u/%u), constants rounded %s, %s records%s\n", a.file.c_str(),
              unsigned(h.version), hls::format_name(img.format()), unsigned(h.exp_bits),
              unsigned(h.man_bits), hls::rounding_name(img.rounding()), hls::ist_kind_name(img.ist_kind()),
              img.vtu_applied() ? ", VTU-translated" : "");
  std::printf("  %-10s 0x%08x .. 0x%08x  64 bytes\n", "header", 0u, 63u);
  auto range = [](const char* name, uint32_t off, uint64_t count, uint64_t each) {
    const uint64_t bytes = count * each;
    std::printf("  %-10s 0x%08" PRIx32 " .. 0x%08" PRIx64 "  %" PRIu64 " x %" PRIu64 " bytes\n", name,
                off, bytes ? off + bytes - 1 : off, count, each);
  };
  range("nodes", h.node_offset, h.node_count, 8);
  range("leaf lists", h.list_offset, h.list_count, 4);
  range("triangles", h.tri_offset, h.tri_count, h.tri_bytes);
  std::printf("  total      %zu bytes\n", img.bytes.size());
  uint32_t lo[3], hi[3];
  img.box(lo, hi);
  std::printf("  scene box  (%.9g, %.9g, %.9g) .. (%.9g, %.9g, %.9g)\n", value(lo[0]), value(lo[1]),
              value(lo[2]), value(hi[0]), value(hi[1]), value(hi[2]));
  const hls::BuildOptions opt;
  const hls::TreeStats s = hls::analyze_image(img, opt);
  std::printf("  tree       %" PRIu64 " nodes (%" PRIu64 " inner, %" PRIu64 " leaves, %" PRIu64
              " empty), depth %d\n",
              s.nodes, s.inner, s.leaves, s.empty_leaves, s.max_depth);
  std::printf("  refs       %" PRIu64 " (%.3f per triangle), leaf size max %" PRIu64 " mean %.2f\n",
              s.refs, s.refs_per_tri, s.max_leaf, s.mean_leaf);
  std::printf("  SAH cost   %.3f (traversal %.2f, intersection %.2f, empty bonus %.2f)\n", s.sah_cost,
              opt.cost_traversal, opt.cost_intersect, opt.empty_bonus);
  std::printf("  triangles  %" PRIu64 " (%" PRIu64 " degenerate), %" PRIu64 " saturated constants\n",
              s.tris, s.degenerate, s.saturated_constants);
  for (uint32_t i = 0; i < img.node_count() && i < uint32_t(a.nodes); ++i) {
    const hls::Node n = hls::decode_node(img.node(i));
    if (n.leaf())
      std::printf("  node %" PRIu32 ": leaf, %" PRIu32 " triangles from list entry %" PRIu32 "\n", i,
                  n.split_or_count, n.index);
    else
      std::printf("  node %" PRIu32 ": split %c = %.9g (0x%" PRIX32 "), right child %" PRIu32 "\n", i,
                  "xyz"[n.axis], value(n.split_or_count), n.split_or_count, n.index);
  }
  if (fp24) print_tris<hls::FP24>(img, a.tris);
  else print_tris<hls::FP32>(img, a.tris);
}

void register_image(CLI::App& app) {
  auto args = std::make_shared<ImageArgs>();
  auto* c = app.add_subcommand("image", "Inspect a memory image (see docs/image.md)");
  c->require_subcommand(1);
  auto* i = c->add_subcommand("info", "Validate an image file; print its address map and tree statistics");
  i->add_option("file", args->file, "memory image (from --dump-image)")->required();
  i->add_option("--nodes", args->nodes, "also print the first N nodes");
  i->add_option("--tris", args->tris, "also print the first N triangle records");
  i->callback([args] { info(*args); });
}

}  // namespace
RAYCORE_COMMAND(register_image);
}  // namespace raycore::cli
