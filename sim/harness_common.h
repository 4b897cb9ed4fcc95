// harness_common.h — what the Verilator harnesses share (sim/harness.cpp for one CPU,
// sim/plant_harness.cpp for a multi-core plant): error exit, exact decimal output,
// the run-file keys of one CPU, $readmemh, the buffered trace writer.
#ifndef HARNESS_COMMON_H
#define HARNESS_COMMON_H
#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

typedef unsigned __int128 u128;
static const char* g_where = "harness";  // prefix of error messages

[[noreturn]] static void die(const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::fprintf(stderr, "%s: ", g_where);
  std::vfprintf(stderr, fmt, ap);
  std::fputc('\n', stderr);
  va_end(ap);
  std::exit(2);
}

// ------------------------------------------------------------------ decimal output
// num/den as a decimal: exact when it terminates within `places` digits, otherwise
// rounded half-up to `places`; trailing zeros and a trailing '.' removed (0.62, 12,
// 0.333333).  Integer arithmetic only: no float can turn 0.62 into 0.6199999.
static std::string fmt_ratio(u128 num, u128 den, unsigned places) {
  u128 scale = 1;
  for (unsigned i = 0; i < places; ++i) scale *= 10;
  const u128 scaled = num * scale;  // callers keep this below 2^128
  u128 v = scaled / den;
  if (2 * (scaled % den) >= den) ++v;
  std::string text;  // digits of v, least significant first, then reversed
  for (unsigned i = 0; i < places || v; ++i, v /= 10) {
    if (i == places && places) text += '.';
    text += char('0' + unsigned(v % 10));
  }
  if (text.size() == places) text += places ? ".0" : "0";  // v < 1: a leading "0."
  std::reverse(text.begin(), text.end());
  if (places) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

// The same rule for the per-scan t_us = end_clock * 10^6 / clock_hz at 6 places,
// in 64-bit arithmetic while end_clock * 10^12 fits (1.8e7 clocks), which is
// cheaper than fmt_ratio's 128-bit divisions and std::string.
static char* put_t_us(char* p, uint64_t end_clock, uint64_t clock_hz) {
  const uint64_t kE12 = 1000000000000ULL;
  uint64_t v;  // t in units of 10^-6 us
  if (end_clock <= UINT64_MAX / kE12) {
    uint64_t scaled = end_clock * kE12;
    v = scaled / clock_hz;
    if (2 * (scaled % clock_hz) >= clock_hz) ++v;  // clock_hz < 2^63, checked
  } else {
    std::string s = fmt_ratio(u128(end_clock) * 1000000u, clock_hz, 6);
    std::memcpy(p, s.data(), s.size());
    return p + s.size();
  }
  p = std::to_chars(p, p + 24, v / 1000000).ptr;
  uint64_t f = v % 1000000;
  if (f) {
    *p++ = '.';
    char d[6];
    for (int i = 5; i >= 0; --i, f /= 10) d[i] = char('0' + f % 10);
    int n = 6;
    while (d[n - 1] == '0') --n;
    std::memcpy(p, d, n);
    p += n;
  }
  return p;
}

// ------------------------------------------------------------------ settings
// A run-time setting's code: its name's position in the generated list (bb_isa.h
// BB_EXCHANGE_NAMES, BB_PROTECTION_NAMES, from the one definition).
template <size_t N>
static unsigned setting_code(const char* what, const char* const (&names)[N], const std::string& v) {
  std::string all;
  for (size_t i = 0; i < N; ++i) {
    if (v == names[i]) return unsigned(i);
    all += (i ? ", " : "") + std::string(names[i]);
  }
  die("%s must be one of %s, not '%s'", what, all.c_str(), v.c_str());
}

// ------------------------------------------------------------------ run file
// One CPU's (one plant core's) process inputs: the generated build sizes (bb_isa.h);
// each harness checks its model's ports against them.
constexpr unsigned kInPins = BB_HW_IN_BYTES * 8;                   // I 0.0 .. InBytes-1.7
constexpr unsigned kInPinWords = (kInPins + 31) / 32;
constexpr unsigned kInWords = BB_HW_IN_WORDS;                      // IW 0 .. InWords-1
static_assert(kInPins % 32 == 0, "the models store the pins in whole 32-bit words");

struct Stim {                                                      // one stimulus row
  uint64_t key;
  uint32_t pins[kInPinWords];                                      // word 0 = I0.0..I3.7
  bool has_words;
  int16_t words[kInWords];                                         // IW0..
};
struct Col  { std::string header, kind; uint32_t index; };

// Progress of a long run (`bitbyte run` on a terminal passes `progress FD [AFTER_S]`):
// from AFTER_S seconds of wall time on (default 2), at most once a second, one line
// rewritten in place on FD: where the run is, the share done and the time left.
struct Progress {
  int fd = -1;
  double after_s = 2.0;
  bool shown = false;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now(), last = t0;
  // done: the share done (0..1), what: where the run is, in words
  void update(double done, const char* what) {
    if (fd < 0) return;
    const auto now = std::chrono::steady_clock::now();
    const double run_s = std::chrono::duration<double>(now - t0).count();
    if (run_s < after_s || (shown && std::chrono::duration<double>(now - last).count() < 1.0)) return;
    last = now;
    shown = true;
    const double left = done > 0 ? run_s * (1 - done) / done : 0;
    dprintf(fd, "\r%s: %.0f %%, %.0f s so far, about %.0f s left   ", what, 100 * done, run_s, left);
  }
  void finish() { if (fd >= 0 && shown) dprintf(fd, "\n"); }
};

struct RunFile {
  std::string prog, trace, waves, gtkw = "sim/bitbyte.gtkw";
  std::string prog_ext;       // the wide image's extension words (.ext.hex; wide harness)
  uint64_t clock_hz = 100000000, watchdog = 100000;
  int64_t scans = -1, until_clock = -1;                          // -1: not given
  uint64_t until_min_scans = 0;  // until_clock counts from this many scans on (startup)
  std::string stim_kind = "none";
  std::vector<Stim> stim;
  std::vector<Col> cols;
  std::string costs = "paper";                                     // byte processor cost table
  std::vector<uint32_t> pool;                                      // constant pool
  bool parallel = false;                                           // mode parallel
  bool free_running = false;                                       // mode free
  unsigned exchange = 0;                                           // 0 handshake, 1 queue, 2 queue-free
  bool marker_write_buffer = false;                                // marker: publish at scan end
  std::string byte_prog;                                           // its byte part (.hex)
  int64_t status_scan = -1;                                        // block status of this scan
  bool line_counts = false;                                        // retirements per address, all scans
  std::string xlog;                                                // exchange log (--exchange-log)
  // --force: the force table (in mask, in values, out mask, out values) a host writes
  // during a scan (key: the scan; -1: before RUN), rows in ascending key order
  struct Force { int64_t key; uint32_t v[4][kInPinWords]; };
  std::vector<Force> force;
  int progress_fd = -1;                                            // progress lines go here
  double progress_after_s = 2.0;
};

static int hex_digit(char c) {  // -1 if c is no hex digit
  if (c >= '0' && c <= '9') return c - '0';
  c = char(std::tolower((unsigned char)c));
  return (c >= 'a' && c <= 'f') ? c - 'a' + 10 : -1;
}

static uint64_t parse_u64(const std::string& s, const char* what) {
  uint64_t v = 0;
  auto r = std::from_chars(s.data(), s.data() + s.size(), v, 10);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) die("bad %s '%s'", what, s.c_str());
  return v;
}

