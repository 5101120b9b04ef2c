// systemc/rtu_rtl.cpp - the frame on RTUs in RTL (see rtu_rtl.h). Built with the Verilated models
// (RAYCORE_RTL=ON); the variants are rtl/units/rtu.cmake's list.
#include "systemc/rtu_rtl.h"

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's
// runtime then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "rtl_rtu_models.h"
#include "systemc/membus_rtl.h"
#include "systemc/rtl_fields.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

using vl::get_bits;
using vl::set_bits;

// A cycle with no ray retired for this long is a hang (the cycle model's frames retire a ray at
// least every few thousand cycles, even with the memory's latency at its largest).
constexpr Cycle kHangCycles = 10'000'000;

// A port's value in hex (a VlWide word by word, the highest first), after a space.
template <class T>
void put_hex(FILE* f, const T& s) {
  if constexpr (std::is_integral_v<T>) {
    std::fprintf(f, " %llx", static_cast<unsigned long long>(s));
  } else {
    std::fprintf(f, " ");
    for (int i = int(sizeof(s) / 4) - 1; i >= 0; --i) std::fprintf(f, "%08x", uint32_t(s[size_t(i)]));
  }
}

// A data beat an RTU takes at its pins in a given cycle (per cycle at most one from the memory,
// routed by membus_if, and one from the L2 of membus_l2).
struct Beat {
  bool valid = false;
  uint32_t rtu = 0, port = 0, tag = 0, index = 0;
  bool last = false;
  std::array<uint8_t, 64> data{};
};

// The parameters rtu.v is Verilated with (rtl/units/rtu.cmake) and what they fix in SimConfig.
struct Built {
  unsigned slot_bits, pipes, ist, words, qbits, hlbits, tile;
  uint32_t node_kb, list_kb, tri_kb, ways, line, mshrs, stages, l2_beat;
};

template <class M, unsigned W>
class RtuRtlRunner {
  static constexpr unsigned BW = 67 + 5 * W;

 public:
  RtuRtlRunner(const char* name, const Built& b, FrameCtx& fc, const SimConfig& cfg,
               const std::vector<uint8_t>& image, const uint32_t vtu_cam[3],
               const pins::HitConfig& hit, const PixelWrite& write)
      : name_(name), fc_(fc), cfg_(cfg), write_(write),
        bus_("membus_rtu", image, cfg.mem_latency, cfg.mem_bandwidth, cfg.mem_queue_depth,
             cfg.seed) {
    image_ = &image;
    check(b);
    while ((1u << mb_) < b.mshrs) ++mb_;
    bus_.set_l2(cfg.l2);
    auto r = make_rtl_membus_for(cfg.rtus, cfg.mem_queue_depth, cfg.mem_bandwidth, cfg.l2);
    if (cfg.mem_bandwidth > 64) throw ConfigError("--rtl rtu: beats of up to 64 bytes");
    const hls::ImageHeader& h = fc.header;
    base_ = {h.node_offset, h.list_offset, h.tri_offset};
    line_ = {cfg.node_cache.line_bytes, cfg.list_cache.line_bytes,
             fc.tri_line_records * (W <= 24 ? 32u : 48u)};
    for (int k = 0; k < cfg.rtus; ++k) {
      rtus_.push_back(std::make_unique<Unit>(this, k));
      Unit& u = *rtus_.back();
      for (uint32_t p = 0; p < 3; ++p) {
        u.req[p].reset(1);
        u.buf[p].assign(size_t(cfg.node_cache.mshrs) * 64, 0);
        bus_.add_requester(&u.req[p], &u, p);
      }
      configure(u.m, k, vtu_cam, hit);
      vl::async_reset(u.m, 1);  // the edge in the reset loads rtu.v's frame registers
    }
    bus_.bind_rtl(std::move(r), uint64_t(cfg.rtus) * (cfg.node_cache.mshrs + cfg.list_cache.mshrs +
                                                      cfg.tri_cache.mshrs));  // as top.h's
    cos_.assign(fc.frame->px.size(), 0.0);
  }
  ~RtuRtlRunner() {
    pool_.reset();  // the second thread stopped before the models it evaluates are finalised
    if (pxf_) std::fclose(pxf_);
    for (auto& u : rtus_) u->m.final();
  }

