// systemc/slot.h - what the units of one RTU share: the ray slots (the trv's register file: each
// ray in flight with its own stack) and the channels between rgu, trv, ist and hit. Every datapath
// value is computed by the hls/ functions; this is only state.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hls/frame.h"
#include "hls/hit.h"
#include "hls/margins.h"
#include "hls/ray.h"
#include "hls/rgu.h"
#include "systemc/ascache.h"
#include "systemc/config.h"
#include "systemc/fifo.h"

namespace raycore::sc {

constexpr int kStackDepth = 64;  // as the golden tracer's

enum class SlotState : uint8_t { start, node, list, wait_ist, leaf_done, pop, done };

struct Best {
  bool found = false;
  uint32_t t = 0, den = 0, pos = 0;  // t: the closest-hit key (hls::KeyFormat; its top bits the F t)
  uint32_t id = 0, k = 0, nu = 0, nv = 0, nd = 0;  // of the winning record
};

struct Slot {
  hls::Ray ray;
  bool shadow = false;
  uint32_t pixel = 0;
  uint32_t skip_id = ~0u;
  SlotState state = SlotState::start;
  uint32_t node = 0, tnear = 0, tfar = 0, tmax = 0;
  struct Entry {
    uint32_t node, tnear, tfar;
  };
  std::array<Entry, kStackDepth> stack{};
  int sp = 0;
  Best best, leaf;
  uint32_t list_first = 0, list_count = 0, list_pos = 0, results = 0;
  // Mailbox (--mailbox M): the last M triangle indices this ray sent to the ist, a FIFO ring.
  std::array<uint32_t, 64> mbox{};
  uint32_t mbox_n = 0, mbox_head = 0;
  double cos_light = 0;  // primary hit: kept for the pixel's shade after the shadow ray
};

// ist input (ist_req_*): one triangle test of a ray's leaf.
struct IstReq {
  uint16_t slot = 0;
  uint32_t pos = 0;  // position in the leaf's list (ties go to the earliest)
  uint32_t tri = 0;  // triangle record index
};

// ist output (ist_res_*).
struct IstRes {
  uint16_t slot = 0;
  bool hit = false;
  uint32_t pos = 0;
  uint32_t t = 0, den = 0, id = 0, k = 0, nu = 0, nv = 0, nd = 0;
};

// Frame-wide set-up and results, shared by all RTUs (the registers the host writes, the frame
// buffer the hit units write).
struct FrameCtx {
  int width = 0, height = 0;
  hls::RguCamera rgu_cam;  // the rgu's camera registers (hls::rgu_camera: ray origin, d00, dx, dy)
  uint32_t light[3] = {0, 0, 0};
  uint32_t box_lo[3] = {0, 0, 0}, box_hi[3] = {0, 0, 0};
  // Before the VTU, in the memory image's coordinates (world, or relative to the anchor with
  // --store anchored; in the format): a VTU at pin level or in RTL translates these at set-up.
  bool vtu_on = false;
  uint32_t light_stored[3] = {0, 0, 0}, box_stored_lo[3] = {0, 0, 0}, box_stored_hi[3] = {0, 0, 0};
  double offset[3] = {0, 0, 0};
  uint32_t tmin = 0;
  uint32_t stack_depth = kStackDepth;  // entries per ray the trv's stack SRAM holds
  uint32_t mailbox = 0;                // triangle indices per ray remembered (0: no mailbox)
  hls::SpawnParams spawn;
  hls::Margins margins;  // the ist's eps / one_eps and the trv's widening (set by simulate)
  bool empty_tree = false;
  hls::ImageHeader header;
  uint32_t tri_line_records = 1;
  hls::Frame* frame = nullptr;
  std::vector<uint8_t> primary_retired, shadow_retired;  // per pixel: times retired
  uint64_t retired = 0, issued = 0;
  Cycle last_retire = 0;
};

// The channels of one RTU.
struct RtuChannels {
  std::vector<Slot> slots;
  std::vector<uint16_t> free_slots;
  TimedFifo<uint16_t> trv_q;     // rays ready for a traversal step (rgu, loop, ist -> trv)
  TimedFifo<IstReq> ist_q;       // trv -> ist
  TimedFifo<IstRes> ist_pipe;    // ist's pipeline (results leave after ist_latency)
  // The entries the ist took out of ist_q in cycle ist_taken_at (its hits, and its misses, which
  // come back in the next cycle): the trv's hand-offs of that cycle do not get their room
  // (ist_room), so that the room is the queue's at the cycle's start less the misses on their
  // way back, registers in rtl/units/ist_unit.v.
  Cycle ist_taken_at = kNever;
  uint32_t ist_taken = 0;
  size_t ist_room(Cycle now) const {
    return ist_q.capacity() - ist_q.size() - (ist_taken_at == now ? ist_taken : 0);
  }
  TimedFifo<uint16_t> hit_q;     // trv -> hit (finished rays)
  TimedFifo<uint16_t> shadow_q;  // hit -> rgu (shadow rays handed over)
  Ascache *node = nullptr, *list = nullptr, *tri = nullptr;
  // With the trv in RTL (systemc/trv_rtl.h): the ist hands its results leaving the pipeline here
  // (for the RTL's reduction) instead of reducing them into the slots itself.
  std::vector<IstRes>* ist_results = nullptr;
};

}  // namespace raycore::sc
