// Verilator harness for a multi-core plant (rtl/plc_system.v, docs/multicore.md): every
// core's byte processor runs the same firmware as in harness.cpp, each in a coroutine
// of its own (ucontext), all in lock step with the one clock. Written by
// `bitbyte run PLANT.toml`; the run file is described in sim/README.md ("Plants").
//
//   Vplc_system RUNFILE
//
// Clock n is the plant's time base (plc_system.time_o): core c starts scan k at
// n = k * period_c. Each clock: every core whose firmware is not asleep runs until it
// asks for the clock (a bus access, hal_spend, hal_wait_dispatch), the bus inputs of
// all cores are applied, the clock-low half is evaluated (bus read data), the rising
// edge follows, finished postcycles write their trace rows and then apply the next
// scan's scan-keyed inputs.
//
// As harness.cpp: the model is observed through its ports only (plc_system's dbg_*
// ports carry what the trace needs beyond the functional ones), evaluated with eval().
// Every core's firmware state has its core as its HAL context (bb_set_hal_ctx), so
// the HAL needs no "current core" global.
#include "Vplc_system.h"
#include "verilated.h"

extern "C" {
#include "byteproc.h"
#include "bus_map.h"   // register addresses, generated from bitbyte/lang/definition.toml
#include "hal.h"
}
#if VM_TRACE_FST
#include "verilated_fst_c.h"
typedef VerilatedFstC WaveWriter;
#elif VM_TRACE_VCD
#include "verilated_vcd_c.h"
typedef VerilatedVcdC WaveWriter;
#else
struct WaveWriter { void dump(uint64_t) {} void close() {} };
#endif
#include <ucontext.h>

#include "harness_common.h"

// ------------------------------------------------------------------ bit fields of ports
// Verilator stores a port of up to 8/16/32/64 bits in an integer, wider ones in 32-bit
// words, least significant first: on a little-endian host all are the same byte array.
template <class P> static void set_field(P& port, unsigned lsb, unsigned width, uint64_t v) {
  uint8_t* b = reinterpret_cast<uint8_t*>(&port);
  if (lsb % 8 == 0 && width % 8 == 0) {  // byte-aligned: the common case
    for (unsigned i = 0; i < width / 8; ++i) b[lsb / 8 + i] = uint8_t(v >> (8 * i));
    return;
  }
  for (unsigned i = 0; i < width; ++i) {
    const unsigned bit = lsb + i;
    if ((v >> i) & 1) b[bit / 8] |= uint8_t(1u << (bit % 8));
    else b[bit / 8] &= uint8_t(~(1u << (bit % 8)));
  }
}
template <class P> static uint64_t get_field(const P& port, unsigned lsb, unsigned width) {
  const uint8_t* b = reinterpret_cast<const uint8_t*>(&port);
  uint64_t v = 0;
  if (lsb % 8 == 0 && width % 8 == 0) {
    for (unsigned i = 0; i < width / 8; ++i) v |= uint64_t(b[lsb / 8 + i]) << (8 * i);
    return v;
  }
  for (unsigned i = 0; i < width; ++i) {
    const unsigned bit = lsb + i;
    v |= uint64_t((b[bit / 8] >> (bit % 8)) & 1) << i;
  }
  return v;
}

// ------------------------------------------------------------------ the run file
struct CoreFile {
  RunFile rf;                      // prog, byte_prog, mode, exchange, costs, pool, stim, col, trace
  std::string name, plan;
  uint64_t period = 0, pre_len = 0, post_base = 0, post_len = 0;  // period: 1/1000 clock
};
struct PlantFile {
  uint64_t clock_hz = 100000000, watchdog = 100000;
  int64_t until_clock = -1;
  unsigned protect = BB_PROTECTION_SEMAPHORE;  // a BB_PROTECTION_* code
  std::string waves, gtkw = "sim/plant.gtkw";
  std::vector<CoreFile> cores;
  int progress_fd = -1;            // progress FD [AFTER_S]: as the single-CPU harness
  double progress_after_s = 2.0;
};