  RtuRtlRun run() {
    RtuRtlRun res;
    Cycle now = 0;
    if (const char* prefix = std::getenv("RAYCORE_CHIP_DUMP")) dump_chip(prefix);
    if (const char* t = std::getenv("RAYCORE_RTL_THREADS")) {
      const std::string v = t;
      if (v != "1" && v != "2") throw ConfigError("RAYCORE_RTL_THREADS must be 1 or 2, not '" + v + "'");
      if (v == "2" && rtus_.size() > 1) pool_ = std::make_unique<Pool>(this);
    }
    for (;; ++now) {
      // The caches' requests of this cycle (registered in rtu.v: valid from the last edge).
      for (auto& up : rtus_) {
        Unit& u = *up;
        for (uint32_t p = 0; p < 3; ++p) {
          u.req[p].reset(1);
          u.asked[p] = get_bits(u.m.req_valid_o, p, 1) != 0;
          if (!u.asked[p]) continue;
          const uint64_t line = get_bits(u.m.req_line_o, p * 26, 26);
          const uint32_t tag = get_bits(u.m.req_tag_o, p * mb_, mb_);
          MemReq q;
          q.addr = base_[p] + line * line_[p];
          q.bytes = line_[p];
          q.tag = tag;
          q.data = u.buf[p].data() + size_t(tag) * 64;
          u.req[p].push(q, now);
        }
      }
      now_ = now;
      beat_next_.valid = l2_next_.valid = false;
      bus_.tick(now);  // arbitration (membus_if), the memory's beats; the routed beat -> beat_next_
      // Every RTU's two evaluations of this cycle: independent models (the bus is resolved
      // above), so RAYCORE_RTL_THREADS=2 splits them over two host threads; what leaves an RTU is
      // applied afterwards in RTU order, as one thread would.
      if (pool_)
        pool_->run(now);
      else
        for (auto& up : rtus_) eval_unit(*up, now);
      bool all_done = true;
      for (auto& up : rtus_) {
        Unit& u = *up;
        if (u.out.valid) leave(u, now);
        if (u.err)
          throw std::runtime_error("rtu: a ray needs more than the " +
                                   std::to_string(fc_.stack_depth) +
                                   " stack entries of --stack-depth (at most 64, the deepest tree)");
        all_done &= u.done;
      }
      if (all_done && now > 0) break;
      if (now > fc_.last_retire + kHangCycles)
        throw std::runtime_error(name_ + ": no ray retired in " + std::to_string(kHangCycles) +
                                 " cycles (cycle " + std::to_string(now) + ")");
    }
    pool_.reset();
    if (pxf_) std::fclose(pxf_);
    pxf_ = nullptr;
    res.clocked = now + 1;
    res.cycles = fc_.last_retire + 1;
    for (auto& up : rtus_) {
      res.rtus.push_back(stats(up->m));
      res.rtus.back().rgu_primary_end = up->primary_end;
      res.rtus.back().rgu_busy_primary = up->busy_primary;
    }
    res.bus = bus_.stats();
    for (const RtuStats& s : res.rtus) fc_.issued += s.primary_rays + s.shadow_rays;
    return res;
  }

 private:

  // What leaves an RTU in a cycle: its pins with the clock low.
  struct Out {
    bool valid = false, shadow = false, spawn = false;
    uint32_t pixel = 0;
    Best best{};
    hls::ShadowSetup ss{};
    std::remove_reference_t<decltype(std::declval<M&>().px_best_o)> best_bits{};
  };

