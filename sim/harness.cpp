// Verilator harness for bitbyte_cpu: runs one scan-by-scan simulation described by a
// run file (written by `bitbyte run`, or by hand) and writes TRACE.csv, an optional
// waveform and the run's figures (`stat` lines; bitbyte/run/summary.py prints them).  No Python in the loop: the whole run is C++, so a
// simulation costs microseconds per scan instead of a Python call per clock.
//
//   Vbitbyte_cpu RUNFILE
//
// The run file and the drive protocol are described in sim/README.md.  The protocol
// must match the Python reference model clock for clock (docs/isa.md "Timing model"):
// clock 0 is the PII latch of scan 0, pins for clock n are set before the rising edge
// that ends clock n, and a scan's end_clock is the number of clocks since clock 0
// when scan_done_o shows it.
//
// The model is observed through its ports only (rtl/bitbyte_cpu.v; the dbg_* ports
// carry what the trace needs beyond the functional ones) and evaluated through
// Verilator's public API (eval()): no Verilator internals, no public signals.
#include "Vbitbyte_cpu.h"
#include "verilated.h"

extern "C" {
#include "byteproc.h"  // the byte processor firmware (firmware_byte/), linked in
#include "bus_map.h"   // register addresses, generated from bitbyte/lang/definition.toml
#include "hal.h"
}
#include <csetjmp>
#include <deque>
#include <map>
// Waves: the build picks one format (Verilator allows one --trace-* per model).
#if VM_TRACE_FST
#include "verilated_fst_c.h"
typedef VerilatedFstC WaveWriter;
static const char* const kWaveExt = ".fst";
#elif VM_TRACE_VCD
#include "verilated_vcd_c.h"
typedef VerilatedVcdC WaveWriter;
static const char* const kWaveExt = ".vcd";
#else  // TRACE=none: a stand-in that is never opened
struct WaveWriter { void dump(uint64_t) {} void close() {} };
static const char* const kWaveExt = "";
#endif

#include "harness_common.h"

#ifndef BB_BIT_ENGINE
#define BB_BIT_ENGINE 0   // the scalar build (harness_wide.cpp: the wide one)
#endif

// ------------------------------------------------------------------ the DUT
// The port widths the harness relies on, checked against the generated build sizes.
static_assert(sizeof(Vbitbyte_cpu::in_pins_i) * 8 == kInPins, "in_pins_i: InBytes * 8");
static_assert(sizeof(Vbitbyte_cpu::dbg_pii_o) == sizeof(Vbitbyte_cpu::in_pins_i), "dbg_pii_o");
static_assert(sizeof(Vbitbyte_cpu::in_words_i) * 8 == 16 * kInWords, "in_words_i: InWords * 16");
static_assert(sizeof(Vbitbyte_cpu::out_words_o) * 8 == 16 * BB_HW_OUT_WORDS, "out_words_o");
static_assert(sizeof(Vbitbyte_cpu::out_pins_o) * 8 == 8 * BB_HW_OUT_BYTES, "out_pins_o");
static_assert(sizeof(Vbitbyte_cpu::dbg_timer_status_o) * 8 == BB_HW_STATUS_BITS, "StatusBits");

// One clock = falling half, rising half.  Waves get both halves.
struct Dut {
  std::unique_ptr<VerilatedContext> ctx{new VerilatedContext};
  std::unique_ptr<Vbitbyte_cpu> top;
  std::unique_ptr<WaveWriter> wave;
  uint64_t t_ps = 0, half_ps = 5000, period_ps = 10000;  // waveform time, 1 ps units

  void eval() { top->eval(); }
  void tick() {
    top->clk_i = 0;
    eval();
    if (wave) wave->dump(t_ps + half_ps);
    top->clk_i = 1;
    eval();
    t_ps += period_ps;
    if (wave) wave->dump(t_ps);
  }
};

// Where a trace column reads its value.
struct ColSrc {
  enum Kind { kBit, kMarker, kWord16, kMw, kZero } kind;
  const uint32_t* word;     // kBit: the 32-bit word of a packed vector; kWord16: vector base
  uint32_t mask;            // kBit
  uint32_t index;           // kWord16: word number; kMw: MW n; kMarker: M bit number
};

