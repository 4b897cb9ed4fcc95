/* test_counters.c — CU CD, S C n, R C n, saturation and the three edge memories. */
#include "tt.h"

#define CS(n) ((int)((FH.c_status >> (n)) & 1u))   /* what the bit side reads */

static void test_cu(void) {
  setup();
  CHECK_EQ(ctr(BB_OP_CU, 1, 1), 1);   /* edge memory 0 after reset: counts */
  CHECK_EQ(CS(1), 1);
  CHECK_EQ(ctr(BB_OP_CU, 1, 1), 1);   /* RLO still 1: no edge */
  CHECK_EQ(ctr(BB_OP_CU, 1, 0), 1);
  CHECK_EQ(S.counter[1].cu_edge, 0);
  CHECK_EQ(ctr(BB_OP_CU, 1, 1), 2);
  CHECK_EQ(S.counter[1].cu_edge, 1);
  CHECK_EQ(RLO, 1);                   /* counters leave the RLO */
  CHECK_EQ(S.rlo_written, 0);
  ex(i_L(BB_AREA_C, 1));              /* L C n */
  CHECK_EQ(S.accu1, 2);
  CHECK_EQ(bb_counter_status(&S, 1), 1);
}

static void test_cd_and_saturation(void) {
  setup();
  CHECK_EQ(ctr(BB_OP_CD, 2, 1), 0);   /* saturates at 0 */
  CHECK_EQ(CS(2), 0);
  CHECK_EQ(ctr(BB_OP_CD, 2, 0), 0);
  CHECK_EQ(ctr(BB_OP_CD, 2, 1), 0);
  /* load 3 and count down to 0 */
  L(3);
  CHECK_EQ(ctr(BB_OP_SC, 2, 1), 3);
  CHECK_EQ(CS(2), 1);
  for (int want = 2; want >= 0; want--) {
    ctr(BB_OP_CD, 2, 0);
    CHECK_EQ(ctr(BB_OP_CD, 2, 1), want);
  }
  CHECK_EQ(CS(2), 0);
  CHECK_EQ(bb_counter_status(&S, 2), 0);
  ctr(BB_OP_CD, 2, 0);
  CHECK_EQ(ctr(BB_OP_CD, 2, 1), 0);
  /* up: saturates at 32767 */
  setup();
  L(32766);
  ctr(BB_OP_SC, 3, 1);
  CHECK_EQ(ctr(BB_OP_CU, 3, 1), 32767);
  CHECK_EQ(ctr(BB_OP_CU, 3, 0), 32767);
  CHECK_EQ(ctr(BB_OP_CU, 3, 1), 32767);
  CHECK_EQ(ctr(BB_OP_CD, 3, 1), 32766);
}

static void test_cu_cd_own_edges(void) {
  setup();
  /* CU and CD on one counter with RLO 1 each: each sees its own 0 -> 1 */
  CHECK_EQ(ctr(BB_OP_CU, 4, 1), 1);
  CHECK_EQ(ctr(BB_OP_CD, 4, 1), 0);
  CHECK_EQ(ctr(BB_OP_CU, 4, 1), 0);   /* CU edge is 1: no count */
  CHECK_EQ(S.counter[4].cu_edge, 1);
  CHECK_EQ(S.counter[4].cd_edge, 1);
  CHECK_EQ(S.counter[4].s_edge, 0);
}