// Hex pin vector, most significant digit first, any length (leading digits beyond the
// last pin must be 0).
static void parse_pins(const std::string& s, uint32_t (&pins)[kInPinWords]) {
  std::memset(pins, 0, sizeof pins);
  unsigned bit = 0;
  for (auto it = s.rbegin(); it != s.rend(); ++it) {
    if (*it == '_') continue;
    const int d = hex_digit(*it);
    if (d < 0) die("bad hex pin vector '%s'", s.c_str());
    if (bit >= kInPins) { if (d) die("pin vector '%s' wider than %u bits", s.c_str(), kInPins); continue; }
    pins[bit / 32] |= uint32_t(d) << (bit % 32);
    bit += 4;
  }
}

// One `key value...` line of a run file that describes one CPU (harness.cpp) or one
// core of a plant (plant_harness.cpp). w: the words, at: where each starts in line.
// Returns false for a key it does not know.
static bool parse_run_key(RunFile& rf, const std::vector<std::string>& w,
                          const std::vector<size_t>& at, const std::string& line) {
  const std::string& k = w[0];
  auto want = [&](size_t n) { if (w.size() != n + 1) die("'%s' takes %zu value(s)", k.c_str(), n); };
  if (k == "prog")             { want(1); rf.prog = w[1]; }
  else if (k == "prog_ext")    { want(1); rf.prog_ext = w[1]; }
  else if (k == "trace")       { want(1); rf.trace = w[1]; }
  else if (k == "waves")       { want(1); rf.waves = w[1]; }
  else if (k == "gtkw")        { want(1); rf.gtkw = w[1]; }
  else if (k == "clock_hz")    { want(1); rf.clock_hz = parse_u64(w[1], "clock_hz"); }
  else if (k == "watchdog")    { want(1); rf.watchdog = parse_u64(w[1], "watchdog"); }
  else if (k == "scans")       { want(1); rf.scans = int64_t(parse_u64(w[1], "scans")); }
  else if (k == "until_clock") { want(1); rf.until_clock = int64_t(parse_u64(w[1], "until_clock")); }
  else if (k == "until_min_scans") { want(1); rf.until_min_scans = parse_u64(w[1], "until_min_scans"); }
  else if (k == "status")      { want(1); rf.status_scan = int64_t(parse_u64(w[1], "status scan")); }
  else if (k == "xlog")        { want(1); rf.xlog = w[1]; }
  else if (k == "line_counts") { want(1); rf.line_counts = parse_u64(w[1], "line_counts") != 0; }
  else if (k == "progress") {
    if (w.size() != 2 && w.size() != 3) die("'progress' takes FD [AFTER_S]");
    rf.progress_fd = int(parse_u64(w[1], "progress fd"));
    if (w.size() == 3) rf.progress_after_s = double(parse_u64(w[2], "progress after_s"));
  }
  else if (k == "force") {
    // force KEY INMASK INVAL OUTMASK OUTVAL: KEY a scan or `pre`; hex vectors as `stim`
    want(5);
    RunFile::Force f{};
    f.key = w[1] == "pre" ? -1 : int64_t(parse_u64(w[1], "force scan"));
    if (!rf.force.empty() && f.key <= rf.force.back().key) die("force keys must be ascending");
    for (int g = 0; g < 4; ++g) parse_pins(w[2 + g], f.v[g]);
    rf.force.push_back(f);
  }
  else if (k == "stim_kind") {
    want(1);
    if (w[1] != "none" && w[1] != "scan" && w[1] != "clock") die("stim_kind must be none, scan or clock");
    rf.stim_kind = w[1];
  } else if (k == "stim") {
    // stim KEY HEXPINS [IW0 .. IW15]: the input words, signed decimal, all of them
    if (w.size() != 3 && w.size() != 3 + kInWords)
      die("'stim' takes KEY HEXPINS [%u input words]", kInWords);
    Stim s{};
    s.key = parse_u64(w[1], "stim key");
    if (!rf.stim.empty() && s.key < rf.stim.back().key) die("stim keys must be ascending");
    parse_pins(w[2], s.pins);
    s.has_words = w.size() == 3 + kInWords;
    for (size_t i = 0; s.has_words && i < kInWords; ++i) {
      const std::string& t = w[3 + i];
      long v = std::strtol(t.c_str(), nullptr, 10);
      if (v < -32768 || v > 65535) die("input word '%s' out of range", t.c_str());
      s.words[i] = int16_t(uint16_t(v));
    }
    rf.stim.push_back(s);
  } else if (k == "mode") {
    want(1);
    if (w[1] != "serial" && w[1] != "parallel" && w[1] != "free")
      die("mode must be serial, parallel or free");
    rf.parallel = w[1] == "parallel";
    rf.free_running = w[1] == "free";
  } else if (k == "exchange") {
    want(1);
    static const char* const kExchanges[] = BB_EXCHANGE_NAMES;
    rf.exchange = setting_code("exchange", kExchanges, w[1]);
  } else if (k == "marker_write_buffer") {
    want(1);
    if (w[1] != "0" && w[1] != "1") die("marker_write_buffer must be 0 or 1");
    rf.marker_write_buffer = w[1] == "1";
  } else if (k == "byte_prog") {
    want(1);
    rf.byte_prog = w[1];
  } else if (k == "costs") {
    want(1);
    rf.costs = w[1];
  } else if (k == "pool") {
    for (size_t i = 1; i < w.size(); ++i)
      rf.pool.push_back(uint32_t(std::strtoul(w[i].c_str(), nullptr, 16)));
  } else if (k == "col") {
    // The header is all the text between `col` and the last two words: `--watch`
    // operands are named exactly as typed, and "I 0.1" is a valid one.
    if (w.size() < 4) die("'col' takes HEADER KIND INDEX");
    const size_t nw = w.size();
    std::string header = line.substr(at[1], at[nw - 2] - at[1]);
    header.erase(header.find_last_not_of(" \t") + 1);
    static const char* kinds[] = {"q", "qr", "qf", "i", "pi", "ir", "if", "m", "t", "c",
                                  "mw", "qw", "iw", "zero"};
    bool ok = false;
    for (const char* kk : kinds) ok |= (w[nw - 2] == kk);
    if (!ok) die("unknown column kind '%s'", w[nw - 2].c_str());
    rf.cols.push_back({header, w[nw - 2], uint32_t(parse_u64(w[nw - 1], "column index"))});
  } else {
    return false;
  }
  return true;
}

