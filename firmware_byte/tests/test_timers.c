/* test_timers.c — SD SS SP SF and R T n with a fake time base (1000 clocks per ms).
 * Each step: tmr(kind, n, enable, preset, now_ms) -> status; then the elapsed value. */
#include "tt.h"

#define EL(n) bb_timer_elapsed(&S, (n))
#define TC(n) ((int)((FH.t_status >> (n)) & 1u))   /* what the bit side reads */

static void test_sd(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 0), 0);   /* rising: start at 0 */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(bb_timer_running(&S, 1), 1);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 3), 0);
  CHECK_EQ(EL(1), 3);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 4), 0);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 5), 1);   /* preset reached */
  CHECK_EQ(EL(1), 5);
  CHECK_EQ(TC(1), 1);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 9), 1);
  CHECK_EQ(EL(1), 5);                       /* min(d, preset) */
  /* status and elapsed change only when an instruction on the timer executes */
  fh_set_ms(100);
  ex(i_L(BB_AREA_T, 1));
  CHECK_EQ(S.accu1, 5);
  CHECK_EQ(bb_timer_status(&S, 1), 1);
  CHECK_EQ(tmr(BB_OP_SD, 1, 0, 5, 10), 0);  /* enable 0: stop */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(bb_timer_running(&S, 1), 0);
  CHECK_EQ(TC(1), 0);
  CHECK_EQ(tmr(BB_OP_SD, 1, 0, 5, 11), 0);
  /* start, stop before the preset, start again from 0 */
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 20), 0);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 23), 0);
  CHECK_EQ(EL(1), 3);
  CHECK_EQ(tmr(BB_OP_SD, 1, 0, 5, 24), 0);
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 26), 0);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 30), 0);  /* d = 4: the old start (20) is gone */
  CHECK_EQ(EL(1), 4);
  CHECK_EQ(tmr(BB_OP_SD, 1, 1, 5, 31), 1);
  /* L T n loads the elapsed ms */
  ex(i_L(BB_AREA_T, 1));
  CHECK_EQ(S.accu1, 5);
}

static void test_sd_preset_instant(void) {
  /* enable drops exactly when d = preset: the execution sees enable 0 -> status 0 */
  setup();
  CHECK_EQ(tmr(BB_OP_SD, 2, 1, 5, 20), 0);
  CHECK_EQ(tmr(BB_OP_SD, 2, 0, 5, 25), 0);
  CHECK_EQ(EL(2), 0);
  CHECK_EQ(TC(2), 0);
  /* the same instant with enable still 1 -> status 1 */
  CHECK_EQ(tmr(BB_OP_SD, 3, 1, 5, 20), 0);
  CHECK_EQ(tmr(BB_OP_SD, 3, 1, 5, 25), 1);
  CHECK_EQ(EL(3), 5);
  CHECK_EQ(TC(3), 1);
}

static void test_sd_preset_zero_and_negative(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SD, 4, 1, 0, 7), 1);   /* status 1 at once */
  CHECK_EQ(EL(4), 0);
  CHECK_EQ(TC(4), 1);
  CHECK_EQ(tmr(BB_OP_SD, 4, 1, 0, 9), 1);
  CHECK_EQ(EL(4), 0);
  CHECK_EQ(tmr(BB_OP_SD, 4, 0, 0, 10), 0);
  CHECK_EQ(tmr(BB_OP_SD, 5, 1, -5, 7), 1);  /* negative counts as 0 */
  CHECK_EQ(EL(5), 0);
  CHECK_EQ(tmr(BB_OP_SD, 5, 1, INT32_MIN, 8), 1);
  /* the preset is ACCU1's full 32 bits: 70000 ms is not INT(70000) = 4464 */
  CHECK_EQ(tmr(BB_OP_SD, 6, 1, 70000, 0), 0);
  CHECK_EQ(tmr(BB_OP_SD, 6, 1, 70000, 4464), 0);
  CHECK_EQ(EL(6), 4464);
  CHECK_EQ(tmr(BB_OP_SD, 6, 1, 70000, 70000), 1);
  CHECK_EQ(EL(6), 70000);
}

static void test_sd_preset_reread(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SD, 7, 1, 10, 40), 0);
  CHECK_EQ(tmr(BB_OP_SD, 7, 1, 10, 45), 0);
  CHECK_EQ(EL(7), 5);
  CHECK_EQ(tmr(BB_OP_SD, 7, 1, 5, 46), 1);  /* a smaller preset: d = 6 >= 5 */
  CHECK_EQ(EL(7), 5);
  CHECK_EQ(tmr(BB_OP_SD, 7, 1, 20, 47), 0); /* larger again: d = 7 < 20 */
  CHECK_EQ(EL(7), 7);
}