static PlantFile read_plant_file(const char* path) {
  PlantFile pf;
  CoreFile* cur = nullptr;
  for_each_run_line(path, [&](const std::vector<std::string>& w, const std::vector<size_t>& at,
                              const std::string& line) {
    const std::string& k = w[0];
    auto one = [&]() { if (w.size() != 2) die("'%s' takes 1 value", k.c_str()); return w[1]; };
    if (k == "core") {
      if (parse_u64(one(), "core") != pf.cores.size()) die("cores must be numbered 0, 1, ... in order");
      pf.cores.emplace_back();
      cur = &pf.cores.back();
    } else if (!cur) {
      if (k == "clock_hz") pf.clock_hz = parse_u64(one(), "clock_hz");
      else if (k == "watchdog") pf.watchdog = parse_u64(one(), "watchdog");
      else if (k == "until_clock") pf.until_clock = int64_t(parse_u64(one(), "until_clock"));
      else if (k == "waves") pf.waves = one();
      else if (k == "progress") {
        if (w.size() != 2 && w.size() != 3) die("'progress' takes FD [AFTER_S]");
        pf.progress_fd = int(parse_u64(w[1], "progress fd"));
        if (w.size() == 3) pf.progress_after_s = double(parse_u64(w[2], "progress after_s"));
      }
      else if (k == "gtkw") pf.gtkw = one();
      else if (k == "protect") {
        static const char* const kProtections[] = BB_PROTECTION_NAMES;
        pf.protect = setting_code("protect", kProtections, one());
      } else die("unknown plant key '%s' (before the first 'core')", k.c_str());
    } else if (k == "name") cur->name = one();
    else if (k == "plan") cur->plan = one();
    else if (k == "period") cur->period = parse_u64(one(), "period");
    else if (k == "pre_len") cur->pre_len = parse_u64(one(), "pre_len");
    else if (k == "post_base") cur->post_base = parse_u64(one(), "post_base");
    else if (k == "post_len") cur->post_len = parse_u64(one(), "post_len");
    else if (!parse_run_key(cur->rf, w, at, line)) die("unknown key '%s'", k.c_str());
  });
  if (pf.until_clock < 0) die("need 'until_clock'");
  if (pf.clock_hz == 0 || pf.clock_hz % 1000 || pf.clock_hz >= (1ULL << 62))
    die("clock_hz must be a whole number of kHz");
  for (CoreFile& c : pf.cores) {
    c.rf.clock_hz = pf.clock_hz;
    c.rf.watchdog = pf.watchdog;
    check_run(c.rf, false);
    if (c.rf.free_running) die("a plant core runs in serial or parallel mode");
    if (c.period >= (1ULL << 62)) die("period out of range");
  }
  return pf;
}

// ------------------------------------------------------------------ cores
// One core's byte processor: its firmware state and the coroutine it runs in.
struct Core {
  unsigned idx = 0;
  CoreFile* cf = nullptr;
  bb_state bb;
  ucontext_t ctx;
  std::vector<char> stack;
  enum Want { kStart, kBus, kSleep, kWaitNext } want = kStart;
  uint64_t wake = 0;
  // the bus access asked for this clock, and its result after the clock-low half
  uint16_t addr = 0;
  uint32_t wdata = 0;
  bool re = false, we = false, ready = false;
  uint32_t rdata = 0;
  // trace and statistics
  std::FILE* trace = nullptr;
  uint64_t scans = 0;              // rows traced (the summary's figures come from them)
  uint64_t skips = 0;              // skips_o at the last traced scan
  bool finished = false;           // a scan ended at or after until_clock
  bool by_clock = false, by_scan = false;  // its stimulus kind
  bool strobed = false;            // its bus strobes are high in the model
  size_t next_stim = 0;
};

static std::vector<Core> g_cores;
static ucontext_t g_sched;         // the scheduler's context
static uint64_t g_n;               // the clock being prepared (plant time)
static Vplc_system* g_top;         // for hal_wait_dispatch: NEXT after the last edge