// Splits a run-file line into words (after removing a comment): w and their starts.
// '#' starts a comment at the line start or after a blank (not inside a header).
static void split_line(std::string& line, std::vector<std::string>& w, std::vector<size_t>& at) {
  for (size_t h = line.find('#'); h != std::string::npos; h = line.find('#', h + 1))
    if (h == 0 || std::isspace((unsigned char)line[h - 1])) { line.erase(h); break; }
  w.clear();
  at.clear();
  for (size_t i = 0; i < line.size();) {
    if (std::isspace((unsigned char)line[i])) { ++i; continue; }
    const size_t j = std::min(line.size(), line.find_first_of(" \t\r", i));
    at.push_back(i);
    w.push_back(line.substr(i, j - i));
    i = j;
  }
}

// Calls fn(words, their starts, the line) for every line of a run file that is not
// empty or a comment; meanwhile g_where is "path:line" for die()'s messages, and the
// path alone afterwards.
template <class F> static void for_each_run_line(const char* path, F fn) {
  std::ifstream in(path);
  if (!in) die("cannot open run file %s", path);
  std::string line, where_buf;
  std::vector<std::string> w;
  std::vector<size_t> at;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    where_buf = std::string(path) + ":" + std::to_string(lineno);
    g_where = where_buf.c_str();
    split_line(line, w, at);
    if (!w.empty()) fn(w, at, line);
  }
  g_where = path;
}