static void test_ss(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 0), 0);   /* start at 0 */
  CHECK_EQ(tmr(BB_OP_SS, 1, 0, 5, 2), 0);   /* retentive: enable 0 does not stop */
  CHECK_EQ(EL(1), 2);
  CHECK_EQ(bb_timer_running(&S, 1), 1);
  CHECK_EQ(tmr(BB_OP_SS, 1, 0, 5, 5), 1);   /* d >= preset, whatever enable */
  CHECK_EQ(EL(1), 5);
  CHECK_EQ(TC(1), 1);
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 7), 1);   /* rising while running: restart at 7 */
  CHECK_EQ(EL(1), 0);                       /* status stays 1 until R T n */
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 9), 1);
  CHECK_EQ(EL(1), 2);
  CHECK_EQ(tmr(BB_OP_SS, 1, 0, 5, 30), 1);
  CHECK_EQ(EL(1), 5);
  /* R T n */
  RLO = 1;
  fh_set_ms(31);
  ex(i_tmr(BB_OP_RT, 1));
  CHECK_EQ(bb_timer_status(&S, 1), 0);
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(bb_timer_running(&S, 1), 0);
  CHECK_EQ(TC(1), 0);
  CHECK_EQ(tmr(BB_OP_SS, 1, 0, 5, 40), 0);  /* stopped: nothing */
  CHECK_EQ(bb_timer_running(&S, 1), 0);
  CHECK_EQ(EL(1), 0);
  /* restart while running before the preset */
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 50), 0);  /* start at 50 */
  CHECK_EQ(tmr(BB_OP_SS, 1, 0, 5, 53), 0);
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 54), 0);  /* restart at 54 */
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 58), 0);  /* d = 4 (not 8) */
  CHECK_EQ(EL(1), 4);
  CHECK_EQ(tmr(BB_OP_SS, 1, 1, 5, 59), 1);
  /* preset 0 */
  CHECK_EQ(tmr(BB_OP_SS, 2, 1, 0, 3), 1);
}

static void test_sp(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SP, 1, 1, 5, 0), 1);   /* rising: pulse starts */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(TC(1), 1);
  CHECK_EQ(tmr(BB_OP_SP, 1, 0, 5, 2), 1);   /* 1 while d < preset, whatever enable */
  CHECK_EQ(EL(1), 2);
  CHECK_EQ(tmr(BB_OP_SP, 1, 1, 5, 3), 1);   /* rising during the pulse: no retrigger */
  CHECK_EQ(EL(1), 3);
  CHECK_EQ(tmr(BB_OP_SP, 1, 1, 5, 5), 0);   /* pulse over (from 0, not from 3) */
  CHECK_EQ(EL(1), 5);
  CHECK_EQ(bb_timer_running(&S, 1), 1);     /* enable still 1: holds */
  CHECK_EQ(TC(1), 0);
  CHECK_EQ(tmr(BB_OP_SP, 1, 1, 5, 8), 0);
  CHECK_EQ(EL(1), 5);
  CHECK_EQ(tmr(BB_OP_SP, 1, 0, 5, 9), 0);   /* enable 0 and d >= preset: stop */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(bb_timer_running(&S, 1), 0);
  CHECK_EQ(tmr(BB_OP_SP, 1, 1, 5, 10), 1);  /* a new pulse */
  CHECK_EQ(EL(1), 0);
  /* enable dropped during the pulse: the pulse still lasts preset */
  setup();
  CHECK_EQ(tmr(BB_OP_SP, 2, 1, 5, 20), 1);
  CHECK_EQ(tmr(BB_OP_SP, 2, 0, 5, 22), 1);
  CHECK_EQ(tmr(BB_OP_SP, 2, 0, 5, 24), 1);
  CHECK_EQ(EL(2), 4);
  CHECK_EQ(tmr(BB_OP_SP, 2, 0, 5, 25), 0);  /* d = 5: over and stopped */
  CHECK_EQ(EL(2), 0);
  CHECK_EQ(bb_timer_running(&S, 2), 0);
  /* rising while still running but with d >= preset: starts anew */
  setup();
  CHECK_EQ(tmr(BB_OP_SP, 3, 1, 5, 30), 1);
  CHECK_EQ(tmr(BB_OP_SP, 3, 0, 5, 31), 1);  /* d = 1: keeps running */
  CHECK_EQ(tmr(BB_OP_SP, 3, 1, 5, 40), 1);  /* rising, d = 10 >= 5: restart at 40 */
  CHECK_EQ(EL(3), 0);
  CHECK_EQ(tmr(BB_OP_SP, 3, 1, 5, 44), 1);
  CHECK_EQ(tmr(BB_OP_SP, 3, 1, 5, 45), 0);
  /* preset 0: no pulse at all */
  CHECK_EQ(tmr(BB_OP_SP, 4, 1, 0, 50), 0);
  CHECK_EQ(EL(4), 0);
}

