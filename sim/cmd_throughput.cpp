// `raycore throughput`: the throughput-against-area study of issue 14 (sim/sweep/throughput.h).
// `--list` prints one `raycore simulate` command per job (scene x configuration) and writes
// DIR/manifest.json; the jobs run anywhere (GNU parallel: scripts/throughput.sh); `--collect DIR`
// reads the reports into DIR/throughput.{csv,md}, the plot data DIR/plot-<scene>.dat and, with
// --doc, the tables into a markdown file between <!-- throughput:begin/end --> marks.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "sim/cli.h"
#include "sim/output.h"
#include "sim/sweep/sweep.h"
#include "sim/sweep/throughput.h"

namespace raycore::cli {
namespace {

namespace fs = std::filesystem;

struct TpArgs {
  sweep::TpOptions o;
  bool list = false;
  std::string collect, area = "docs/area_configs.md", doc;
};

void do_list(const TpArgs& a) {
  std::vector<sweep::TpJob> jobs;
  try {
    jobs = sweep::make_tp_jobs(a.o);
  } catch (const std::invalid_argument& e) {
    throw UserError(std::string("throughput: ") + e.what());
  }
  nlohmann::json m = {{"scenes", a.o.scenes}, {"jobs", nlohmann::json::array()}};
  for (const auto& j : jobs) {
    m["jobs"].push_back({{"id", j.id}, {"scene", j.scene}, {"config", j.config}, {"json", j.json}});
    std::string line;
    for (const auto& x : j.argv) line += (line.empty() ? "" : " ") + sweep::shell_quote(x);
    std::cout << line << "\n";
  }
  sim::write_text(a.o.out + "/manifest.json", m.dump(1) + "\n");
}

void do_collect(const TpArgs& a) {
  const std::string mpath = a.collect + "/manifest.json";
  std::ifstream is(mpath);
  if (!is) throw UserError("throughput: no " + mpath + " (run --list first)");
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(is);
  } catch (const std::exception& e) {
    throw UserError("throughput: " + mpath + ": " + e.what());
  }
  sweep::TpArea area;
  try {
    area = sweep::read_tp_area(a.area);
  } catch (const std::exception& e) {
    throw UserError(std::string("throughput: ") + e.what());
  }
  std::vector<sweep::TpRow> rows;
  size_t missing = 0;
  for (const auto& x : m.at("jobs")) {
    sweep::TpJob j;
    j.id = x.at("id");
    j.scene = x.at("scene");
    j.config = x.at("config");
    j.json = x.at("json");
    std::ifstream r(j.json);
    sweep::TpRow row;
    row.scene = j.scene;
    row.config = j.config;
    if (r) {
      try {
        row = sweep::read_tp_row(j, nlohmann::json::parse(r), area);
      } catch (const std::exception& e) {
        std::cerr << "throughput: " << e.what() << "\n";
      }
    }
    if (!row.ok) ++missing;
    rows.push_back(row);
  }
  sweep::mark_tp(rows);
  const std::vector<std::string> scenes = m.at("scenes").get<std::vector<std::string>>();
  const std::string md = sweep::tp_markdown(rows, scenes, &area);
  sim::write_text(a.collect + "/throughput.md", md);
  sim::write_text(a.collect + "/throughput.csv", sweep::tp_csv(rows));
  for (const auto& s : scenes) sim::write_text(a.collect + "/plot-" + s + ".dat", sweep::tp_plot_data(rows, s));
  if (!a.doc.empty()) sim::write_doc_section(a.doc, "throughput", md);
  std::cout << "throughput: " << rows.size() - missing << " of " << rows.size() << " reports -> " << a.collect
            << "/throughput.{md,csv}" << (a.doc.empty() ? "" : " and " + a.doc) << "\n";
  if (missing) throw UserError("throughput: " + std::to_string(missing) + " reports missing or incomplete");
}

void register_throughput(CLI::App& app) {
  auto a = std::make_shared<TpArgs>();
  auto* c = app.add_subcommand("throughput",
                               "Throughput against RTU area: the levers of issue 14 as a ladder and a grid "
                               "(--list the jobs, --collect their reports)");
  c->add_flag("--list", a->list, "print one `raycore simulate` command per job; write OUT/manifest.json");
  c->add_option("--collect", a->collect, "read the reports of DIR/manifest.json into tables and plot data");
  c->add_option("--scenes", a->o.scenes, "scenes (sponza-paper sibenik-paper corridor)")->delimiter(',');
  c->add_option("--configs", a->o.configs, "configurations (default: all; see docs/results.md)")->delimiter(',');
  c->add_option("--width", a->o.width, "frame width")->check(CLI::Range(1, 16384))->capture_default_str();
  c->add_option("--height", a->o.height, "frame height")->check(CLI::Range(1, 16384))->capture_default_str();
  c->add_option("--threads", a->o.threads, "host threads per job")->check(CLI::Range(0, 1024));
  c->add_option("--scenes-dir", a->o.scenes_dir, "folder of the .glb scenes")->capture_default_str();
  c->add_option("--out", a->o.out, "output folder of the jobs")->capture_default_str();
  c->add_option("--raycore", a->o.raycore, "the raycore binary in the job lines (default: this one)");
  c->add_option("--area", a->area, "collect: rtu.v synthesised at several configurations (make area-configs), the area model's fit")->capture_default_str();
  c->add_option("--doc", a->doc, "collect: also write the tables into this markdown file");
  c->callback([a] {
    if (a->list == !a->collect.empty()) throw UserError("throughput: give exactly one of --list and --collect");
    if (a->o.raycore.empty()) a->o.raycore = fs::read_symlink("/proc/self/exe").string();
    if (a->list)
      do_list(*a);
    else
      do_collect(*a);
  });
}

}  // namespace
RAYCORE_COMMAND(register_throughput);
}  // namespace raycore::cli