  struct Unit : MemClient {
    Unit(RtuRtlRunner* r, int k) : run(r), index(uint32_t(k)) {}
    void mem_resp(uint32_t, uint32_t, Cycle) override {}  // the last beat told rtu.v already
    void mem_beat(uint32_t port, uint32_t tag, uint32_t beat, bool last, const uint8_t* data,
                  uint32_t bytes, bool l2, Cycle at) override {
      Beat& b = l2 ? run->l2_next_ : run->beat_next_;
      if (b.valid)
        throw std::logic_error(std::string("--rtl rtu: two ") + (l2 ? "L2" : "memory") +
                               " beats in one cycle");
      if (bytes > b.data.size()) throw std::logic_error("--rtl rtu: a beat of more than 64 bytes");
      if (at != run->now_next()) throw std::logic_error("--rtl rtu: a beat for another cycle");
      b.valid = true;
      b.rtu = index;
      b.port = port;
      b.tag = tag;
      b.index = beat;
      b.last = last;
      std::copy(data, data + bytes, b.data.begin());
    }
    RtuRtlRunner* run;
    uint32_t index;
    // A context of its own: the models may be evaluated on different host threads.
    std::unique_ptr<VerilatedContext> ctx = std::make_unique<VerilatedContext>();
    M m{ctx.get()};
    Out out;        // what left it in this cycle (eval_unit), applied by leave()
    bool err = false, done = false;
    std::array<TimedFifo<MemReq>, 3> req;
    std::array<bool, 3> asked{};
    std::array<std::vector<uint8_t>, 3> buf;  // the bus's copies of the lines (by MSHR)
    Cycle primary_end = 0;                     // RtuStats::rgu_primary_end, rgu_busy_primary
    uint64_t busy_primary = 0;
  };

  Cycle now_next() const { return now_ + 1; }

  void check(const Built& b) const {
    auto kb = [](const CacheConfig& c) { return c.size_bytes / 1024; };
    std::string bad;
    auto need = [&](bool ok, const std::string& what) {
      if (!ok) bad += (bad.empty() ? "" : ", ") + what;
    };
    need(cfg_.rays_in_flight <= (1u << b.slot_bits),
         "--rays-in-flight <= " + std::to_string(1u << b.slot_bits));
    need(fc_.stack_depth <= 64, "--stack-depth <= 64");
    need(cfg_.trv_pipes >= 1 && cfg_.trv_pipes <= b.pipes,
         "--trv-pipes <= " + std::to_string(b.pipes));
    need(cfg_.ist_units >= 1 && cfg_.ist_units <= b.ist,
         "--ist-units <= " + std::to_string(b.ist));
    need(cfg_.ist_queue <= (1u << b.qbits), "--ist-queue <= " + std::to_string(1u << b.qbits));
    need(cfg_.tri_cache.hit_latency >= 1 && cfg_.tri_cache.hit_latency < (1u << b.hlbits),
         "a triangle-cache hit latency of 1 .. " + std::to_string((1u << b.hlbits) - 1) +
             " (ist_unit.v registers the cache's answer before ist.v)");
    need(cfg_.tile == b.tile, "--tile " + std::to_string(b.tile));
    need(kb(cfg_.node_cache) == b.node_kb && kb(cfg_.list_cache) == b.list_kb &&
             kb(cfg_.tri_cache) == b.tri_kb,
         "caches of " + std::to_string(b.node_kb) + " / " + std::to_string(b.list_kb) + " / " +
             std::to_string(b.tri_kb) + " KB");
    for (const CacheConfig* c : {&cfg_.node_cache, &cfg_.list_cache, &cfg_.tri_cache})
      need(c->ways == b.ways && c->line_bytes == b.line && c->mshrs == b.mshrs,
           std::to_string(b.ways) + " ways, " + std::to_string(b.line) + "-byte lines and " +
               std::to_string(b.mshrs) + " MSHRs per cache");
    need(fc_.tri_line_records * (W <= 24 ? 32u : 48u) == b.line,
         std::to_string(b.line) + "-byte triangle lines");
    need(cfg_.vtu_depth == kVtuLevels * b.stages && ist_latency_for(cfg_, hls::IstKind::wald) == kIstLevels * b.stages &&
             cfg_.hit_latency == kHitLevels * b.stages && cfg_.rgu_latency == kRguLevels * b.stages,
         "pipeline depths of STAGES " + std::to_string(b.stages) + " (--vtu-depth " +
             std::to_string(kVtuLevels * b.stages) + ", --ist-latency " +
             std::to_string(kIstLevels * b.stages) + ", --hit-latency " +
             std::to_string(kHitLevels * b.stages) + ", --rgu-latency " +
             std::to_string(kRguLevels * b.stages) + ")");
    need(uint64_t(cfg_.trv_latency) + cfg_.node_cache.hit_latency >= kTrvRtlMinLoop,
         "--trv-latency + the node cache's hit latency >= " + std::to_string(kTrvRtlMinLoop) +
             " (an inner node's split is written back " + std::to_string(kTrvRtlMinLoop - 1) +
             " cycles after its pass)");
    need(cfg_.mailbox == 0, "--mailbox 0");
    need(cfg_.l2.size_bytes == 0 || (cfg_.l2.line_bytes == b.line && cfg_.l2.bandwidth == b.l2_beat),
         "an L2 of " + std::to_string(b.line) + "-byte lines (the caches') and --l2-bandwidth " +
             std::to_string(b.l2_beat) + " (rtu.v's L2 beats), or --l2-kb 0");
    need(cfg_.rtus >= 1 && cfg_.rtus <= 16, "--rtus <= 16");
    need(uint32_t(fc_.width) <= 65535 && uint32_t(fc_.height) <= 65535,
         "frames up to 65535 pixels a side");
    if (!bad.empty())
      throw ConfigError("--rtl rtu: " + name_ + " is built for " + bad +
                        " (rtl/units/rtu.cmake); built: " + rtl_rtu_built());
  }