static void test_sf(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 0), 0);   /* enable 0 from reset: no falling edge */
  CHECK_EQ(bb_timer_running(&S, 1), 0);
  CHECK_EQ(tmr(BB_OP_SF, 1, 1, 5, 1), 1);   /* enable 1: status 1 */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(TC(1), 1);
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 2), 1);   /* falling: start at 2 */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 4), 1);
  CHECK_EQ(EL(1), 2);
  CHECK_EQ(tmr(BB_OP_SF, 1, 1, 5, 5), 1);   /* enable again before expiry: stop */
  CHECK_EQ(EL(1), 0);
  CHECK_EQ(bb_timer_running(&S, 1), 0);
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 6), 1);   /* falling: start at 6 */
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 10), 1);
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 11), 0);  /* d = 5: off */
  CHECK_EQ(EL(1), 5);
  CHECK_EQ(TC(1), 0);
  CHECK_EQ(tmr(BB_OP_SF, 1, 0, 5, 20), 0);
  CHECK_EQ(EL(1), 5);
  CHECK_EQ(tmr(BB_OP_SF, 1, 1, 5, 21), 1);
  CHECK_EQ(EL(1), 0);
  /* preset 0: off at the falling execution itself */
  CHECK_EQ(tmr(BB_OP_SF, 2, 1, 0, 30), 1);
  CHECK_EQ(tmr(BB_OP_SF, 2, 0, 0, 31), 0);
}

static void test_rt(void) {
  setup();
  CHECK_EQ(tmr(BB_OP_SD, 9, 1, 2, 0), 0);
  CHECK_EQ(tmr(BB_OP_SD, 9, 1, 2, 3), 1);
  /* R T n with RLO = 0 does nothing (but still reports the status) */
  RLO = 0;
  fh_clear_log();
  CHECK_EQ(ex(i_tmr(BB_OP_RT, 9)), BB_CL_TIMER);
  CHECK_EQ(bb_timer_status(&S, 9), 1);
  CHECK_EQ(EL(9), 2);
  CHECK_EQ(S.timer[9].edge, 1);
  CHECK_EQ(FH.nlog, 1);
  CHECK_EQ(FH.log[0].addr, BB_BUS_TC_BIT);
  CHECK_EQ(FH.log[0].data, BB_TC_VALUE | 9u);
  /* with RLO = 1: status 0, elapsed 0, stopped, edge 0 */
  RLO = 1;
  ex(i_tmr(BB_OP_RT, 9));
  CHECK_EQ(bb_timer_status(&S, 9), 0);
  CHECK_EQ(EL(9), 0);
  CHECK_EQ(bb_timer_running(&S, 9), 0);
  CHECK_EQ(S.timer[9].edge, 0);
  CHECK_EQ(TC(9), 0);
  CHECK_EQ(RLO, 1);               /* R T n leaves the RLO */
  /* so the next execution with enable 1 is rising (enable was 1 all along) */
  CHECK_EQ(tmr(BB_OP_SD, 9, 1, 2, 10), 0);
  CHECK_EQ(bb_timer_running(&S, 9), 1);
  CHECK_EQ(tmr(BB_OP_SD, 9, 1, 2, 12), 1);
}