template <class W> static ColSrc wide_bit(const W& v, uint32_t idx, const Col& c) {
  const uint32_t bits = sizeof(W) * 8;
  if (idx >= bits) die("column %s: index %u out of range (0..%u)", c.header.c_str(), idx, bits - 1);
  return {ColSrc::kBit, reinterpret_cast<const uint32_t*>(&v) + idx / 32, 1u << (idx % 32), 0};
}

template <class W> static ColSrc word16(const W& v, uint32_t idx, const Col& c) {
  if (idx >= sizeof(W) / 2) die("column %s: word %u out of range", c.header.c_str(), idx);
  return {ColSrc::kWord16, reinterpret_cast<const uint32_t*>(&v), 0, idx};
}

// ------------------------------------------------------------------ the run
// The byte processor's firmware owns the main loop: it calls the HAL, and every HAL
// call that takes time runs clocks through Run::fall() / Run::end_clock(). Each clock
// n: the inputs of clock n are already applied; the HAL sets the bus; fall() evaluates
// the clock-low half (combinational outputs valid: bus read data); end_clock() makes
// the rising edge, records a finished scan, applies the inputs of clock n+1 and, when
// the run is over, jumps out of the firmware (longjmp back into main).
struct Run {
  Dut* d;
  Vbitbyte_cpu* top;
  const RunFile* rf;
  bb_state* bb;
  std::vector<ColSrc> srcs;
  TraceOut* out;
  uint64_t n = 0, scans = 0;
  uint64_t want_scans = UINT64_MAX, until = UINT64_MAX, until_min_scans = 0;
  bool fault = false, by_scan = false, by_clock = false;
  size_t next_stim = 0;
  uint64_t next_stim_clock = UINT64_MAX;
  std::jmp_buf stop;