  void configure(M& m, int k, const uint32_t vtu_cam[3], const pins::HitConfig& hit) {
    const hls::RguCamera& c = fc_.rgu_cam;
    for (unsigned i = 0; i < 3; ++i) {  // {o xyz, d00 xyz, dx xyz, dy xyz}, o x highest
      set_bits(m.cam_i, (11 - i) * W, W, c.o[i]);
      set_bits(m.cam_i, (8 - i) * W, W, c.d00[i]);
      set_bits(m.cam_i, (5 - i) * W, W, c.dx[i]);
      set_bits(m.cam_i, (2 - i) * W, W, c.dy[i]);
      set_bits(m.box_i, i * W, W, fc_.box_lo[i]);
      set_bits(m.box_i, (3 + i) * W, W, fc_.box_hi[i]);
      set_bits(m.light_i, i * W, W, hit.light[i]);
      set_bits(m.vtu_cam_i, i * W, W, vtu_cam[i]);
    }
    m.width_i = uint16_t(fc_.width);
    m.height_i = uint16_t(fc_.height);
    m.rtu_i = uint8_t(k);
    m.rtus_i = uint8_t(cfg_.rtus);
    m.slots_i = static_cast<std::remove_reference_t<decltype(m.slots_i)>>(cfg_.rays_in_flight);
    m.tmin_i = fc_.tmin;
    m.trv_lat_i = uint16_t(cfg_.trv_latency);
    m.node_hl_i = uint16_t(cfg_.node_cache.hit_latency);
    m.list_hl_i = uint16_t(cfg_.list_cache.hit_latency);
    m.pipes_i = uint8_t(cfg_.trv_pipes);
    m.fuse_i = cfg_.trv_fuse;
    m.any_hit_i = fc_.spawn.any_hit;
    m.empty_i = fc_.empty_tree;
    m.depth_i = uint8_t(fc_.stack_depth);
    m.widen_i = uint8_t(fc_.margins.widen_ulps);
    m.eps_i = fc_.margins.eps;
    m.one_eps_i = fc_.margins.one_eps;
    m.qcap_i = uint16_t(cfg_.ist_queue);
    m.tri_hl_i = uint8_t(cfg_.tri_cache.hit_latency);
    m.ist_units_i = uint8_t(cfg_.ist_units);
    m.strategy_i = uint8_t(uint32_t(hit.sp.spawn) & 7u);
    m.segment_i = hit.sp.segment;
    m.all_i = hit.sp.spawn_all;
    m.back_i = uint32_t(hit.g.back);
    m.scale_i = hit.g.scale;
    m.fixed_i = hit.g.fixed;
    m.slab_scale_i = hit.g.slab_scale;
    m.vtu_on_i = fc_.vtu_on;
    m.node_count_i = fc_.header.node_count;
    m.tri_count_i = fc_.header.tri_count;
    m.clk_i = 0;
    m.eval();
  }