static void test_edge_memory_shared(void) {
  setup();
  /* the edge memory is set to enable after every SD/SS/SP/SF */
  tmr(BB_OP_SD, 10, 1, 5, 0);
  CHECK_EQ(S.timer[10].edge, 1);
  tmr(BB_OP_SP, 10, 0, 5, 1);
  CHECK_EQ(S.timer[10].edge, 0);
  tmr(BB_OP_SS, 10, 1, 5, 2);
  CHECK_EQ(S.timer[10].edge, 1);
  tmr(BB_OP_SF, 10, 0, 5, 3);
  CHECK_EQ(S.timer[10].edge, 0);
  /* one timer, all 64 */
  setup();
  CHECK_EQ(tmr(BB_OP_SD, 63, 1, 0, 0), 1);
  CHECK_EQ(TC(63), 1);
  CHECK_EQ(bb_timer_status(&S, 62), 0);
  CHECK_EQ(bb_timer_status(&S, 64), 0);       /* accessor out of range */
  CHECK_EQ(ex(i_tmr(BB_OP_SD, 64)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(BB_INSTR(BB_OP_SD, BB_AREA_C, 1)), BB_CL_ILLEGAL);  /* wrong area */
  CHECK_EQ(S.flags, BB_FLAG_ILLEGAL);
}

static void test_time_wrap(void) {
  /* TIME_MS wraps after 2^32 ms; d = now - start modulo 2^32 */
  bb_timer t = {0};
  bb_timer_update(&t, BB_OP_SD, 1, 10, 0xFFFFFFFCu);
  CHECK_EQ(t.running, 1);
  bb_timer_update(&t, BB_OP_SD, 1, 10, 5u);   /* d = 9 */
  CHECK_EQ(t.status, 0);
  CHECK_EQ(t.elapsed, 9);
  bb_timer_update(&t, BB_OP_SD, 1, 10, 6u);
  CHECK_EQ(t.status, 1);
  CHECK_EQ(t.elapsed, 10);
  /* a preset near 2^31: elapsed fits int32 */
  bb_timer u = {0};
  bb_timer_update(&u, BB_OP_SD, 1, INT32_MAX, 0);
  bb_timer_update(&u, BB_OP_SD, 1, INT32_MAX, 0xFFFFFFFFu);
  CHECK_EQ(u.status, 1);
  CHECK_EQ(u.elapsed, INT32_MAX);
}

/* --tc-path status: a flagged SD takes its enable from T_ENABLE bit n (the bit side's
 * `= T n`), not from F_B, which it leaves as it was; n >= 32 is in T_ENABLE_HI. */
static void test_from_status(void) {
  setup();
  const uint32_t sd40 = i_tmr(BB_OP_SD, 40) | BB_FROM_STATUS;
  S.accu1 = 5;
  RLO = 0;                                   /* F_B says 0: ignored */
  FH.t_enable = 1ull << 40;                  /* the bit side enabled T 40 */
  fh_set_ms(10);
  ex(sd40);
  CHECK_EQ(bb_timer_running(&S, 40), 1);     /* rising enable: started at 10 */
  CHECK_EQ(RLO, 0);                          /* F_B untouched */
  CHECK_EQ(FH.tc_in_reads, 1u);              /* one bus read */
  S.accu1 = 5;
  RLO = 1;
  fh_set_ms(15);
  ex(sd40);
  CHECK_EQ(S.timer[40].status, 1);           /* 5 ms enabled: done */
  CHECK_EQ(TC(40), 1);
  FH.t_enable = 0;                           /* the bit side dropped it; F_B says 1 */
  S.accu1 = 5;
  fh_set_ms(16);
  ex(sd40);
  CHECK_EQ(S.timer[40].status, 0);
  CHECK_EQ(bb_timer_running(&S, 40), 0);
  CHECK_EQ(RLO, 1);
  /* the flag on a timer in T_ENABLE_LO; another bit set there does not count */
  FH.t_enable = 1ull << 3;
  S.accu1 = 5;
  RLO = 1;
  ex(i_tmr(BB_OP_SD, 2) | BB_FROM_STATUS);
  CHECK_EQ(bb_timer_running(&S, 2), 0);
  /* without the flag, nothing is read: F_B as before */
  const unsigned reads = FH.tc_in_reads;
  ex(i_tmr(BB_OP_SD, 2));
  CHECK_EQ(bb_timer_running(&S, 2), 1);
  CHECK_EQ(FH.tc_in_reads, reads);
}

void suite_timers(void) {
  RUN(test_from_status);
  RUN(test_sd);
  RUN(test_sd_preset_instant);
  RUN(test_sd_preset_zero_and_negative);
  RUN(test_sd_preset_reread);
  RUN(test_ss);
  RUN(test_sp);
  RUN(test_sf);
  RUN(test_rt);
  RUN(test_edge_memory_shared);
  RUN(test_time_wrap);
}