// ------------------------------------------------------------------ the HAL (hal.h)
// The HAL context of a core's firmware is its Core: the call hands the clock back to
// the scheduler from that core's coroutine.
static Core& core_of(void* ctx) { return *static_cast<Core*>(ctx); }
static void yield_clock(Core& c) { swapcontext(&c.ctx, &g_sched); }

extern "C" uint32_t hal_bus_read(void* ctx, uint16_t addr) {
  Core& c = core_of(ctx);
  for (;;) {
    c.want = Core::kBus;
    c.addr = addr;
    c.re = true;
    c.we = false;
    yield_clock(c);
    if (c.ready) return c.rdata;   // else a not-ready clock: the access repeats
  }
}

extern "C" void hal_bus_write(void* ctx, uint16_t addr, uint32_t data) {
  Core& c = core_of(ctx);
  for (;;) {
    c.want = Core::kBus;
    c.addr = addr;
    c.wdata = data;
    c.we = true;
    c.re = false;
    yield_clock(c);
    if (c.ready) return;
  }
}

extern "C" void hal_spend(void* ctx, uint32_t clocks) {
  if (!clocks) return;
  Core& c = core_of(ctx);
  c.want = Core::kSleep;
  c.wake = g_n + clocks;
  yield_clock(c);
}

extern "C" void hal_wait_dispatch(void* ctx) {
  // NEXT already up after the last edge: the dispatch clock is this one (as in
  // harness.cpp, waiting costs no clock then)
  Core& c = core_of(ctx);
  if (get_field(g_top->byte_next_o, c.idx, 1)) return;
  c.want = Core::kWaitNext;
  yield_clock(c);
}

extern "C" uint64_t hal_now(void*) { return g_n; }

// A core's coroutine: the firmware's own main loop (it never returns; the harness
// stops resuming it).
static void core_main(int idx) {
  Core& c = g_cores[size_t(idx)];
  bb_run(&c.bb, c.cf->rf.parallel ? BB_MODE_PARALLEL : BB_MODE_SERIAL);
}

// ------------------------------------------------------------------ sizes
// Per-core field widths of the flattened ports: the generated build sizes (bb_isa.h,
// bus_map.h), checked against the model's port sizes in main().
static constexpr unsigned log2u(unsigned v) { return v > 1 ? 1 + log2u(v / 2) : 0; }
constexpr unsigned kOutPins = BB_HW_OUT_BYTES * 8;
constexpr unsigned kWordBits = 16 * kInWords;                  // in_words_i per core
constexpr unsigned kMarkerBits = BB_HW_MARKER_BYTES * 8;
constexpr unsigned kMAddrBits = log2u(kMarkerBits);            // dbg_m_addr_i per core
constexpr unsigned kMwAddrBits = log2u(BB_HW_MW_WORDS);        // dbg_mw_addr_i per core
constexpr unsigned kBusAddrBits = BB_BUS_PLANT_ADDR_BITS;      // bus_addr_i per core
constexpr unsigned kPlanAddrBits = log2u(BB_HW_PLAN_WORDS);    // post_base_i per core
static_assert((1u << kMAddrBits) == kMarkerBits && (1u << kMwAddrBits) == BB_HW_MW_WORDS &&
              (1u << kPlanAddrBits) == BB_HW_PLAN_WORDS, "powers of two");
static_assert(16 * BB_HW_OUT_WORDS == kWordBits, "out_words_o per core as in_words_i");

// The elements a trace column kind can address (run-file `col`).
static unsigned col_range(const std::string& kind) {
  if (kind == "q" || kind == "qr" || kind == "qf") return kOutPins;
  if (kind == "i" || kind == "pi" || kind == "ir" || kind == "if") return kInPins;
  if (kind == "qw" || kind == "iw") return kInWords;
  if (kind == "t" || kind == "c") return BB_HW_STATUS_BITS;
  if (kind == "m") return kMarkerBits;
  if (kind == "mw") return BB_HW_MW_WORDS;
  return ~0u;  // zero
}

