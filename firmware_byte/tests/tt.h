/*
 * tt.h — a tiny test framework: CHECK / CHECK_EQ count checks and report failures
 * with file:line; RUN runs one test function and counts it. Plus the helpers every
 * test file shares (one bb_state S, the fake HAL, instruction builders).
 */
#ifndef TT_H
#define TT_H

#include <stdint.h>
#include <stdio.h>

#include "../bb_internal.h"
#include "../bus_map.h"
#include "../byteproc.h"
#include "../hal.h"
#include "fake_hal.h"

extern int tt_tests, tt_checks, tt_fails;
extern const char *tt_current;

#define CHECK(cond) do { \
    tt_checks++; \
    if (!(cond)) { tt_fails++; \
      fprintf(stderr, "%s:%d: [%s] CHECK(%s) failed\n", __FILE__, __LINE__, tt_current, #cond); } \
  } while (0)

#define CHECK_EQ(actual, expected) do { \
    long long tt_a_ = (long long)(actual), tt_e_ = (long long)(expected); \
    tt_checks++; \
    if (tt_a_ != tt_e_) { tt_fails++; \
      fprintf(stderr, "%s:%d: [%s] %s = %lld, expected %s = %lld\n", __FILE__, __LINE__, \
              tt_current, #actual, tt_a_, #expected, tt_e_); } \
  } while (0)

/* Access k of the fake HAL's log (FH.log[k]): its register and the clock it completed
 * in, two checks. */
#define CHECK_ACCESS(k, reg, clk) do { \
    CHECK_EQ(FH.log[k].addr, reg); \
    CHECK_EQ(FH.log[k].clock, clk); \
  } while (0)

#define RUN(fn) do { \
    int tt_f0_ = tt_fails; tt_current = #fn; tt_tests++; fn(); \
    if (tt_fails != tt_f0_) fprintf(stderr, "FAIL %s\n", #fn); \
  } while (0)

/* ------------------------------------------------------------------ shared helpers */

extern bb_state S;   /* the state under test */
extern int RLO;      /* F_B for bb_exec */

/* Fresh state, fresh fake HAL (FH, the state's HAL context), default table. */
static inline void setup(void) {
  fh_reset();
  bb_init(&S, NULL);
  bb_set_hal_ctx(&S, &FH);
  RLO = 0;
}

static inline int ex(uint32_t instr) { return bb_exec(&S, instr, &RLO); }

static inline uint32_t i_imm(int32_t v) { return BB_INSTR_IMM(BB_OP_L_IMM, (uint32_t)v); }
static inline uint32_t i_op(unsigned op) { return (uint32_t)op << 24; }
static inline uint32_t i_cmp(unsigned base, unsigned c) { return (uint32_t)(base + c) << 24; }
static inline uint32_t i_L(unsigned area, unsigned n) { return BB_INSTR(BB_OP_L_WORD, area, n); }
static inline uint32_t i_T(unsigned area, unsigned n) { return BB_INSTR(BB_OP_T_WORD, area, n); }
static inline uint32_t i_tmr(unsigned op, unsigned n) { return BB_INSTR(op, BB_AREA_T, n); }
static inline uint32_t i_ctr(unsigned op, unsigned n) { return BB_INSTR(op, BB_AREA_C, n); }
static inline uint32_t i_ch(unsigned op, unsigned k) { return BB_INSTR(op, BB_AREA_FB, k); }

/* L v (ACCU2 := ACCU1; ACCU1 := v). */
static inline void L(int32_t v) { ex(i_imm(v)); }

/* ACCU2 := a; ACCU1 := b; then op; returns the new ACCU1. */
static inline int32_t arith(int32_t a, unsigned op, int32_t b) {
  L(a);
  L(b);
  ex(i_op(op));
  return S.accu1;
}

/* One timer instruction at time `ms` (clock = ms * tick_div), enable = en, preset in
 * ACCU1. Returns the status it leaves. */
static inline int tmr(unsigned op, unsigned n, int en, int32_t preset, uint32_t ms) {
  S.accu1 = preset;
  RLO = en;
  fh_set_ms(ms);
  ex(i_tmr(op, n));
  return S.timer[n].status;
}

/* One counter instruction with RLO = r; returns the value. */
static inline int ctr(unsigned op, unsigned n, int r) {
  RLO = r;
  ex(i_ctr(op, n));
  return S.counter[n].value;
}

/* The suites (one per file). */
void suite_arith(void);
void suite_compare(void);
void suite_timers(void);
void suite_counters(void);
void suite_exchange(void);
void suite_serial(void);
void suite_bus(void);
void suite_costs(void);
void suite_program(void);
void suite_contexts(void);

#endif
