// systemc/pins/rgu.h - the ray generation unit at pin level: the pins of rtl/units/rgu.v (the
// primary-ray path: pixel walk + datapath), its SystemC twin RguTwin, and RguPort / RguPortT, the
// cycle-level view the cycle model's rgu (systemc/rgu.h) uses with either the twin or the
// Verilated --sc model bound in the same place.
//
// rgu.v is a source, not a valid/ready stage: it has no in_valid_i / in_ready_o, but
// configuration registers (the camera hls::RguCamera, the frame size, this RTU and the number of
// RTUs), start_i, busy_o and a valid/ready output. So it has its own pin struct (RguPins) built
// from port.h's per-pin macros, and its own twin process.
//
// The twin: hls::RguTiles (the pixel order; its startup() is rgu_walk.v's set-up: start_i sampled,
// one cycle per subtraction dividing rtu and rtus by the tile columns, one loading the first
// tile), a walk register holding the current pixel while running, and hls::rgu_primary computed
// when the pixel enters the datapath, carried through a ReadyChain of 15 * STAGES registers (the
// RTL's latency and handshake). busy_o = walking or rays in the chain.
#pragma once

#include <systemc>

#include <cstdint>
#include <optional>

#include "hls/ray.h"
#include "hls/rgu.h"
#include "systemc/config.h"
#include "systemc/pins/port.h"

namespace raycore::sc::pins {

// One primary ray at the unit's output (hls::Ray's o, d, inv; tmin and tmax are host registers)
// and its pixel index y * width + x.
struct RguRay {
  uint32_t o[3] = {}, d[3] = {}, inv[3] = {}, pixel = 0;
};

// The data pins of rtl/units/rgu.v (list format: port.h; CFG: the configuration registers and
// start_i; OUT: the ray). busy_o is a plain output, declared by hand below.
#define RAYCORE_RGU_PINS(CFG, OUT, E)                                                          \
  CFG(E, uint32_t, cam_o, xyz) CFG(E, uint32_t, cam_d00, xyz) CFG(E, uint32_t, cam_dx, xyz)   \
  CFG(E, uint32_t, cam_dy, xyz) CFG(E, uint32_t, width, one) CFG(E, uint32_t, height, one)    \
  CFG(E, uint32_t, rtu, one) CFG(E, uint32_t, rtus, one) CFG(E, bool, start, one)             \
  OUT(E, uint32_t, o, xyz) OUT(E, uint32_t, d, xyz) OUT(E, uint32_t, inv, xyz)                \
  OUT(E, uint32_t, pixel, one)

struct RguPins {
  using Out = RguRay;
  struct Signals {
    sc_core::sc_signal<bool> out_valid, out_ready, busy;
    RAYCORE_RGU_PINS(RAYCORE_PINS_CFG, RAYCORE_PINS_OUT, RAYCORE_PINS_SIGNAL)
  };
  struct Ports {
    sc_core::sc_in<bool> clk_i, rst_ni;
    sc_core::sc_out<bool> busy_o, out_valid_o;
    sc_core::sc_in<bool> out_ready_i;
    RAYCORE_RGU_PINS(RAYCORE_PINS_CFG, RAYCORE_PINS_OUT, RAYCORE_PINS_PORT)
    void write_out(const Out& r) {
      RAYCORE_RGU_PINS(RAYCORE_PINS_SKIP, RAYCORE_PINS_OUT, RAYCORE_PINS_WRITE)
    }
  };
  template <class M>
  static void bind(M& m, Signals& s, sc_core::sc_signal<bool>& clk,
                   sc_core::sc_signal<bool>& rst_n) {
    m.clk_i(clk);
    m.rst_ni(rst_n);
    m.busy_o(s.busy);
    m.out_valid_o(s.out_valid);
    m.out_ready_i(s.out_ready);
    RAYCORE_RGU_PINS(RAYCORE_PINS_CFG, RAYCORE_PINS_OUT, RAYCORE_PINS_BIND)
  }
  static Out get(const Signals& s) {
    Out r;
    RAYCORE_RGU_PINS(RAYCORE_PINS_SKIP, RAYCORE_PINS_OUT, RAYCORE_PINS_GET)
    return r;
  }
};

// The cycle-level view of a pin-level rgu: the configuration registers and start_i in, the ray
// the last edge produced out. BoundPort (port.h) binds the twin or the Verilated model to it.
class RguPort {
 public:
  using Pins = RguPins;
  virtual ~RguPort() = default;
  // The registers the host writes once per frame (stable while busy_o).
  void config(const hls::RguCamera& c, int width, int height, int rtu, int rtus) {
    s.cam_o_x.write(c.o[0]), s.cam_o_y.write(c.o[1]), s.cam_o_z.write(c.o[2]);
    s.cam_d00_x.write(c.d00[0]), s.cam_d00_y.write(c.d00[1]), s.cam_d00_z.write(c.d00[2]);
    s.cam_dx_x.write(c.dx[0]), s.cam_dx_y.write(c.dx[1]), s.cam_dx_z.write(c.dx[2]);
    s.cam_dy_x.write(c.dy[0]), s.cam_dy_y.write(c.dy[1]), s.cam_dy_z.write(c.dy[2]);
    s.width.write(uint32_t(width));
    s.height.write(uint32_t(height));
    s.rtu.write(uint32_t(rtu));
    s.rtus.write(uint32_t(rtus));
  }
  void start(bool on) { s.start.write(on); }
  void out_ready(bool r) { s.out_ready.write(r); }
  bool out_valid() const { return s.out_valid.read(); }
  bool busy() const { return s.busy.read(); }
  RguRay out() const { return RguPins::get(s); }
  virtual const char* model() const = 0;
  RguPins::Signals s;
};
template <class M>
using RguPortT = BoundPort<RguPort, M>;

// The SystemC twin of rtl/units/rgu.v for the arithmetic A (hls::Arith<F, R>), STAGES registers
// per operator level, tiles of `tile` x `tile` pixels (rgu.v: 2^TILE_BITS).
template <class A>
class RguTwin : public sc_core::sc_module, public RguPins::Ports {
 public:
  SC_HAS_PROCESS(RguTwin);
  RguTwin(sc_core::sc_module_name name, unsigned stages, int tile)
      : sc_core::sc_module(name), tile_(tile), chain_(kRguLevels * stages) {
    SC_METHOD(seq);
    sensitive << clk_i.pos() << rst_ni.neg();
    dont_initialize();
    SC_METHOD(comb);
    sensitive << out_ready_i << changed_;
  }