  // RAYCORE_CHIP_DUMP=<prefix>: the frame as tb/rtl/tb_chip.v runs it on chip.v (tb/rtl/run_chip.sh):
  // <prefix>.regs the frame registers (RTU 0's pins, tb_chip.v's order) and the image's regions,
  // <prefix>.img the memory image (a byte per line, $readmemh), and later <prefix>.px every ray
  // leaving a hit unit: its pixel, kind and best record (the frame's, to compare as a set).
  void dump_chip(const std::string& prefix) {
    auto open = [&](const char* ext) {
      FILE* f = std::fopen((prefix + ext).c_str(), "w");
      if (!f) throw std::runtime_error("RAYCORE_CHIP_DUMP: cannot write " + prefix + ext);
      return f;
    };
    M& m = rtus_[0]->m;
    FILE* f = open(".regs");
    put_hex(f, m.cam_i); put_hex(f, m.box_i); put_hex(f, m.light_i); put_hex(f, m.vtu_cam_i);
    put_hex(f, m.width_i); put_hex(f, m.height_i); put_hex(f, m.rtus_i); put_hex(f, m.slots_i);
    put_hex(f, m.tmin_i); put_hex(f, m.trv_lat_i); put_hex(f, m.node_hl_i); put_hex(f, m.list_hl_i);
    put_hex(f, m.pipes_i); put_hex(f, m.fuse_i); put_hex(f, m.any_hit_i); put_hex(f, m.empty_i);
    put_hex(f, m.depth_i); put_hex(f, m.widen_i); put_hex(f, m.eps_i); put_hex(f, m.one_eps_i);
    put_hex(f, m.qcap_i); put_hex(f, m.tri_hl_i); put_hex(f, m.ist_units_i); put_hex(f, m.strategy_i);
    put_hex(f, m.segment_i); put_hex(f, m.all_i); put_hex(f, m.back_i); put_hex(f, m.scale_i);
    put_hex(f, m.fixed_i); put_hex(f, m.slab_scale_i); put_hex(f, m.vtu_on_i);
    put_hex(f, m.node_count_i); put_hex(f, m.tri_count_i);
    for (uint64_t b : base_) put_hex(f, b);
    put_hex(f, uint64_t(image_->size()));
    std::fprintf(f, "\n");
    std::fclose(f);
    f = open(".img");
    for (uint8_t b : *image_) std::fprintf(f, "%02x\n", b);
    std::fclose(f);
    pxf_ = open(".px");
  }

  // The ray leaving RTU u's hit unit in cycle now: the frame buffer's pixel write.
  void leave(Unit& u, Cycle now) {
    const Out& o = u.out;
    const uint32_t pixel = o.pixel;
    if (pixel >= fc_.frame->px.size())
      throw std::logic_error("--rtl rtu: a ray of pixel " + std::to_string(pixel) +
                             " outside the frame");
    const bool spawn = write_(pixel, o.shadow, o.best, o.ss, cos_[pixel]);
    if (spawn != o.spawn)
      throw std::logic_error("--rtl rtu: pixel " + std::to_string(pixel) +
                             ": the RTL's spawn decision differs from the frame buffer's");
    if (pxf_) {
      std::fprintf(pxf_, "%x %x", pixel, unsigned(o.shadow));
      put_hex(pxf_, o.best_bits);
      std::fprintf(pxf_, "\n");
    }
    ++fc_.retired;
    fc_.last_retire = std::max(fc_.last_retire, now);
  }

  // A channel's beat (the memory's or the L2's) on rtu.v's pins for it, if it is RTU rtu's.
  template <class V, class T, class I, class L, class D>
  static void drive_beat(const Beat& b, uint32_t rtu, uint32_t bytes, V& valid, T& tag, I& idx,
                         L& last, D& data) {
    valid = 0;
    if (!b.valid || b.rtu != rtu) return;
    valid = static_cast<V>(1u << b.port);
    tag = static_cast<T>(b.tag);
    idx = static_cast<I>(b.index);
    last = static_cast<L>(b.last);
    vl::set_bytes(data, 0, bytes, b.data.data());
  }