  void apply_stim(uint64_t key) {  // the last row with KEY <= key, if any is due
    const Stim* st = nullptr;
    while (next_stim < rf->stim.size() && rf->stim[next_stim].key <= key) st = &rf->stim[next_stim++];
    if (!st) return;
    static_assert(sizeof st->pins == sizeof top->in_pins_i, "a stimulus row holds every pin");
    std::memcpy(&top->in_pins_i, st->pins, sizeof top->in_pins_i);
    if (st->has_words) {
      uint32_t* w = reinterpret_cast<uint32_t*>(&top->in_words_i);
      for (unsigned i = 0; i < kInWords; ++i) {
        w[i / 2] &= ~(0xFFFFu << (16 * (i % 2)));
        w[i / 2] |= uint32_t(uint16_t(st->words[i])) << (16 * (i % 2));
      }
    }
  }
  void inputs_for_clock() {  // clock stimulus: inputs of clock n, before its edge
    if (n == next_stim_clock) {
      apply_stim(n);
      next_stim_clock = next_stim < rf->stim.size() ? rf->stim[next_stim].key : UINT64_MAX;
    }
  }
  void fall() {
    top->clk_i = 0;
    d->eval();
    if (d->wave) d->wave->dump(d->t_ps + d->half_ps);
  }
  uint32_t value(const ColSrc& c) {
    switch (c.kind) {
      case ColSrc::kBit: return (*c.word & c.mask) ? 1 : 0;
      case ColSrc::kMarker:  // M[n] through the look-up port: settle it when n is new
        if (top->dbg_m_addr_i != c.index) {
          top->dbg_m_addr_i = c.index;
          top->eval();  // no clock edge: combinational only
        }
        return top->dbg_m_o & 1;
      case ColSrc::kWord16: return (c.word[c.index / 2] >> (16 * (c.index % 2))) & 0xFFFF;
      case ColSrc::kMw: return uint16_t(bb_mw(bb, c.index));
      default: return 0;
    }
  }
  void record() {  // a scan ended with clock n-1: its row, values after its END
    const uint64_t cycles = top->scan_cycles_o;
    if (!out->f) return;
    char* p = out->row();
    p = std::to_chars(p, p + 24, scans).ptr;
    *p++ = ',';
    p = put_t_us(p, n, rf->clock_hz);
    *p++ = ',';
    p = std::to_chars(p, p + 24, cycles).ptr;
    for (const ColSrc& c : srcs) {
      *p++ = ',';
      const uint32_t v = value(c);
      if (c.kind == ColSrc::kWord16 || c.kind == ColSrc::kMw) p = std::to_chars(p, p + 8, int(int16_t(v))).ptr;
      else *p++ = v ? '1' : '0';
    }
    *p++ = '\n';
    out->commit(p);
  }
  // Block status (bitbyte run --status): per address, the last retirement in the
  // chosen scan (its RLO after, the operand bit, the firmware's accumulators after it)
  // and how often the address retired in that scan.
  struct Status { uint64_t count = 0; unsigned rlo = 0, opnd = 0; int32_t accu1 = 0, accu2 = 0; };
  std::map<uint32_t, Status> status, byte_status;  // the bit processor's; the byte part's
  uint64_t byte_seq = 0;                              // byte-part instructions seen completed
  // --line-counts: how often each address retired over the whole run (every scan, and
  // in parallel and free-running mode the byte part's too, from the firmware's record)
  std::map<uint32_t, uint64_t> counts, byte_counts;
  uint64_t count_seq = 0;                             // byte-part instructions counted
  // --exchange-log: every condition that crosses, one line each, for a model of the
  // exchange (tests/exchange_model.py): the bit side's retirements with an FBI / FBY
  // operand (clock, its scan, the instruction word, the operand it read, the RLO after
  // it), the clock that latches each bit scan after scan 0 (`latch`), and the byte
  // side's channel and cell accesses and SCAN_DONE (clock, its scan, the address, bit 0
  // of the data, 1 for a write).
  FILE* xlog = nullptr;
  std::vector<uint32_t> bit_words;                    // the bit program, by address
  uint64_t byte_scans = 0;                            // SCAN_DONE writes so far
  void log_bit_exchange() {
    if (!xlog || !top->dbg_ret_valid_o) return;
    const uint32_t pc = top->dbg_ret_pc_o;
    if (pc >= bit_words.size() || ((bit_words[pc] >> BB_AREA_SHIFT) & BB_AREA_MASK) != BB_AREA_FB)
      return;
    std::fprintf(xlog, "%llu,bit,%llu,%u,%u,%u\n", (unsigned long long)(n - 1),
                 (unsigned long long)scans, bit_words[pc], unsigned(top->dbg_ret_opnd_o),
                 unsigned(top->dbg_rlo_o));
  }
  void log_byte_exchange(uint16_t addr, uint32_t data, bool write) {  // in its clock
    if (!xlog) return;
    const bool cell = addr >= BB_BUS_FBY(0) && addr < BB_BUS_FBI(0) + BB_BUS_CHANNELS;
    const bool window = addr >= BB_BUS_MCELL(0) && addr < BB_BUS_MCELL(0) + BB_BUS_MCELLS;
    if (!cell && !window && addr != BB_BUS_SCAN_DONE) return;
    std::fprintf(xlog, "%llu,byte,%llu,%u,%u,%u\n", (unsigned long long)n,
                 (unsigned long long)byte_scans, unsigned(addr), unsigned(data & 1),
                 unsigned(write));
    if (addr == BB_BUS_SCAN_DONE) ++byte_scans;
  }
  void count_retirement() {
    if (!rf->line_counts) return;
    if (top->dbg_ret_valid_o) ++counts[top->dbg_ret_pc_o];
    if ((rf->parallel || rf->free_running) && bb_ret_seq(bb) != count_seq) {
      count_seq = bb_ret_seq(bb);     // one completion per clock at most (see below)
      ++byte_counts[bb_ret_pc(bb)];
    }
  }
  void observe_retirement() {
    log_bit_exchange();
    count_retirement();
    if (int64_t(scans) != rf->status_scan) {
      byte_seq = bb_ret_seq(bb);
      return;
    }
    if (top->dbg_ret_valid_o) {
      Status& s = status[top->dbg_ret_pc_o];
      ++s.count;
      s.rlo = top->dbg_rlo_o;
      s.opnd = top->dbg_ret_opnd_o;
      s.accu1 = bb_accu1(bb);
      s.accu2 = bb_accu2(bb);
    }
    // parallel mode: the firmware's record of its byte part's last completed
    // instruction (every instruction but END_B takes a clock: none is missed)
    if (rf->parallel && bb_ret_seq(bb) != byte_seq) {
      byte_seq = bb_ret_seq(bb);
      Status& s = byte_status[bb_ret_pc(bb)];
      ++s.count;
      s.rlo = unsigned(bb_ret_rlo(bb));
      s.accu1 = bb_ret_accu1(bb);
      s.accu2 = bb_ret_accu2(bb);
    }
  }
  // --force: the host's writes of the force table (FORCE_*, docs/byte-bus.md) go over
  // the byte bus in clocks the byte processor leaves it idle (idle_clock), the table
  // for scan k during scan k; what changed since the last table only.
  std::deque<std::pair<uint16_t, uint32_t>> host_writes;
  uint32_t force_written[4][kInPinWords] = {};
  size_t next_force = 0;
  void queue_force(int64_t key) {
    if (next_force >= rf->force.size() || rf->force[next_force].key != key) return;
    const RunFile::Force& f = rf->force[next_force++];
    for (unsigned g = 0; g < 4; ++g)
      for (unsigned n = 0; n < kInPinWords; ++n)
        if (f.v[g][n] != force_written[g][n]) {
          host_writes.emplace_back(uint16_t(BB_BUS_FORCE_IN_MASK(0) + 4 * g + n), f.v[g][n]);
          force_written[g][n] = f.v[g][n];
        }
  }
  Progress progress;
  void show_progress() {
    if (progress.fd < 0) return;
    const double done = until != UINT64_MAX ? double(n) / double(until)
                      : want_scans != UINT64_MAX ? double(scans) / double(want_scans) : 0.0;
    char what[96];
    std::snprintf(what, sizeof what, "bitbyte run: scan %llu, %.3f s simulated",
                  (unsigned long long)scans, double(n) / double(rf->clock_hz));
    progress.update(std::min(done, 1.0), what);
  }
  void end_clock() {
    top->clk_i = 1;
    d->eval();
    d->t_ps += d->period_ps;
    if (d->wave) d->wave->dump(d->t_ps);
    top->bus_re_i = 0;
    top->bus_we_i = 0;
    ++n;
    if ((n & 0xFFFF) == 0) show_progress();
    observe_retirement();  // before scan_done: END retires in its scan's last clock
    if (top->fault_o) { fault = true; std::longjmp(stop, 1); }
    if (top->scan_done_o) {
      if (!host_writes.empty())  // the table would take effect a scan late: say so
        die("--force: the force table of scan %llu did not fit into that scan (%zu of its "
            "register writes left; it takes effect at the scan's END, so all must be "
            "written in clocks where the byte processor leaves the bus idle): a short "
            "scan, or one whose byte side keeps the bus busy; spread the changes over "
            "more scans", (unsigned long long)scans, host_writes.size());
      record();
      ++scans;
      if (xlog)  // END ran in the clock that just ended: this one latches the next scan
        std::fprintf(xlog, "%llu,bit,%llu,latch,0,0\n", (unsigned long long)n,
                     (unsigned long long)scans);
      queue_force(int64_t(scans));
      if (scans >= want_scans || (n >= until && scans >= until_min_scans)) std::longjmp(stop, 1);
      if (by_scan) apply_stim(scans);  // the next clock latches scan `scans`
    }
    inputs_for_clock();
  }
  void idle_clock() {
    if (!host_writes.empty()) {  // the bus is free in this clock: a host write
      top->bus_addr_i = host_writes.front().first;
      top->bus_wdata_i = host_writes.front().second;
      top->bus_we_i = 1;
      host_writes.pop_front();
    }
    fall();
    end_clock();
  }
  bool next() const { return top->byte_next_o; }
};