  // The ray of pixel (x, y) as the datapath computes it from the camera registers.
  static RguRay compute(const hls::RguCamera& c, uint32_t x, uint32_t y, uint32_t pixel) {
    const hls::Ray r = hls::rgu_primary<A>(c, x, y, 0);
    RguRay o;
    for (int i = 0; i < 3; ++i) o.o[i] = r.o[i], o.d[i] = r.d[i], o.inv[i] = r.inv[i];
    o.pixel = pixel;
    return o;
  }

 private:
  enum class State : uint8_t { idle, init, run };

  hls::RguCamera camera() const {
    hls::RguCamera c;
    const sc_core::sc_in<uint32_t>* p[12] = {&cam_o_x_i,   &cam_o_y_i,   &cam_o_z_i,
                                              &cam_d00_x_i, &cam_d00_y_i, &cam_d00_z_i,
                                              &cam_dx_x_i,  &cam_dx_y_i,  &cam_dx_z_i,
                                              &cam_dy_x_i,  &cam_dy_y_i,  &cam_dy_z_i};
    for (int i = 0; i < 3; ++i) {
      c.o[i] = p[i]->read();
      c.d00[i] = p[3 + i]->read();
      c.dx[i] = p[6 + i]->read();
      c.dy[i] = p[9 + i]->read();
    }
    return c;
  }

  void seq() {
    if (!rst_ni.read()) {
      chain_.reset();
      st_ = State::idle;
    } else {
      const bool out_ready = out_ready_i.read();
      // The walk register -> the datapath (taken when the chain's input is ready).
      const bool wv = st_ == State::run;
      const bool wr = chain_.in_ready(out_ready);
      RguRay in{};
      if (wv && wr)
        in = compute(camera(), uint32_t(walk_->x()), uint32_t(walk_->y()), walk_->pixel());
      chain_.edge(wv, in, out_ready);
      switch (st_) {
        case State::idle:
          if (start_i.read() && width_i.read() != 0 && height_i.read() != 0) {
            walk_.emplace(int(width_i.read()), int(height_i.read()), tile_, int(rtu_i.read()),
                          int(rtus_i.read()));
            divide_ = walk_->startup() - 2;  // the subtractions; then one cycle loads the tile
            st_ = State::init;
          }
          break;
        case State::init:
          if (divide_ > 0) --divide_;
          else st_ = walk_->done() ? State::idle : State::run;
          break;
        case State::run:
          if (wr) {
            walk_->next();
            if (walk_->done()) st_ = State::idle;
          }
          break;
      }
    }
    changed_.write(!changed_.read());
  }
  void comb() {
    out_valid_o.write(chain_.out_valid());
    busy_o.write(st_ != State::idle || chain_.any());
    write_out(chain_.out());
  }

  int tile_;
  ReadyChain<RguRay> chain_;
  State st_ = State::idle;
  std::optional<hls::RguTiles> walk_;
  int divide_ = 0;
  sc_core::sc_signal<bool> changed_;
};

}  // namespace raycore::sc::pins