// What every run needs, checked after the whole file is read.
static void check_run(const RunFile& rf, bool need_stop) {
  if (rf.prog.empty()) die("no 'prog'");
  if (need_stop && rf.scans < 0 && rf.until_clock < 0) die("need 'scans' or 'until_clock'");
  if (rf.clock_hz == 0 || rf.clock_hz >= (1ULL << 62)) die("clock_hz out of range");
  if (rf.watchdog > 0xFFFFFFFFULL) die("watchdog exceeds 32 bits");
  if (rf.stim_kind == "none" && !rf.stim.empty()) die("stim rows with stim_kind none");
}

// $readmemh subset: hex words separated by white space, // comments, @ADDR jumps; a
// word of up to `limbs` x 32 bits, least significant limb first.
using HexWord = std::vector<uint32_t>;
static std::vector<std::pair<uint32_t, HexWord>> read_hex_limbs(const std::string& path,
                                                                uint32_t words, unsigned limbs,
                                                                unsigned bits = 0) {
  if (bits == 0) bits = 32 * limbs;   // a word's width (at most limbs x 32 bits)
  std::ifstream in(path);
  if (!in) die("cannot open program %s", path.c_str());
  std::vector<std::pair<uint32_t, HexWord>> image;  // (address, word), in file order
  uint32_t addr = 0;
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    if (auto c = line.find("//"); c != std::string::npos) line.erase(c);
    std::istringstream ls(line);
    for (std::string t; ls >> t;) {
      bool jump = (t[0] == '@');
      HexWord v(limbs, 0);
      unsigned digits = 0;
      for (size_t i = jump; i < t.size(); ++i) {
        if (t[i] == '_') continue;
        const int d = hex_digit(t[i]);
        if (d < 0) die("%s:%d: bad hex '%s'", path.c_str(), lineno, t.c_str());
        if (++digits > (jump ? 8 : (bits + 3) / 4))
          die("%s:%d: '%s' wider than %u bits", path.c_str(), lineno, t.c_str(), jump ? 32 : bits);
        for (unsigned l = limbs; l-- > 1;) v[l] = v[l] << 4 | v[l - 1] >> 28;   // v = v*16 + d
        v[0] = v[0] << 4 | unsigned(d);
      }
      if (jump) { addr = v[0]; continue; }
      if (addr >= words) die("%s:%d: program longer than %u words", path.c_str(), lineno, words);
      image.push_back({addr++, v});
    }
  }
  return image;
}

static std::vector<std::pair<uint32_t, uint32_t>> read_hex(const std::string& path, uint32_t words) {
  std::vector<std::pair<uint32_t, uint32_t>> image;
  for (auto& [a, v] : read_hex_limbs(path, words, 1)) image.push_back({a, v[0]});
  return image;
}

// TRACE.csv rows are formatted straight into a large buffer that is written in big
// blocks, instead of one (locking) stdio call per row.
struct TraceOut {
  std::FILE* f = nullptr;
  std::string path;
  std::vector<char> buf;
  size_t used = 0, row_max = 0;  // row_max: longest possible row

  char* row() {
    if (used + row_max > buf.size()) flush();
    return buf.data() + used;
  }
  void commit(const char* end) { used = size_t(end - buf.data()); }
  void flush() {
    if (used && std::fwrite(buf.data(), 1, used, f) != used) die("error writing %s", path.c_str());
    used = 0;
  }
};

#endif  // HARNESS_COMMON_H