  // One RTU's cycle: its inputs, the evaluation with the clock low (what leaves it is kept in
  // u.out), the edge. Touches only u and reads the cycle's routed beat.
  void eval_unit(Unit& u, Cycle now) {
    M& m = u.m;
    m.clk_i = 0;
    m.start_i = now == 0;
    uint32_t ready = 0;
    for (uint32_t p = 0; p < 3; ++p)
      if (u.asked[p] && u.req[p].empty()) ready |= 1u << p;  // the bus took it
    m.req_ready_i = uint8_t(ready);
    // rtu.v is built with BEAT_REG = 1: its beat pins take the next cycle's beats (routed by
    // membus_if and sent by the L2 in this cycle), registered at this edge as the bus's response
    // registers.
    drive_beat(beat_next_, u.index, cfg_.mem_bandwidth, m.beat_valid_i, m.beat_tag_i, m.beat_idx_i,
               m.beat_last_i, m.beat_data_i);
    drive_beat(l2_next_, u.index, cfg_.l2.bandwidth, m.l2_valid_i, m.l2_tag_i, m.l2_idx_i,
               m.l2_last_i, m.l2_data_i);
    m.eval();
    Out& o = u.out;
    o.valid = m.px_valid_o != 0;
    if (o.valid) {
      o.pixel = get_bits(m.px_pixel_o, 0, 32);  // y * width + x (rgu.v)
      o.shadow = m.px_shadow_o != 0;
      o.best = vl::get_best(m.px_best_o, 0, W, 0, W <= 24 ? 7 : 0);  // rtu.v's t (Wald's: F's) as the key
      o.best_bits = m.px_best_o;
      for (unsigned i = 0; i < 3; ++i) o.ss.h[i] = get_bits(m.px_h_o, i * W, W);
      o.ss.front = m.px_front_o;
      o.ss.spawn = m.px_spawn_o;
      o.ss.dens = m.px_dens_o;
      o.ss.ray = vl::get_ray(m.px_ray_o, 0, W);
      o.spawn = m.px_spawn_o != 0;
    }
    m.clk_i = 1;
    m.eval();
    u.err = m.err_o != 0;
    u.done = m.done_o != 0;
    if (now > 0 && !m.primaries_o && !u.primary_end) {  // the rgu's last primary ray went
      u.primary_end = now + 1;
      u.busy_primary = count(m, 15) + count(m, 16);
    }
  }

  // RAYCORE_RTL_THREADS=2: a second host thread evaluates the odd RTUs of each cycle while this
  // one evaluates the even ones (spinning on two atomics: one handshake per cycle; for a machine
  // with a core to spare, not for one already busy).
  class Pool {
   public:
    explicit Pool(RtuRtlRunner* r) : r_(r), t_([this] { work(); }) {}
    ~Pool() {
      stop_.store(true, std::memory_order_release);
      t_.join();
    }
    void run(Cycle now) {
      go_.store(now + 1, std::memory_order_release);
      for (size_t k = 0; k < r_->rtus_.size(); k += 2) r_->eval_unit(*r_->rtus_[k], now);
      while (done_.load(std::memory_order_acquire) != now + 1) std::this_thread::yield();
      if (err_) std::rethrow_exception(err_);
    }

   private:
    void work() {
      Cycle seen = 0;
      for (;;) {
        Cycle g;
        while ((g = go_.load(std::memory_order_acquire)) == seen) {
          if (stop_.load(std::memory_order_acquire)) return;
          std::this_thread::yield();  // the main thread's sequential part (the bus) runs meanwhile
        }
        seen = g;
        try {
          for (size_t k = 1; k < r_->rtus_.size(); k += 2) r_->eval_unit(*r_->rtus_[k], g - 1);
        } catch (...) {
          err_ = std::current_exception();
        }
        done_.store(g, std::memory_order_release);
      }
    }
    RtuRtlRunner* r_;
    std::atomic<Cycle> go_{0}, done_{0};
    std::atomic<bool> stop_{false};
    std::exception_ptr err_;
    std::thread t_;
  };

  // Counter i of rtu.v (cnt_sel_i -> cnt_o: combinational, the clock low).
  static uint64_t count(M& m, unsigned i) {
    m.cnt_sel_i = uint8_t(i);
    m.eval();
    return uint64_t(m.cnt_o);
  }

