// systemc/timing.h - the clock that Mrays/s and GB/s are reported at: the RTU's clock from static
// timing of the synthesised RTL (docs/timing.json, written by `make timing`: rtl/units/rtu.v
// mapped to a standard-cell library and timed by OpenSTA, scaled to 28 nm under the assumptions
// stated there), unless --clock-mhz (or a --config file's clock_mhz) gives one. The JSON is built
// into the binary at configure time (systemc/CMakeLists.txt), so a binary reports the timing of
// the RTL it was built with; without it the clock is the old assumed 500 MHz, said so.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "systemc/config.h"

namespace raycore::sc {

struct TimedClock {
  bool found = false;
  double mhz = 0;          // the RTU's clock at 28 nm (clock_mhz_28nm)
  double worst_fo4 = 0;    // its slowest path, in FO4 of the timed library
  std::string design;      // what was timed (rtu.v and its parameters)
  std::string start, end;  // the slowest path's start and end points
  std::string why_not;     // found == false: why
};

// The RTU's timed clock in `timing_json` (the text of a docs/timing.json); the built-in one when
// called without an argument.
TimedClock timed_rtu_clock(const std::string& timing_json);
TimedClock timed_rtu_clock();

// cfg.clock_source "assumed" (no --clock-mhz, no clock_mhz in a --config file): the timed clock,
// source "timing"; without a timed clock, cfg keeps its assumed 500 MHz and clock_note says why.
void apply_timed_clock(SimConfig& cfg, const TimedClock& t = timed_rtu_clock());

// The report's hardware.clock object: mhz, source (timing / option / assumed) and what it rests on.
nlohmann::json clock_json(const SimConfig& cfg);

}  // namespace raycore::sc