// ------------------------------------------------------------------ the HAL (hal.h)
// The firmware's HAL context (bb_set_hal_ctx) is the Run.
extern "C" uint32_t hal_bus_read(void* ctx, uint16_t addr) {
  Run& r = *static_cast<Run*>(ctx);
  for (;;) {
    r.top->bus_addr_i = addr;
    r.top->bus_re_i = 1;
    r.fall();
    const uint32_t data = r.top->bus_rdata_o;
    const bool ready = r.top->bus_ready_o;
    if (ready) r.log_byte_exchange(addr, data, false);
    // DISPATCH_CTX's scan number (for observation: the firmware does not use it) is
    // the scan the dispatch came from, low 16 bits
    if (ready && addr == BB_BUS_DISPATCH_CTX && !r.rf->free_running &&
        (data >> BB_CTX_SCAN_SHIFT) != (r.scans & 0xFFFFu))
      die("DISPATCH_CTX names scan %u in scan %llu", unsigned(data >> BB_CTX_SCAN_SHIFT),
          (unsigned long long)r.scans);
    r.end_clock();
    if (ready) return data;  // else: a byte-side stall, the access repeats
  }
}

extern "C" void hal_bus_write(void* ctx, uint16_t addr, uint32_t data) {
  Run& r = *static_cast<Run*>(ctx);
  for (;;) {
    r.top->bus_addr_i = addr;
    r.top->bus_wdata_i = data;
    r.top->bus_we_i = 1;
    r.fall();
    const bool ready = r.top->bus_ready_o;
    if (ready) r.log_byte_exchange(addr, data, true);
    r.end_clock();
    if (ready) return;
  }
}