int main(int argc, char** argv) {
  // +name=value after the run file: plusargs for the model, as in harness.cpp (the
  // +mutsel=<id> of a mutant netlist, mutation/run_mutate.py's plant campaign).
  bool usage = argc < 2;
  for (int i = 2; i < argc; ++i) usage = usage || argv[i][0] != '+';
  if (usage) { std::fprintf(stderr, "usage: %s RUNFILE [+PLUSARG...]\n", argv[0]); return 2; }
  PlantFile pf = read_plant_file(argv[1]);
  std::unique_ptr<VerilatedContext> ctx{new VerilatedContext};
  ctx->commandArgs(argc, argv);
  if (!pf.waves.empty()) ctx->traceEverOn(true);
  std::unique_ptr<Vplc_system> topp{new Vplc_system{ctx.get(), "TOP"}};
  Vplc_system& top = *topp;
  g_top = &top;
  const unsigned hw_cores = unsigned(sizeof(top.scan_count_o) * 8 / 32);
  if (pf.cores.size() != hw_cores)
    die("this harness is built for %u cores, the run file has %zu", hw_cores, pf.cores.size());
  if (sizeof(top.in_pins_i) * 8 != hw_cores * kInPins || sizeof(top.dbg_pii_o) != sizeof(top.in_pins_i) ||
      sizeof(top.out_pins_o) * 8 != hw_cores * kOutPins ||
      sizeof(top.in_words_i) * 8 != hw_cores * kWordBits ||
      sizeof(top.out_words_o) * 8 != hw_cores * kWordBits ||
      sizeof(top.dbg_timer_status_o) * 8 != hw_cores * BB_HW_STATUS_BITS ||
      // packed fields: the model's word holds them (Verilator rounds the width up)
      sizeof(top.dbg_m_addr_i) * 8 < hw_cores * kMAddrBits ||
      sizeof(top.dbg_mw_addr_i) * 8 < hw_cores * kMwAddrBits ||
      sizeof(top.bus_addr_i) * 8 < hw_cores * kBusAddrBits)
    die("the model's port widths differ from the build sizes of bb_isa.h (regenerate?)");

  std::unique_ptr<WaveWriter> wave;
  uint64_t t_ps = 0, period_ps = 10000;
  auto tick_half = [&](int clk) {
    top.clk_i = clk;
    top.eval();
    if (wave) wave->dump(t_ps + (clk ? period_ps : period_ps / 2));
    if (clk) t_ps += period_ps;
  };
  auto tick = [&]() { tick_half(0); tick_half(1); };
  if (!pf.waves.empty()) {
#if VM_TRACE
    period_ps = std::max<uint64_t>(2, (1000000000000ULL + pf.clock_hz / 2) / pf.clock_hz);
    wave.reset(new WaveWriter);
    top.trace(wave.get(), 99);
    wave->set_time_unit("1ps");
    wave->set_time_resolution("1ps");
    wave->open(pf.waves.c_str());
#else
    die("this harness was built without waves");
#endif
  }

  // Plan address width: post_len_i holds Cores fields of (aw + 1) bits.
  const unsigned aw = kPlanAddrBits;
  const unsigned plan_words = BB_HW_PLAN_WORDS;
  const unsigned prog_words = BB_HW_PROG_WORDS;

  // ---- reset, programs, plans, configuration
  top.rst_ni = 0;
  top.run_i = 0;
  top.clk_i = 1;
  top.eval();
  if (wave) wave->dump(0);
  tick();
  for (unsigned c = 0; c < hw_cores; ++c) {
    CoreFile& cf = pf.cores[c];
    for (auto [a, word] : read_hex(cf.rf.prog, prog_words)) {
      top.prog_we_i = 1u << c;
      top.prog_waddr_i = a;
      top.prog_wdata_i = word;
      tick();
    }
    top.prog_we_i = 0;
    if (!cf.plan.empty())
      for (auto [a, word] : read_hex(cf.plan, plan_words)) {
        top.plan_we_i = 1u << c;
        top.plan_waddr_i = a;
        top.plan_wdata_i = word;
        tick();
      }
    top.plan_we_i = 0;
    if (cf.pre_len > plan_words || cf.post_base + cf.post_len > plan_words) die("core %u: plan too long", c);
    set_field(top.period_i, 64 * c, 64, cf.period);
    set_field(top.pre_len_i, (aw + 1) * c, aw + 1, cf.pre_len);
    set_field(top.post_base_i, aw * c, aw, cf.post_base);
    set_field(top.post_len_i, (aw + 1) * c, aw + 1, cf.post_len);
    set_field(top.parallel_i, c, 1, cf.rf.parallel);
    set_field(top.exchange_i, 2 * c, 2, cf.rf.exchange);
  }
  top.protect_i = pf.protect;
  top.watchdog_limit_i = uint32_t(pf.watchdog);
  tick();
  top.rst_ni = 1;
  for (int i = 0; !top.ready_o; ++i) {
    if (i > 1000000) die("ready_o never rose after reset");
    tick();
  }
  for (unsigned c = 0; c < hw_cores; ++c) {  // TICK_DIV on every core, before the start
    set_field(top.bus_addr_i, kBusAddrBits * c, kBusAddrBits, BB_BUS_TICK_DIV);
    set_field(top.bus_wdata_i, 32 * c, 32, pf.clock_hz / 1000);
    set_field(top.bus_we_i, c, 1, 1);
  }
  tick();
  top.bus_we_i = 0;
  top.run_i = 1;
  tick();  // the plant starts running: the next clock is clock 0 of the time base

  // ---- cores: firmware, coroutines, traces, columns
  g_cores.resize(hw_cores);
  for (unsigned c = 0; c < hw_cores; ++c) {
    Core& k = g_cores[c];
    k.idx = c;
    k.cf = &pf.cores[c];
    const RunFile& rf = k.cf->rf;
    const bb_costs* costs = bb_cost_table(rf.costs.c_str());
    if (!costs) die("unknown cost table '%s'", rf.costs.c_str());
    bb_init(&k.bb, costs);
    bb_set_hal_ctx(&k.bb, &k);
    bb_set_mw_bus(&k.bb, 1);
    if (!rf.pool.empty()) bb_load_pool(&k.bb, rf.pool.data(), unsigned(rf.pool.size()));
    if (rf.parallel) {
      std::vector<uint32_t> words;
      for (auto [a, word] : read_hex(rf.byte_prog, BB_PROG_WORDS)) {
        if (a >= words.size()) words.resize(a + 1, 0);
        words[a] = word;
      }
      if (bb_load_program(&k.bb, words.data(), unsigned(words.size())) != 0) die("byte part too large");
    }
    k.stack.resize(256 * 1024);
    getcontext(&k.ctx);
    k.ctx.uc_stack.ss_sp = k.stack.data();
    k.ctx.uc_stack.ss_size = k.stack.size();
    k.ctx.uc_link = &g_sched;
    makecontext(&k.ctx, reinterpret_cast<void (*)()>(core_main), 1, int(c));
    for (const Col& col : rf.cols)  // each reads a field of core c's slice of a port
      if (col.index >= col_range(col.kind)) die("column %s: index out of range", col.header.c_str());
    if (!rf.trace.empty()) {
      k.trace = std::fopen(rf.trace.c_str(), "w");
      if (!k.trace) die("cannot write trace %s", rf.trace.c_str());
      std::fputs("scan,t_us,cycles,pre,post,sem_wait,copy_fail,overrun", k.trace);
      for (const Col& col : rf.cols) std::fprintf(k.trace, ",%s", col.header.c_str());
      std::fputc('\n', k.trace);
    }
  }
  auto apply_stim = [&](Core& k, uint64_t key) {  // the last row with KEY <= key, if due
    const RunFile& rf = k.cf->rf;
    const Stim* st = nullptr;
    while (k.next_stim < rf.stim.size() && rf.stim[k.next_stim].key <= key) st = &rf.stim[k.next_stim++];
    if (!st) return;
    for (unsigned i = 0; i < kInPinWords; ++i)
      set_field(top.in_pins_i, kInPins * k.idx + 32 * i, 32, st->pins[i]);
    if (st->has_words)
      for (unsigned i = 0; i < kInWords; ++i)
        set_field(top.in_words_i, kWordBits * k.idx + 16 * i, 16, uint16_t(st->words[i]));
  };
  // M / MW through core c's look-up ports: a new address is settled by an eval without
  // a clock edge (combinational only)
  auto look = [&](auto& addr_port, unsigned width, unsigned c, unsigned n) {
    if (get_field(addr_port, width * c, width) == n) return;
    set_field(addr_port, width * c, width, n);
    top.eval();
  };
  auto col_value = [&](Core& k, size_t i) -> int {
    const Col& col = k.cf->rf.cols[i];
    const unsigned c = k.idx, n = col.index;
    if (col.kind == "q") return int(get_field(top.out_pins_o, kOutPins * c + n, 1));
    if (col.kind == "pi") return int(get_field(top.in_pins_i, kInPins * c + n, 1));
    if (col.kind == "qw") return int16_t(get_field(top.out_words_o, kWordBits * c + 16 * n, 16));
    if (col.kind == "iw") return int16_t(get_field(top.in_words_i, kWordBits * c + 16 * n, 16));
    if (col.kind == "i") return int(get_field(top.dbg_pii_o, kInPins * c + n, 1));
    if (col.kind == "ir") return int(get_field(top.dbg_rise_o, kInPins * c + n, 1));
    if (col.kind == "qr") return int(get_field(top.dbg_q_rise_o, kOutPins * c + n, 1));
    if (col.kind == "qf") return int(get_field(top.dbg_q_fall_o, kOutPins * c + n, 1));
    if (col.kind == "if") return int(get_field(top.dbg_fall_o, kInPins * c + n, 1));
    if (col.kind == "t") return int(get_field(top.dbg_timer_status_o, BB_HW_STATUS_BITS * c + n, 1));
    if (col.kind == "c") return int(get_field(top.dbg_counter_status_o, BB_HW_STATUS_BITS * c + n, 1));
    if (col.kind == "m") {
      look(top.dbg_m_addr_i, kMAddrBits, c, n);
      return int(get_field(top.dbg_m_o, c, 1));
    }
    if (col.kind == "mw") {
      look(top.dbg_mw_addr_i, kMwAddrBits, c, n);
      return int16_t(get_field(top.dbg_mw_o, 16 * c, 16));
    }
    return 0;
  };

  // ---- the clocks
  for (Core& k : g_cores) {
    k.by_clock = k.cf->rf.stim_kind == "clock";
    k.by_scan = k.cf->rf.stim_kind == "scan";
    if (k.by_scan) apply_stim(k, 0);
  }
  const uint64_t until = uint64_t(pf.until_clock);
  bool fault = false;
  Progress progress;
  progress.fd = pf.progress_fd;
  progress.after_s = pf.progress_after_s;
  for (g_n = 0;; ++g_n) {
    if ((g_n & 0xFFFF) == 0 && progress.fd >= 0) {
      char what[96];
      std::snprintf(what, sizeof what, "bitbyte run (plant): %.3f s simulated",
                    double(g_n) / double(pf.clock_hz));
      progress.update(std::min(1.0, double(g_n) / double(until)), what);
    }
    for (Core& k : g_cores) {                         // inputs of clock g_n
      if (k.by_clock) apply_stim(k, g_n);
      const bool run = k.want == Core::kStart || k.want == Core::kBus ||
                       (k.want == Core::kSleep && g_n >= k.wake) ||
                       (k.want == Core::kWaitNext && get_field(top.byte_next_o, k.idx, 1));
      if (!run && !k.strobed) continue;            // an idle core: its bus stays idle
      k.re = k.we = false;
      if (run) swapcontext(&g_sched, &k.ctx);
      const bool access = k.want == Core::kBus;
      set_field(top.bus_addr_i, kBusAddrBits * k.idx, kBusAddrBits, k.addr);
      set_field(top.bus_wdata_i, 32 * k.idx, 32, k.wdata);
      set_field(top.bus_re_i, k.idx, 1, access && k.re);
      set_field(top.bus_we_i, k.idx, 1, access && k.we);
      k.strobed = access;
    }
    tick_half(0);
    for (Core& k : g_cores)
      if (k.want == Core::kBus) {
        k.ready = get_field(top.bus_ready_o, k.idx, 1);
        k.rdata = uint32_t(get_field(top.bus_rdata_o, 32 * k.idx, 32));
      }
    tick_half(1);
    bool all_done = true;
    for (Core& k : g_cores) {
      const unsigned c = k.idx;
      if (get_field(top.fault_o, c, 1)) fault = true;
      const bool cycle_done = get_field(top.cycle_done_o, c, 1);
      if (cycle_done && !k.finished) {
        const uint64_t cycles = get_field(top.scan_cycles_o, 32 * c, 32);
        const uint64_t pre = get_field(top.pre_clocks_o, 32 * c, 32);
        const uint64_t post = get_field(top.post_clocks_o, 32 * c, 32);
        const uint64_t wait = get_field(top.sem_wait_o, 32 * c, 32);
        const unsigned over = unsigned(get_field(top.overrun_o, c, 1));
        k.skips = get_field(top.skips_o, 32 * c, 32);
        if (k.trace) {
          char buf[64];
          char* e = put_t_us(buf, g_n + 1, pf.clock_hz);
          std::fprintf(k.trace, "%llu,%.*s,%llu,%llu,%llu,%llu,%u,%u", (unsigned long long)k.scans,
                       int(e - buf), buf, (unsigned long long)cycles, (unsigned long long)pre,
                       (unsigned long long)post, (unsigned long long)wait,
                       unsigned(get_field(top.copy_fail_o, c, 1)), over);
          for (size_t i = 0; i < k.cf->rf.cols.size(); ++i) std::fprintf(k.trace, ",%d", col_value(k, i));
          std::fputc('\n', k.trace);
        }
        ++k.scans;
        if (g_n + 1 >= until) k.finished = true;
      }
      // the next scan's scan-keyed inputs: after the row (its PI / IW columns are this
      // scan's), before the next latch
      if (cycle_done && k.by_scan) apply_stim(k, get_field(top.scan_count_o, 32 * c, 32));
      all_done = all_done && k.finished;
    }
    if (fault || all_done) { ++g_n; break; }
  }
  progress.finish();

  for (Core& k : g_cores)
    if (k.trace && std::fclose(k.trace) != 0) die("error writing %s", k.cf->rf.trace.c_str());
  if (wave) wave->close();
  top.final();
  if (fault) {
    for (Core& k : g_cores)
      if (get_field(top.fault_o, k.idx, 1))
        std::fprintf(stderr, "scan watchdog: core %s scan %llu exceeded %llu clocks\n", k.cf->name.c_str(),
                     (unsigned long long)k.scans, (unsigned long long)pf.watchdog);
  }

  // ---- figures for the run summary: `stat NAME VALUE` lines; `bitbyte run` prints the
  // summary from them and the traces (bitbyte/run/summary.py, one printer for every
  // simulator)
  std::printf("stat clocks %llu\n", (unsigned long long)g_n);
  // the plant's own time base (plc_system time_o), which the host checks against g_n
  std::printf("stat time_o %llu\n", (unsigned long long)top.time_o);
  for (Core& k : g_cores)
    std::printf("stat skips.%s %llu\n", k.cf->name.c_str(), (unsigned long long)k.skips);
  // each core's mode and exchange as driven on plc_system's parallel_i / exchange_i
  // (read back from the ports): the summary's mode labels come from these
  for (Core& k : g_cores) {
    std::printf("stat parallel.%s %llu\n", k.cf->name.c_str(),
                (unsigned long long)get_field(top.parallel_i, k.idx, 1));
    std::printf("stat exchange.%s %llu\n", k.cf->name.c_str(),
                (unsigned long long)get_field(top.exchange_i, 2 * k.idx, 2));
  }
  return fault ? 3 : 0;
}
