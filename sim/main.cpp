// sim/main.cpp - entry point of build/bin/raycore.
#include <cstdio>
#include <exception>
#include <vector>

#include "sim/cli.h"
#include "systemc/config.h"

namespace raycore::cli {
namespace {
std::vector<Registrar>& registry() {
  static std::vector<Registrar> r;
  return r;
}
}  // namespace
int add_command(Registrar r) {
  registry().push_back(r);
  return 0;
}
}  // namespace raycore::cli

int main(int argc, char** argv) {
  CLI::App app{
      "raycore: a cycle-accurate model of the RayCore mobile ray-tracing architecture with the "
      "VTU (viewport transfer unit), its FP24 number system, golden tracer and reference"};
  app.require_subcommand(1);
  for (auto r : raycore::cli::registry()) r(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const raycore::cli::UserError& e) {
    std::fprintf(stderr, "raycore: %s\n", e.what());
    return 2;
  } catch (const raycore::sc::ConfigError& e) {  // e.g. --rtl of a configuration not built
    std::fprintf(stderr, "raycore: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "raycore: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