extern "C" void hal_spend(void* ctx, uint32_t clocks) {
  Run& r = *static_cast<Run*>(ctx);
  for (uint32_t i = 0; i < clocks; ++i) r.idle_clock();
}

extern "C" void hal_wait_dispatch(void* ctx) {
  Run& r = *static_cast<Run*>(ctx);
  while (!r.next()) r.idle_clock();
}

extern "C" uint64_t hal_now(void* ctx) { return static_cast<Run*>(ctx)->n; }

static RunFile read_run_file(const char* path) {
  RunFile rf;
  for_each_run_line(path, [&](const std::vector<std::string>& w, const std::vector<size_t>& at,
                              const std::string& line) {
    if (!parse_run_key(rf, w, at, line)) die("unknown key '%s'", w[0].c_str());
  });
  check_run(rf, true);
  return rf;
}

int main(int argc, char** argv) {
  // +name=value after the run file: plusargs for the model ($value$plusargs), e.g. the
  // +mutsel=<id> of a mutant netlist (mutation/run_mutate.py).
  bool usage = argc < 2;
  for (int i = 2; i < argc; ++i) usage = usage || argv[i][0] != '+';
  if (usage) { std::fprintf(stderr, "usage: %s RUNFILE [+PLUSARG...]\n", argv[0]); return 2; }
  const RunFile rf = read_run_file(argv[1]);
  Dut d;
  d.ctx->commandArgs(argc, argv);
  if (!rf.waves.empty()) d.ctx->traceEverOn(true);  // before the model is built
  d.top.reset(new Vbitbyte_cpu{d.ctx.get(), "TOP"});
  Vbitbyte_cpu& top = *d.top;
  const uint32_t prog_words = BB_HW_PROG_WORDS;

  // The byte processor: firmware state, cost table, constant pool.
  static bb_state bb;
  const bb_costs* costs = bb_cost_table(rf.costs.c_str());
  if (!costs) die("unknown cost table '%s'", rf.costs.c_str());
  bb_init(&bb, costs);
  if (!rf.pool.empty()) bb_load_pool(&bb, rf.pool.data(), unsigned(rf.pool.size()));
  if (rf.parallel || rf.free_running) {  // the byte part: the byte processor's own program
    if (rf.byte_prog.empty()) die("mode parallel/free needs 'byte_prog'");
    std::vector<uint32_t> words;
    for (auto [a, w] : read_hex(rf.byte_prog, BB_PROG_WORDS)) {
      if (a >= words.size()) words.resize(a + 1, 0);
      words[a] = w;
    }
    if (bb_load_program(&bb, words.data(), unsigned(words.size())) != 0) die("byte part too large");
  }
  if (rf.clock_hz % 1000) die("clock_hz must be a whole number of kHz (the 1 ms time base)");

  TraceOut out;
  Run run;
  run.d = &d;
  run.top = &top;
  run.rf = &rf;
  run.bb = &bb;
  run.out = &out;
  bb_set_hal_ctx(&bb, &run);

  // Trace columns resolved once: the per-scan cost is a load each.
  for (const Col& c : rf.cols) {
    auto& srcs = run.srcs;
    if (c.kind == "q") srcs.push_back(wide_bit(top.out_pins_o, c.index, c));
    else if (c.kind == "pi") srcs.push_back(wide_bit(top.in_pins_i, c.index, c));
    else if (c.kind == "i") srcs.push_back(wide_bit(top.dbg_pii_o, c.index, c));
    else if (c.kind == "ir") srcs.push_back(wide_bit(top.dbg_rise_o, c.index, c));
    else if (c.kind == "if") srcs.push_back(wide_bit(top.dbg_fall_o, c.index, c));
    else if (c.kind == "qr") srcs.push_back(wide_bit(top.dbg_q_rise_o, c.index, c));
    else if (c.kind == "qf") srcs.push_back(wide_bit(top.dbg_q_fall_o, c.index, c));
    else if (c.kind == "t") srcs.push_back(wide_bit(top.dbg_timer_status_o, c.index, c));
    else if (c.kind == "c") srcs.push_back(wide_bit(top.dbg_counter_status_o, c.index, c));
    else if (c.kind == "qw") srcs.push_back(word16(top.out_words_o, c.index, c));
    else if (c.kind == "iw") srcs.push_back(word16(top.in_words_i, c.index, c));
    else if (c.kind == "mw") {
      if (c.index >= BB_NUM_MW) die("column %s: MW %u out of range", c.header.c_str(), c.index);
      srcs.push_back({ColSrc::kMw, nullptr, 0, c.index});
    } else if (c.kind == "m") {
      const uint32_t nm = BB_HW_MARKER_BYTES * 8;
      if (c.index >= nm) die("column %s: marker %u out of range (0..%u)", c.header.c_str(), c.index, nm - 1);
      srcs.push_back({ColSrc::kMarker, nullptr, 0, c.index});
    } else srcs.push_back({ColSrc::kZero, nullptr, 0, 0});
  }

  // Waveform: 1 ps resolution, real clock period, time 0 = start of reset.
  std::string wave_file = rf.waves;
  bool convert_vcd = false;
  if (!rf.waves.empty()) {
    d.period_ps = std::max<uint64_t>(2, (1000000000000ULL + rf.clock_hz / 2) / rf.clock_hz);
    d.half_ps = d.period_ps / 2;
#if VM_TRACE
    const bool want_vcd = rf.waves.size() > 4 && rf.waves.compare(rf.waves.size() - 4, 4, ".vcd") == 0;
    if (want_vcd != (std::strcmp(kWaveExt, ".vcd") == 0)) {
      // An FST build asked for VCD writes FST and converts with gtkwave's fst2vcd.
      if (want_vcd) { convert_vcd = true; wave_file = rf.waves + ".tmp.fst"; }
      else die("this harness was built for %s waves; rebuild with TRACE=fst", kWaveExt);
    }
    d.wave.reset(new WaveWriter);
    top.trace(d.wave.get(), 99);
    d.wave->set_time_unit("1ps");
    d.wave->set_time_resolution("1ps");
    d.wave->open(wave_file.c_str());
#else
    die("this harness was built without waves (TRACE=none)");
#endif
  }

  if (!rf.trace.empty()) {
    out.path = rf.trace;
    out.f = std::fopen(rf.trace.c_str(), "w");
    if (!out.f) die("cannot write trace %s", rf.trace.c_str());
    out.row_max = 3 * 24 + 8 * rf.cols.size() + 8;
    out.buf.resize(std::max<size_t>(1 << 20, 4 * out.row_max));
    std::fputs("scan,t_us,cycles", out.f);
    for (const Col& c : rf.cols) std::fprintf(out.f, ",%s", c.header.c_str());
    std::fputc('\n', out.f);
  }

  // ---- reset, program load, memory clear, time base, RUN (the protocol the Python
  // model assumes)
  const auto image = read_hex(rf.prog, prog_words);
  if (!rf.xlog.empty()) {
    run.xlog = std::fopen(rf.xlog.c_str(), "w");
    if (!run.xlog) die("cannot write %s", rf.xlog.c_str());
    std::fputs("clock,side,scan,at,value,rlo\n", run.xlog);
    for (auto [a, w] : image) {
      if (a >= run.bit_words.size()) run.bit_words.resize(a + 1, 0);
      run.bit_words[a] = w;
    }
  }
  top.rst_ni = 0;
  top.run_i = 0;
  top.watchdog_limit_i = uint32_t(rf.watchdog);
  std::memset(&top.in_pins_i, 0, sizeof top.in_pins_i);  // inputs count as 0 before clock 0
  top.clk_i = 1;
  top.eval();
  if (d.wave) d.wave->dump(0);
  d.tick();
  // the wide image's extension words (a LUT word's tables and operands), written with
  // their base words; every other word's is 0
  constexpr unsigned kExtLimbs = (BB_LUT_EXT_BITS + 31) / 32;
  std::map<uint32_t, HexWord> ext;
  if (!rf.prog_ext.empty()) {
    if (!BB_BIT_ENGINE) die("prog_ext: this harness is the scalar build (make harness-wide builds the wide one)");
    for (auto& [a, v] : read_hex_limbs(rf.prog_ext, prog_words, kExtLimbs, BB_LUT_EXT_BITS)) ext[a] = v;
    // every LUT word (tag BB_LUT_TAG_VALUE) has its extension word, every extension
    // word its base word: a missing one would run as a table of 0s without a word
    std::map<uint32_t, uint32_t> base(image.begin(), image.end());
    for (auto& [a, v] : ext)
      if (!base.count(a)) die("%s: an extension word at @%X, no program word there", rf.prog_ext.c_str(), a);
    for (auto& [a, w] : base)
      if ((w >> BB_LUT_TAG_SHIFT) == BB_LUT_TAG_VALUE && !ext.count(a))
        die("%s: the LUT word at @%X has no extension word", rf.prog_ext.c_str(), a);
  }
  for (auto [a, w] : image) {  // one word per clock, under reset
    top.prog_we_i = 1;
    top.prog_waddr_i = a;
    top.prog_wdata_i = w;
    const auto e = ext.find(a);
    for (unsigned l = 0; l < kExtLimbs; ++l)
      top.prog_ext_wdata_i[l] = e == ext.end() ? 0u : e->second[l];
    d.tick();
  }
  top.prog_we_i = 0;
  // the load port carries junk from now on (a host's bus does not stay at the last
  // word): a RAM that wrote without prog_we_i would change the program
  top.prog_waddr_i = 0;
  top.prog_wdata_i = 0xFFFFFFFFu;
  d.tick();
  top.rst_ni = 1;
  for (int i = 0; !top.ready_o; ++i) {  // the marker RAM clears itself, one bit a clock
    if (i > 1000000) die("ready_o never rose after reset");
    d.tick();
  }
  top.bus_addr_i = BB_BUS_TICK_DIV;  // clocks per ms, set before scan 0 (no clock of any scan)
  top.bus_wdata_i = uint32_t(rf.clock_hz / 1000);
  top.bus_we_i = 1;
  d.tick();
  top.bus_we_i = 0;
  run.progress.fd = rf.progress_fd;
  run.progress.after_s = rf.progress_after_s;
  run.progress.t0 = run.progress.last = std::chrono::steady_clock::now();
  run.queue_force(-1);  // --force: the table before RUN (applies at once), then scan 0's
  for (; !run.host_writes.empty(); run.host_writes.pop_front()) {
    top.bus_addr_i = run.host_writes.front().first;
    top.bus_wdata_i = run.host_writes.front().second;
    top.bus_we_i = 1;
    d.tick();
    top.bus_we_i = 0;
  }
  run.queue_force(0);
  top.parallel_i = rf.parallel;
  top.free_i = rf.free_running;
  top.exchange_i = rf.exchange;
  top.marker_write_buffer_i = rf.marker_write_buffer;
  top.run_i = 1;
  d.tick();  // IDLE sees run_i: the next clock is clock 0, the latch of scan 0
  const uint64_t t0_ps = d.t_ps;  // waveform time of clock 0 (the layout's first view)

  // ---- the scans: the firmware runs until Run::end_clock() jumps back here
  run.by_scan = rf.stim_kind == "scan";
  run.by_clock = rf.stim_kind == "clock";
  run.next_stim_clock = (run.by_clock && !rf.stim.empty()) ? rf.stim[0].key : UINT64_MAX;
  run.want_scans = rf.scans < 0 ? UINT64_MAX : uint64_t(rf.scans);
  run.until = rf.until_clock < 0 ? UINT64_MAX : uint64_t(rf.until_clock);
  run.until_min_scans = rf.until_min_scans;
  if (run.by_scan) run.apply_stim(0);
  run.inputs_for_clock();
  const auto wall0 = std::chrono::steady_clock::now();
  if (setjmp(run.stop) == 0) {
    // the firmware's own main loop, until Run::end_clock() jumps back here
    bb_run(&bb, rf.parallel ? BB_MODE_PARALLEL : rf.free_running ? BB_MODE_FREE
                                                                : BB_MODE_SERIAL);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  run.progress.finish();
  const uint64_t n = run.n, scans = run.scans;
  const bool fault = run.fault;

  if (fault) {
    std::fprintf(stderr, "scan watchdog: scan %llu exceeded %llu clocks\n",
                 (unsigned long long)scans, (unsigned long long)rf.watchdog);
    if (d.wave) { d.tick(); d.tick(); }  // show the outputs dropping to 0
  }
  // The status buffer's enable / pulse bits after the last scan (Fig. 2's bit -> byte
  // half: a serial dispatch's RLO, or `= T n` / `= C n`), read as a host reads them:
  // the bus read data is combinational, so no clock passes.
  uint32_t tc_inputs[4] = {0, 0, 0, 0};
  const uint16_t tc_regs[4] = {BB_BUS_T_ENABLE_LO, BB_BUS_T_ENABLE_HI, BB_BUS_C_PULSE_LO,
                               BB_BUS_C_PULSE_HI};
  if (!fault) {
    top.bus_we_i = 0;
    top.bus_re_i = 1;
    for (int i = 0; i < 4; ++i) {
      top.bus_addr_i = tc_regs[i];
      top.eval();
      if (!top.bus_ready_o) die("bus register 0x%02x not ready for a read", tc_regs[i]);
      tc_inputs[i] = top.bus_rdata_o;
    }
    top.bus_re_i = 0;
    top.eval();
  }
  if (out.f) {
    out.flush();
    if (std::fclose(out.f) != 0) die("error writing %s", rf.trace.c_str());
  }
  if (run.xlog && std::fclose(run.xlog) != 0) die("error writing %s", rf.xlog.c_str());
  if (d.wave) d.wave->close();
  top.final();
  if (convert_vcd) {
    const std::string cmd = "fst2vcd -f '" + wave_file + "' -o '" + rf.waves + "' >/dev/null";
    if (std::system(cmd.c_str()) != 0) die("fst2vcd failed (is gtkwave installed?): %s", cmd.c_str());
    std::remove(wave_file.c_str());
  }

  // ---- figures for the run summary: `stat NAME VALUE` lines (sim/README.md), which
  // `bitbyte run` turns into the summary text that every simulator shares
  // (bitbyte/run/summary.py). The trace holds the scans themselves.
  auto stat = [](const char* name, unsigned long long v) { std::printf("stat %s %llu\n", name, v); };
  stat("scans", scans);
  stat("clocks", n);
  stat("stalls_bit", top.stalls_bit_o);
  stat("stalls_byte", top.stalls_byte_o);
  if (rf.free_running) stat("byte_scans", bb_byte_scans(&bb));
  if (rf.exchange == BB_EXCHANGE_QUEUE_FREE) {
    stat("queue_overflows", top.dbg_queue_overflows_o);
    stat("queue_underflows", top.dbg_queue_underflows_o);
  }
  stat("byte_flags", bb_flags(&bb));
  stat("scan_count", top.scan_count_o);            // the CPU's own counters, which
  stat("scan_cycles_max", top.scan_cycles_max_o);  // the run summary cross-checks
  if (!fault) {
    stat("t_enable", uint64_t(tc_inputs[1]) << 32 | tc_inputs[0]);
    stat("c_pulse", uint64_t(tc_inputs[3]) << 32 | tc_inputs[2]);
  }
  if (!rf.waves.empty()) stat("wave_t0_ps", t0_ps);  // waves only: the layout's first view
  for (const auto& [pc, s] : run.status)  // with `status K` only: the block status
    std::printf("status %u %llu %u %u %d %d\n", pc, (unsigned long long)s.count, s.rlo,
                s.opnd, s.accu1, s.accu2);
  for (const auto& [pc, s] : run.byte_status)  // ... of the byte part (parallel mode)
    std::printf("bstatus %u %llu %u %d %d\n", pc, (unsigned long long)s.count, s.rlo,
                s.accu1, s.accu2);
  for (const auto& [pc, c] : run.counts)  // with `line_counts 1` only: the whole run
    std::printf("count %u %llu\n", pc, (unsigned long long)c);
  for (const auto& [pc, c] : run.byte_counts)
    std::printf("bcount %u %llu\n", pc, (unsigned long long)c);
  std::printf("stat wall_s %.6f\n", wall);
  return fault ? 3 : 0;
}