  RtuStats stats(M& m) {
    auto cnt = [&](unsigned i) { return count(m, i); };
    RtuStats s;
    s.trv_busy = cnt(1);
    s.trv_node_miss = cnt(2);
    s.trv_list_miss = cnt(3);
    s.trv_ist_full = cnt(4);
    s.inner_steps = cnt(5);
    s.leaf_visits = cnt(6);
    s.pops = cnt(7);
    s.list_steps = cnt(8);
    s.trv_fused = cnt(9);
    s.stack_max = cnt(10);
    s.ist_busy = cnt(11);
    s.ist_tri_miss = cnt(12);
    s.tri_tests = cnt(13);
    s.hit_busy = cnt(14);
    s.primary_rays = cnt(15);
    s.shadow_rays = cnt(16);
    s.rgu_stall_no_slot = cnt(17);
    s.vtu_busy = cnt(18);
    s.vtu_paired = cnt(37);
    s.vtu_fill_waits = cnt(38);
    s.rgu_busy = s.primary_rays + s.shadow_rays;
    s.retired = s.primary_rays + s.shadow_rays;
    CacheStats* cs[3] = {&s.node, &s.list, &s.tri};
    for (unsigned c = 0; c < 3; ++c) {
      cs[c]->hits = cnt(19 + 5 * c);
      cs[c]->misses = cnt(20 + 5 * c);
      cs[c]->mshr_merges = cnt(21 + 5 * c);
      cs[c]->mshr_full = cnt(22 + 5 * c);
      cs[c]->fills = cnt(23 + 5 * c);
      cs[c]->set_full = cnt(34 + c);
      cs[c]->accesses = cs[c]->hits + cs[c]->misses;
      cs[c]->cycles_lost = cs[c]->misses;  // as the model counts: an issue slot per miss
    }
    return s;
  }

  std::string name_;
  FrameCtx& fc_;
  const SimConfig& cfg_;
  const PixelWrite& write_;
  Membus bus_;
  std::vector<std::unique_ptr<Unit>> rtus_;
  std::array<uint64_t, 3> base_{};
  std::array<uint32_t, 3> line_{};
  std::vector<double> cos_;  // per pixel: its primary's cosine, for the shadow ray's shade
  Beat beat_next_;  // the beat membus_if routed in this cycle, for the next
  Beat l2_next_;    // the L2's beat of this cycle, for the next
  Cycle now_ = 0;
  FILE* pxf_ = nullptr;
  std::unique_ptr<Pool> pool_;  // RAYCORE_RTL_THREADS=2
  const std::vector<uint8_t>* image_ = nullptr;
  unsigned mb_ = 1;  // MSHR tag bits (rtu.v's MB_)
};

}  // namespace

RtuRtlRun run_rtl_rtus(hls::FormatId f, hls::Rounding r, FrameCtx& fc, const SimConfig& cfg,
                       const std::vector<uint8_t>& image, const uint32_t vtu_cam[3],
                       const pins::HitConfig& hit, const PixelWrite& write) {
#define RAYCORE_RTL_RTU_VARIANT(prefix, fmt, mode, width, stages, slot_bits, pipes, ist, words,   \
                                qbits, hlbits, tile, node_kb, list_kb, tri_kb, ways, line, mshrs, \
                                l2_beat)                                                        \
  if (vl::variant_is(#fmt, #mode, f, r)) {                                                      \
    const Built b{slot_bits, pipes, ist, words, qbits, hlbits, tile,                            \
                  node_kb, list_kb, tri_kb, ways, line, mshrs, stages, l2_beat};                \
    RtuRtlRunner<prefix, width> run("Verilated rtu " #fmt " " #mode, b, fc, cfg, image, vtu_cam, \
                                    hit, write);                                                \
    return run.run();                                                                           \
  }
#include "rtl_rtu_variants.h"
#undef RAYCORE_RTL_RTU_VARIANT
  throw ConfigError(std::string("--rtl rtu: no Verilated rtu for ") + hls::format_name(f) + " " +
                    hls::rounding_name(r) + " in this build; built: " + rtl_rtu_built());
}

std::string rtl_rtu_built() {
  std::string s;
#define RAYCORE_RTL_RTU_VARIANT(prefix, fmt, mode, width, stages, slot_bits, pipes, ist, words,   \
                                qbits, hlbits, tile, node_kb, list_kb, tri_kb, ways, line, mshrs, \
                                l2_beat)                                                        \
  s += std::string(s.empty() ? "" : ", ") + "rtu " #fmt " " #mode " (STAGES " #stages ", " +      \
       std::to_string(1u << slot_bits) + " slots, " #pipes " trv pipes, " #ist " ist units, " +    \
       #node_kb "/" #list_kb "/" #tri_kb " KB caches)";
#include "rtl_rtu_variants.h"
#undef RAYCORE_RTL_RTU_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
