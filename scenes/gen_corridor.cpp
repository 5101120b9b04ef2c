// scenes/gen_corridor.cpp - `corridor`: a stand-in for the paper's unpublished "Spatial
// Partitioning II" (Game Institute lab scene: several rooms joined by a long passage, bounding box
// about (-886, -279, -886) .. (1242, 279, 1003), camera at (780.94, 141.63, 73.59)).
//
// The building's air space is a union of axis-aligned boxes (rooms, the passage, door openings);
// its boundary is emitted on the grid of all box coordinates, so walls, floors and ceilings are
// closed and T-junction free (every primary ray hits something). Furniture is made of closed boxes,
// cylinders and spheres, placed with a fixed-seed integer RNG.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "scenes/builder.h"

namespace raycore::scenes::gen {
namespace {

struct Air {
  const char* name;
  Vec3 lo, hi;
};

// The walls: boundary faces of the union of the air boxes, facing into the air, one part per box
// and kind (floor / ceiling / walls). Extra grid lines every `step` units keep faces modest.
void emit_shell(Builder& b, const std::vector<Air>& air, double step) {
  std::array<std::vector<double>, 3> g;
  for (const Air& a : air)
    for (int k = 0; k < 3; ++k) {
      g[size_t(k)].push_back(a.lo[k]);
      g[size_t(k)].push_back(a.hi[k]);
    }
  for (int k = 0; k < 3; ++k) {
    auto& v = g[size_t(k)];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    std::vector<double> extra;
    for (size_t i = 0; i + 1 < v.size(); ++i) {
      const int n = int(std::ceil((v[i + 1] - v[i]) / step));
      for (int j = 1; j < n; ++j) extra.push_back(std::floor(v[i] + (v[i + 1] - v[i]) * j / n));
    }
    v.insert(v.end(), extra.begin(), extra.end());
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  const int nx = int(g[0].size()) - 1, ny = int(g[1].size()) - 1, nz = int(g[2].size()) - 1;
  // owner[cell] = index of the first air box containing the cell's centre, or -1.
  auto owner = [&](int i, int j, int k) -> int {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return -1;
    const Vec3 c{0.5 * (g[0][size_t(i)] + g[0][size_t(i) + 1]), 0.5 * (g[1][size_t(j)] + g[1][size_t(j) + 1]),
                 0.5 * (g[2][size_t(k)] + g[2][size_t(k) + 1])};
    for (size_t a = 0; a < air.size(); ++a)
      if (c.x > air[a].lo.x && c.x < air[a].hi.x && c.y > air[a].lo.y && c.y < air[a].hi.y && c.z > air[a].lo.z &&
          c.z < air[a].hi.z)
        return int(a);
    return -1;
  };
  const char* kinds[3] = {"floor", "ceiling", "walls"};
  for (size_t a = 0; a < air.size(); ++a)
    for (int kind = 0; kind < 3; ++kind) {
      b.part(std::string(air[a].name) + "_" + kinds[kind]);
      for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
          for (int k = 0; k < nz; ++k) {
            if (owner(i, j, k) != int(a)) continue;
            const double x0 = g[0][size_t(i)], x1 = g[0][size_t(i) + 1], y0 = g[1][size_t(j)], y1 = g[1][size_t(j) + 1];
            const double z0 = g[2][size_t(k)], z1 = g[2][size_t(k) + 1];
            if (kind == 0 && owner(i, j - 1, k) < 0)
              b.quad_facing({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, {0, 1, 0});
            if (kind == 1 && owner(i, j + 1, k) < 0)
              b.quad_facing({x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, {0, -1, 0});
            if (kind == 2) {
              if (owner(i - 1, j, k) < 0) b.quad_facing({x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, {1, 0, 0});
              if (owner(i + 1, j, k) < 0) b.quad_facing({x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}, {-1, 0, 0});
              if (owner(i, j, k - 1) < 0) b.quad_facing({x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, {0, 0, 1});
              if (owner(i, j, k + 1) < 0) b.quad_facing({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, {0, 0, -1});
            }
          }
    }
}

// Furniture, all in a Frame (position on the floor + yaw); +z is the chair's "back" side.
void table(Builder& b, const Frame& f, double w, double d, double h) {
  b.box(f, {-w / 2, h - 4, -d / 2}, {w / 2, h, d / 2});
  for (int sx : {-1, 1})
    for (int sz : {-1, 1})
      b.box(f, {sx * (w / 2 - 8) - 3, 0, sz * (d / 2 - 8) - 3}, {sx * (w / 2 - 8) + 3, h - 4, sz * (d / 2 - 8) + 3});
}

void chair(Builder& b, const Frame& f) {
  const double w = 20, h = 24;
  b.box(f, {-w / 2, h - 3, -w / 2}, {w / 2, h, w / 2});
  for (int sx : {-1, 1})
    for (int sz : {-1, 1}) b.box(f, {sx * (w / 2 - 2) - 1.5, 0, sz * (w / 2 - 2) - 1.5}, {sx * (w / 2 - 2) + 1.5, h - 3, sz * (w / 2 - 2) + 1.5});
  b.box(f, {-w / 2, h, w / 2 - 3}, {w / 2, h + 26, w / 2});
  b.box(f, {-w / 2 + 2, h + 26, w / 2 - 3}, {w / 2 - 2, h + 30, w / 2});
}

// A bookshelf against a wall: back along +z in its frame, books with random sizes.
void bookshelf(Builder& b, const Frame& f, double w, double h, int boards, Rng& rng) {
  const double d = 24;
  b.box(f, {-w / 2, 0, -d / 2}, {-w / 2 + 3, h, d / 2});
  b.box(f, {w / 2 - 3, 0, -d / 2}, {w / 2, h, d / 2});
  b.box(f, {-w / 2 + 3, 0, d / 2 - 2}, {w / 2 - 3, h, d / 2});
  const double gap = (h - 3) / boards;
  for (int i = 0; i <= boards; ++i) {
    const double y = i * gap;
    b.box(f, {-w / 2 + 3, y, -d / 2}, {w / 2 - 3, y + 3, d / 2 - 2});
    if (i == boards) break;
    double x = -w / 2 + 3.5;
    while (true) {
      const double bw = rng.range(4, 9), bh = rng.range(0.55, 0.85) * (gap - 3), bd = rng.range(14, 20);
      if (x + bw > w / 2 - 3.5) break;
      if (rng.uniform() < 0.12) {  // a gap, or a book lying flat
        x += bw;
        continue;
      }
      b.box(f, {x, y + 3, d / 2 - 2 - bd}, {x + bw - 0.4, y + 3 + bh, d / 2 - 2});
      x += bw;
    }
  }
}

void barrel(Builder& b, Vec3 base) {
  b.cylinder(Frame(), base, 16, 44, 20);
  b.cylinder(Frame(), base + Vec3{0, 10, 0}, 16.8, 3, 20);
  b.cylinder(Frame(), base + Vec3{0, 31, 0}, 16.8, 3, 20);
}

}  // namespace

Scene build_corridor() {
  Builder b("corridor");
  Rng rng(0x5EED0C0441D0Eull);

  // Air space: rooms, the passage and the door openings joining them.
  const std::vector<Air> air = {
      {"passage", {-886, 0, -40}, {1242, 279, 190}},
      {"hall", {480, 0, 330}, {1242, 279, 1003}},
      {"hall_door", {520, 0, 190}, {660, 220, 330}},
      {"gallery", {60, 0, 330}, {380, 279, 760}},
      {"gallery_door", {150, 0, 190}, {290, 220, 330}},
      {"dining", {-886, 0, 330}, {-60, 279, 1003}},
      {"dining_door", {-420, 0, 190}, {-240, 230, 330}},
      {"library", {300, 0, -886}, {1242, 279, -200}},
      {"library_door", {380, 0, -200}, {560, 230, -40}},
      {"storage", {-60, 0, -640}, {220, 240, -200}},
      {"storage_door", {20, 0, -200}, {140, 200, -40}},
      {"basement", {-886, -279, -886}, {-150, 200, -180}},
      {"basement_door", {-520, 0, -180}, {-380, 200, -40}},
  };
  emit_shell(b, air, 128);

  // --- The passage: pillars on both sides (not in front of doors), ceiling beams, benches,
  // plants, hanging lamps and a statue in the middle that hides part of the far end.
  struct Door {
    double x0, x1;
    bool north;
  };
  const Door doors[] = {{520, 660, true},  {150, 290, true},  {-420, -240, true},
                        {380, 560, false}, {20, 140, false}, {-520, -380, false}};
  int pillar = 0;
  for (double x = -800; x <= 1200; x += 165) {
    for (bool north : {false, true}) {
      bool blocked = false;
      for (const Door& d : doors)
        if (d.north == north && x > d.x0 - 40 && x < d.x1 + 40) blocked = true;
      if (blocked) continue;
      const double z = north ? 168 : -18;
      b.part("pillar_" + std::to_string(pillar++));
      b.box(Frame(), {x - 20, 0, z - 20}, {x + 20, 12, z + 20});
      b.cylinder(Frame(), {x, 12, z}, 13, 235, 32);
      b.box(Frame(), {x - 18, 247, z - 18}, {x + 18, 255, z + 18});
    }
  }
  for (int i = 0; i < 11; ++i) {
    const double x = -790 + 200.0 * i;
    b.part("beam_" + std::to_string(i));
    b.box(Frame(), {x - 10, 255, -40}, {x + 10, 279, 190});
  }
  const double bench_x[] = {-680, -40, 430, 1090};
  for (int i = 0; i < 4; ++i) {
    const bool north = i % 2 == 0;
    b.part("bench_" + std::to_string(i));
    const Frame f({bench_x[i], 0, north ? 175.0 : -25.0}, 0);
    b.box(f, {-45, 16, -8}, {45, 20, 8});
    b.box(f, {-40, 0, -6}, {-34, 16, 6});
    b.box(f, {34, 0, -6}, {40, 16, 6});
  }
  const double plant_x[] = {-860, -300, 230, 760, 1215};
  for (int i = 0; i < 5; ++i) {
    const double z = i % 2 ? 160.0 : -12.0;
    b.part("plant_" + std::to_string(i));
    b.cylinder(Frame(), {plant_x[i], 0, z}, 11, 26, 20, 15);
    Rng leaf(1000 + uint64_t(i));
    const double bumps = leaf.range(3, 6), phase = leaf.range(0, 6);
    b.sphere(Frame(), {plant_x[i], 52, z}, 24, 8, 16, [&](Vec3 d) {
      double s, c;
      sincos(bumps * (d.x + d.z) * 3 + phase, s, c);
      return 22 + 3 * s * c;
    });
  }
  for (int i = 0; i < 6; ++i) {
    const double x = -690 + 365.0 * i;
    b.part("lamp_" + std::to_string(i));
    b.cylinder(Frame(), {x, 225, 75}, 1.2, 30, 8);
    b.sphere(Frame(), {x, 215, 75}, 11, 6, 12);
  }
  b.part("statue");
  b.box(Frame(), {-335, 0, 45}, {-265, 60, 105});
  b.sphere(Frame(), {-300, 100, 75}, 40, 16, 32, [](Vec3 d) {
    double s1, c1, s2, c2;
    sincos(5 * d.y + 2 * d.x, s1, c1);
    sincos(4 * d.z - 3 * d.x, s2, c2);
    return 30 + 6 * s1 + 4 * c2 + (d.y > 0.6 ? 6 * (d.y - 0.6) : 0);
  });

  // --- Hall: two long tables with chairs, chandeliers, a fireplace, columns.
  for (int row = 0; row < 2; ++row) {
    const double z = 560 + 240.0 * row;
    b.part("hall_table_" + std::to_string(row));
    table(b, Frame({860, 0, z}, 0.02 * (row ? 1 : -1)), 520, 70, 40);
    for (int i = 0; i < 8; ++i) {
      for (int side : {-1, 1}) {
        b.part("hall_chair_" + std::to_string(row) + "_" + std::to_string(i) + (side > 0 ? "n" : "s"));
        const double yaw = (side > 0 ? kPi : 0) + rng.range(-0.25, 0.25);
        chair(b, Frame({640 + 63.0 * i + rng.range(-6, 6), 0, z + side * (52 + rng.range(-4, 6))}, yaw));
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    b.part("chandelier_" + std::to_string(i));
    const Vec3 c{620 + 240.0 * i, 225, 680};
    b.cylinder(Frame(), c + Vec3{0, 14, 0}, 1.5, 40, 8);
    b.sphere(Frame(), c, 16, 10, 20);
    for (int k = 0; k < 6; ++k) {
      double s, co;
      sincos(2 * kPi * k / 6, s, co);
      b.sphere(Frame(), c + Vec3{34 * co, -6, 34 * s}, 5, 5, 8);
    }
  }
  b.part("hall_fireplace");
  b.box(Frame(), {1160, 0, 600}, {1242, 30, 760});
  b.box(Frame(), {1180, 30, 600}, {1242, 150, 620});
  b.box(Frame(), {1180, 30, 740}, {1242, 150, 760});
  b.box(Frame(), {1170, 150, 590}, {1242, 170, 770});
  for (int i = 0; i < 4; ++i) {
    b.part("hall_column_" + std::to_string(i));
    b.cylinder(Frame(), {560 + 200.0 * i, 0, 940}, 18, 279, 32);
  }

  // --- Library: bookshelves on the walls, reading tables, a globe.
  int shelf = 0;
  for (int i = 0; i < 5; ++i) {
    b.part("library_shelf_" + std::to_string(shelf++));
    bookshelf(b, Frame({400 + 170.0 * i, 0, -860}, 0), 120, 220, 4, rng);
  }
  for (int i = 0; i < 3; ++i) {
    b.part("library_shelf_" + std::to_string(shelf++));
    bookshelf(b, Frame({1216, 0, -740 + 170.0 * i}, -kPi / 2), 120, 220, 4, rng);
  }
  b.part("library_shelf_" + std::to_string(shelf++));
  bookshelf(b, Frame({326, 0, -620}, kPi / 2), 120, 180, 3, rng);
  for (int i = 0; i < 3; ++i) {
    const Vec3 p{560 + 220.0 * i, 0, -520};
    b.part("library_table_" + std::to_string(i));
    table(b, Frame(p, 0.1 * i), 140, 70, 38);
    for (int side : {-1, 1}) {
      b.part("library_chair_" + std::to_string(i) + (side > 0 ? "n" : "s"));
      chair(b, Frame(p + Vec3{rng.range(-30, 30), 0, side * 55.0}, (side > 0 ? kPi : 0) + rng.range(-0.4, 0.4)));
    }
  }
  b.part("library_globe");
  b.cylinder(Frame(), {1100, 0, -300}, 14, 4, 24);
  b.cylinder(Frame(), {1100, 4, -300}, 2.5, 50, 12);
  b.sphere(Frame(), {1100, 78, -300}, 26, 20, 40);

  // --- Storage: metal racks with crates.
  for (int r = 0; r < 3; ++r) {
    const double x = -20 + 100.0 * r;
    b.part("storage_rack_" + std::to_string(r));
    for (int px : {-1, 1})
      for (int pz : {-1, 1}) b.box(Frame(), {x + px * 35 - 2, 0, -560.0 + pz * 130 - 2}, {x + px * 35 + 2, 200, -560.0 + pz * 130 + 2});
    for (int lvl = 0; lvl < 4; ++lvl) {
      const double y = 10 + 60.0 * lvl;
      b.box(Frame(), {x - 37, y, -692}, {x + 37, y + 3, -428});
      for (int k = 0; k < 4; ++k) {
        if (rng.uniform() < 0.25) continue;
        const double s = rng.range(20, 30);
        b.box(Frame({x, y + 3, -660 + 65.0 * k + rng.range(-5, 5)}, rng.range(-0.2, 0.2)), {-s / 2, 0, -s / 2}, {s / 2, s * rng.range(0.6, 1.0), s / 2});
      }
    }
  }

  // --- Basement: stairs down from the door, railings, barrels, stacked crates, square pillars.
  b.part("basement_stairs");
  const int steps = 12;
  const double rise = 279.0 / steps, run = 40;
  for (int i = 0; i < steps; ++i)
    b.box(Frame(), {-520, -279, -180 - run * (i + 1)}, {-380, -rise * i, -180 - run * i});
  for (int side : {0, 1}) {
    const double x = side ? -380.0 : -520.0;
    b.part(std::string("basement_rail_") + (side ? "e" : "w"));
    for (int i = 0; i < steps; i += 2) {
      const double z = -180 - run * (i + 0.5);
      b.cylinder(Frame(), {x + (side ? 6.0 : -6.0), -rise * i, z}, 1.5, 60, 8);
    }
    // The hand rail: a box sheared along the stairs, as two triangles strips (a closed prism).
    const Vec3 top{x + (side ? 6.0 : -6.0), 60, -180 - run * 0.5}, bot{top.x, 60 - rise * (steps - 2), -180 - run * (steps - 1.5)};
    const Vec3 dx{2, 0, 0}, dy{0, 3, 0};
    Vec3 c0[4] = {top - dx, top + dx, top + dx + dy, top - dx + dy};
    Vec3 c1[4] = {bot - dx, bot + dx, bot + dx + dy, bot - dx + dy};
    for (int k = 0; k < 4; ++k) b.quad(c0[k], c1[k], c1[(k + 1) % 4], c0[(k + 1) % 4]);
    b.quad(c0[3], c0[2], c0[1], c0[0]);
    b.quad(c1[0], c1[1], c1[2], c1[3]);
  }
  for (int i = 0; i < 12; ++i) {
    b.part("basement_barrel_" + std::to_string(i));
    barrel(b, {-840 + 36.0 * (i % 8), -279 + (i >= 8 ? 44.0 : 0.0), -840 + (i >= 8 ? 10.0 : 0.0)});
  }
  for (int i = 0; i < 24; ++i) {
    b.part("basement_crate_" + std::to_string(i));
    const double s = rng.range(34, 48);
    const Vec3 p{-300 + 60.0 * (i % 3) + rng.range(-5, 5), -279 + 44.0 * (i / 12), -820 + 55.0 * ((i / 3) % 4)};
    b.box(Frame(p, rng.range(-0.3, 0.3)), {-s / 2, 0, -s / 2}, {s / 2, std::min(s, 43.0), s / 2});
  }
  for (int i = 0; i < 3; ++i) {
    b.part("basement_pillar_" + std::to_string(i));
    b.box(Frame(), {-720 + 200.0 * i - 15, -279, -420 - 15}, {-720 + 200.0 * i + 15, 200, -420 + 15});
  }

  // --- Dining room: round tables with chairs in a circle, vases.
  int t = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) {
      const Vec3 p{-760 + 250.0 * i + rng.range(-15, 15), 0, 480 + 300.0 * j + rng.range(-15, 15)};
      b.part("dining_table_" + std::to_string(t));
      b.cylinder(Frame(), p, 45, 3, 24);
      b.cylinder(Frame(), p + Vec3{0, 3, 0}, 4, 34, 12);
      b.cylinder(Frame(), p + Vec3{0, 37, 0}, 50, 4, 24);
      b.sphere(Frame(), p + Vec3{0, 50, 0}, 9, 8, 16, [](Vec3 d) { return 9 - 3 * d.y * d.y; });
      const int n = 5 + (t % 2);
      for (int k = 0; k < n; ++k) {
        b.part("dining_chair_" + std::to_string(t) + "_" + std::to_string(k));
        const double a = 2 * kPi * k / n + rng.range(-0.2, 0.2);
        double s, c;
        sincos(a, s, c);
        chair(b, Frame(p + Vec3{70 * c, 0, 70 * s}, -a - kPi / 2 + rng.range(-0.3, 0.3)));
      }
      ++t;
    }

  // --- Gallery: pedestals with sculptures.
  for (int i = 0; i < 6; ++i) {
    const Vec3 p{120 + 140.0 * (i % 2), 0, 420 + 120.0 * (i / 2)};
    b.part("gallery_sculpture_" + std::to_string(i));
    b.box(Frame(p, 0.3 * i), {-20, 0, -20}, {20, 70, 20});
    const double f1 = rng.range(2, 6), f2 = rng.range(2, 6), ph = rng.range(0, 6);
    b.sphere(Frame(), p + Vec3{0, 100, 0}, 28, 14, 28, [=](Vec3 d) {
      double s1, c1, s2, c2;
      sincos(f1 * d.x + ph, s1, c1);
      sincos(f2 * d.z + 2 * d.y, s2, c2);
      return 22 + 5 * s1 * c2 + 3 * s2;
    });
  }

  Scene s = b.finish();
  s.camera = look_at_camera({780.94, 141.63, 73.59}, {-886, 100, 95}, 50.0);
  s.light = {true, {240, 200, 100}, 1.0};
  return s;
}

}  // namespace raycore::scenes::gen