static void test_set(void) {
  static const struct { int32_t accu1; int value; } rows[] = {
    {100, 100}, {-5, 0}, {32767, 32767}, {0, 0},
    {40000, 0},     /* INT(40000) = -25536 -> 0 */
    {70000, 4464},  /* INT(70000) = 4464 */
    {65535, 0},     /* INT = -1 */
    {-32768, 0},
  };
  for (unsigned i = 0; i < sizeof rows / sizeof rows[0]; i++) {
    setup();
    L(rows[i].accu1);
    CHECK_EQ(ctr(BB_OP_SC, 5, 1), rows[i].value);
    CHECK_EQ(CS(5), rows[i].value > 0);
  }
  /* the S edge memory: no reload while the RLO stays 1 */
  setup();
  L(10);
  CHECK_EQ(ctr(BB_OP_SC, 6, 1), 10);
  L(20);
  CHECK_EQ(ctr(BB_OP_SC, 6, 1), 10);
  CHECK_EQ(ctr(BB_OP_SC, 6, 0), 10);  /* RLO 0: no load, edge := 0 */
  CHECK_EQ(S.counter[6].s_edge, 0);
  CHECK_EQ(ctr(BB_OP_SC, 6, 1), 20);
  /* S C n leaves the accumulators */
  CHECK_EQ(S.accu1, 20);
  CHECK_EQ(S.accu2, 10);
}

static void test_reset(void) {
  setup();
  ctr(BB_OP_CU, 7, 1);
  ctr(BB_OP_CU, 7, 0);
  ctr(BB_OP_CU, 7, 1);
  CHECK_EQ(bb_counter_value(&S, 7), 2);
  CHECK_EQ(ctr(BB_OP_RC, 7, 0), 2);   /* RLO 0: nothing */
  CHECK_EQ(ctr(BB_OP_RC, 7, 1), 0);
  CHECK_EQ(CS(7), 0);
  /* edge memories untouched: CU's is still 1, so RLO 1 does not count */
  CHECK_EQ(S.counter[7].cu_edge, 1);
  CHECK_EQ(ctr(BB_OP_CU, 7, 1), 0);
  CHECK_EQ(ctr(BB_OP_CU, 7, 0), 0);
  CHECK_EQ(ctr(BB_OP_CU, 7, 1), 1);
  /* R C n does not write the edge memories either way */
  S.counter[7].cd_edge = 0;
  S.counter[7].s_edge = 1;
  ctr(BB_OP_RC, 7, 1);
  ctr(BB_OP_RC, 7, 0);
  CHECK_EQ(S.counter[7].cu_edge, 1);
  CHECK_EQ(S.counter[7].cd_edge, 0);
  CHECK_EQ(S.counter[7].s_edge, 1);
}

static void test_worked_example(void) {
  /* spec §3: LD I0.0, CU C1, L C1, T MW0 with I0.0 = 1 from scan 0:
   * MW0 = 1 and C1 = 1 in every scan (one count, in scan 0). */
  setup();
  for (int scan = 0; scan < 4; scan++) {
    bb_scan_start(&S);
    RLO = 1;                          /* LD I0.0 */
    ex(i_ctr(BB_OP_CU, 1));
    ex(i_L(BB_AREA_C, 1));
    ex(i_T(BB_AREA_MW, 0));
    CHECK_EQ(bb_mw(&S, 0), 1);
    CHECK_EQ(CS(1), 1);
  }
}

