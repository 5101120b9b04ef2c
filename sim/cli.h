// sim/cli.h - the raycore command line. Each sim/cmd_*.cpp registers its subcommands with
// RAYCORE_COMMAND(fn), where fn(CLI::App&) adds a subcommand and its callback.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace raycore::cli {

using Registrar = void (*)(CLI::App&);
int add_command(Registrar r);

// Thrown for bad input (files, options, scenes): main prints "raycore: <what>" and exits with 2.
struct UserError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace raycore::cli

#define RAYCORE_COMMAND(fn) \
  [[maybe_unused]] static const int raycore_cmd_##fn = ::raycore::cli::add_command(fn)