static void test_range(void) {
  setup();
  CHECK_EQ(ctr(BB_OP_CU, 63, 1), 1);
  CHECK_EQ(CS(63), 1);
  CHECK_EQ(FH.t_status, 0);           /* the counter bit, not the timer bit */
  CHECK_EQ(ex(i_ctr(BB_OP_CU, 64)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(BB_INSTR(BB_OP_CU, BB_AREA_T, 1)), BB_CL_ILLEGAL);
  CHECK_EQ(bb_counter_value(&S, 64), 0);
  CHECK_EQ(S.flags, BB_FLAG_ILLEGAL);
}

/* --tc-path status: a flagged CU / CD / S C takes its input from C_PULSE bit n (the bit
 * side's `= C n`) and counts the rising edges it sees there, F_B left as it was. */
static void test_from_status(void) {
  setup();
  const uint32_t cu = i_ctr(BB_OP_CU, 33) | BB_FROM_STATUS;
  RLO = 1;                                   /* F_B 1 throughout: ignored */
  FH.c_pulse = 0;
  ex(cu);
  CHECK_EQ(S.counter[33].value, 0);
  FH.c_pulse = 1ull << 33;
  ex(cu);
  CHECK_EQ(S.counter[33].value, 1);          /* 0 -> 1 seen */
  ex(cu);
  CHECK_EQ(S.counter[33].value, 1);          /* still 1: no edge */
  FH.c_pulse = 0;
  ex(cu);
  FH.c_pulse = 1ull << 33;
  ex(cu);
  CHECK_EQ(S.counter[33].value, 2);
  CHECK_EQ(CS(33), 1);
  CHECK_EQ(RLO, 1);
  /* CD and S C through the buffer too */
  FH.c_pulse = 0;
  ex(i_ctr(BB_OP_CD, 33) | BB_FROM_STATUS);
  FH.c_pulse = 1ull << 33;
  ex(i_ctr(BB_OP_CD, 33) | BB_FROM_STATUS);
  CHECK_EQ(S.counter[33].value, 1);
  L(7);
  ex(i_ctr(BB_OP_SC, 33) | BB_FROM_STATUS);  /* S edge memory 0 -> input 1: load */
  CHECK_EQ(S.counter[33].value, 7);
  RLO = 1;
  FH.c_pulse = 0;                            /* R C with F_B 1 but input 0: kept */
  ex(i_ctr(BB_OP_RC, 33) | BB_FROM_STATUS);
  CHECK_EQ(S.counter[33].value, 7);
}

/* The bit side writes C 40's input (1) and its written bit only after the third
 * not-ready clock of the TC_WAIT read (the fake HAL's after-access hook plays the bit
 * side): a flagged CU with the status wait selects C 40, stalls until then and counts
 * the 1 written this scan, not the 0 C_PULSE held before; without the wait the same
 * instruction reads the stale 0. */
static unsigned stalls_before_write;
static void bit_side_writes_c40(void *arg) {
  (void)arg;
  if (FH.tc_wait_stalls == stalls_before_write && !(FH.c_written >> 40 & 1u)) {
    FH.c_pulse |= 1ull << 40;
    FH.c_written |= 1ull << 40;
  }
}

static void test_status_wait(void) {
  setup();
  const uint32_t cu = i_ctr(BB_OP_CU, 40) | BB_FROM_STATUS;
  FH.c_pulse = 0;
  FH.t_written = 1ull << 40;                 /* timer 40 and counter 39: not this one */
  FH.c_written = 1ull << 39;
  stalls_before_write = 3;
  FH.after_access = bit_side_writes_c40;
  ex(cu | BB_STATUS_WAIT);
  CHECK_EQ(FH.tc_wait_sel, BB_TC_COUNTER | 40u);
  CHECK_EQ(FH.tc_wait_stalls, 3u);
  CHECK_EQ(S.counter[40].value, 1);          /* this scan's input: 0 -> 1 counted */
  /* a new scan: the latch clears the written bits; the input drops to 0 at once */
  FH.c_written = 0;
  FH.c_pulse = 0;
  FH.tc_wait_stalls = 0;
  FH.after_access = NULL;
  ex(cu);                                    /* no wait: reads the 0 of before */
  CHECK_EQ(FH.tc_wait_stalls, 0u);
  FH.after_access = bit_side_writes_c40;
  stalls_before_write = 2;
  ex(cu | BB_STATUS_WAIT);
  CHECK_EQ(FH.tc_wait_stalls, 2u);
  CHECK_EQ(S.counter[40].value, 2);          /* the next edge */
  FH.after_access = NULL;
  /* a timer selects without the counter bit */
  FH.t_written = FH.t_enable = 1ull << 5;
  S.accu1 = 5;
  ex(i_tmr(BB_OP_SD, 5) | BB_FROM_STATUS | BB_STATUS_WAIT);
  CHECK_EQ(FH.tc_wait_sel, 5u);
}

void suite_counters(void) {
  RUN(test_from_status);
  RUN(test_status_wait);
  RUN(test_cu);
  RUN(test_cd_and_saturation);
  RUN(test_cu_cd_own_edges);
  RUN(test_set);
  RUN(test_reset);
  RUN(test_worked_example);
  RUN(test_range);
}
