/* test_serial.c — bb_serial_step(): the dispatch protocol, exact cost, DONE in the
 * last clock, ACCU reset on a new scan (DISPATCH_CTX's FIRST), RLO in and out, and the
 * inputs (time, IW) taken from the port's dispatch snapshot of the instruction's first
 * clock. */
#include "tt.h"

/* Dispatch `instr` at clock `at` (or now, if later) with RLO `rlo` in scan `scan`, a
 * full scan number: the context word is the one rtl/dispatch.v builds, the number's
 * low 16 bits and FIRST for the first dispatch of a scan (this one's scan differs from
 * the last dispatch's). */
static int dispatch(uint32_t instr, int rlo, uint64_t scan, uint64_t at) {
  static uint64_t last_scan = UINT64_MAX;
  FH.dispatch_instr = instr;
  FH.dispatch_ctx = ((uint32_t)(scan & 0xFFFFu) << BB_CTX_SCAN_SHIFT)
                  | (scan != last_scan ? BB_CTX_FIRST : 0u) | (rlo ? BB_CTX_RLO : 0u);
  last_scan = scan;
  FH.dispatch_at = at;
  return bb_serial_step(&S);
}

#define DONE_RLO() ((int)(FH.done_data & 1u))
#define DONE_WE() ((int)((FH.done_data >> 1) & 1u))

static void test_exact_cost(void) {
  setup();
  fh_clear_log();
  CHECK_EQ(dispatch(i_imm(5), 0, 0, 100), 10);
  CHECK_EQ(FH.clock, 110);              /* hal_now() difference = 10 */
  CHECK_EQ(FH.done_count, 1);
  CHECK_EQ(FH.done_clock, 109);         /* DONE in the last clock of the cost */
  CHECK_EQ(FH.nlog, 3);
  CHECK_EQ(FH.log[0].addr, BB_BUS_DISPATCH_INSTR);
  CHECK_EQ(FH.log[0].write, 0);
  CHECK_EQ(FH.log[0].clock, 100);       /* the dispatch clock is the first clock */
  CHECK_EQ(FH.log[1].addr, BB_BUS_DISPATCH_CTX);
  CHECK_EQ(FH.log[1].write, 0);
  CHECK_EQ(FH.log[1].clock, 101);
  CHECK_EQ(FH.log[2].addr, BB_BUS_DONE);
  CHECK_EQ(FH.log[2].write, 1);
  CHECK_EQ(FH.log[2].data, 0);          /* RLO 0, not written */
  CHECK_EQ(FH.log[2].clock, 109);
  CHECK_EQ(FH.spent, 7);                /* 10 - 2 reads - 1 DONE */
  CHECK_EQ(FH.spend_calls, 1);
  CHECK_EQ(S.accu1, 5);
  CHECK_EQ(S.overruns, 0);
  /* back to back: the next dispatch in the clock right after */
  CHECK_EQ(dispatch(i_imm(6), 0, 0, 0), 10);
  CHECK_ACCESS(3, BB_BUS_DISPATCH_INSTR, 110);
  CHECK_EQ(FH.done_clock, 119);
  CHECK_EQ(FH.clock, 120);
  CHECK_EQ(FH.spent, 14);
  CHECK_EQ(S.accu1, 6);
  CHECK_EQ(S.accu2, 5);
  CHECK_EQ(S.overruns, 0);
}

static void test_exact_cost_with_inputs(void) {
  /* the instructions that read a snapshot register: INSTR t0, CTX t0+1, the snapshot
   * t0+2, (TC_BIT t0+3,) DONE t0+9 — still exactly 10 clocks */
  setup();
  FH.iw[2] = 77;
  fh_clear_log();
  CHECK_EQ(dispatch(i_L(BB_AREA_IW, 2), 0, 0, 300), 10);
  CHECK_EQ(FH.nlog, 4);
  CHECK_ACCESS(2, BB_BUS_DISPATCH_IW, 302);
  CHECK_EQ(FH.log[2].data, 77);
  CHECK_ACCESS(3, BB_BUS_DONE, 309);
  CHECK_EQ(FH.spent, 6);                /* 10 - 3 reads - 1 DONE */
  CHECK_EQ(S.accu1, 77);
  fh_clear_log();
  S.accu1 = 5;                          /* preset */
  CHECK_EQ(dispatch(i_tmr(BB_OP_SD, 0), 1, 0, 400), 10);
  CHECK_EQ(FH.nlog, 5);
  CHECK_ACCESS(2, BB_BUS_DISPATCH_MS, 402);
  CHECK_ACCESS(3, BB_BUS_TC_BIT, 403);
  CHECK_ACCESS(4, BB_BUS_DONE, 409);
  CHECK_EQ(FH.spent, 6 + 5);            /* 10 - 3 accesses - 1 DONE */
  CHECK_EQ(S.overruns, 0);
}

static void test_every_class_exact(void) {
  /* every word instruction takes exactly 10 clocks in serial mode (default table) */
  static const uint32_t prog[] = {
    0x80000003u,                                  /* L 3 */
    BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 0),        /* L IW0 */
    BB_INSTR(BB_OP_L_WORD, BB_AREA_QW, 1),        /* L QW1 */
    BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 2),        /* L MW2 */
    BB_INSTR(BB_OP_L_WORD, BB_AREA_T, 3),         /* L T3 */
    BB_INSTR(BB_OP_L_WORD, BB_AREA_C, 4),         /* L C4 */
    BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 5),        /* T MW5 */
    BB_INSTR(BB_OP_T_WORD, BB_AREA_QW, 6),        /* T QW6 */
    0x88000000u, 0x89000000u, 0x8A000000u, 0x8B000000u, 0x8C000000u,
    0x90000000u, 0x95000000u, 0x98000000u, 0xA5000000u,
    BB_INSTR(BB_OP_SD, BB_AREA_T, 1), BB_INSTR(BB_OP_SS, BB_AREA_T, 1),
    BB_INSTR(BB_OP_SP, BB_AREA_T, 1), BB_INSTR(BB_OP_SF, BB_AREA_T, 1),
    BB_INSTR(BB_OP_RT, BB_AREA_T, 1),
    BB_INSTR(BB_OP_CU, BB_AREA_C, 1), BB_INSTR(BB_OP_CD, BB_AREA_C, 1),
    BB_INSTR(BB_OP_SC, BB_AREA_C, 1), BB_INSTR(BB_OP_RC, BB_AREA_C, 1),
  };
  setup();
  for (unsigned i = 0; i < sizeof prog / sizeof prog[0]; i++) {
    uint64_t t0 = FH.clock + 3;
    CHECK_EQ(dispatch(prog[i], 1, 0, t0), 10);
    CHECK_EQ(FH.clock - t0, 10);
    CHECK_EQ(FH.done_clock, t0 + 9);
  }
  CHECK_EQ(S.overruns, 0);
  CHECK_EQ(FH.done_count, sizeof prog / sizeof prog[0]);
  CHECK_EQ(S.flags, BB_FLAG_ARITH);     /* /I and MOD by 0 above, nothing illegal */
}

static void test_fig5_serial(void) {
  /* spec §5: the byte instructions of Fig. 5 serially: L Time, SD Timer, L SP_cur,
   * L SP_nom, A >=I = 5 x 10 clocks; with 9 bit instructions: 59 */
  setup();
  uint64_t t0 = 50;
  FH.dispatch_at = t0;
  int total = 0;
  total += dispatch(BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 1), 1, 0, t0);
  total += dispatch(BB_INSTR(BB_OP_SD, BB_AREA_T, 1), 1, 0, 0);
  total += dispatch(BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 0), 1, 0, 0);
  total += dispatch(BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 0), 1, 0, 0);
  total += dispatch(0x9C000000u, 1, 0, 0);                      /* A >=I */
  CHECK_EQ(total, 50);
  CHECK_EQ(FH.clock - t0, 50);
  CHECK_EQ(DONE_WE(), 1);
  CHECK_EQ(DONE_RLO(), 1);              /* 0 >= 0 */
}

static void test_rlo_protocol(void) {
  setup();
  /* non-compares: DONE bit 1 = 0, bit 0 = the RLO they were given */
  dispatch(i_imm(5), 1, 0, 0);
  CHECK_EQ(DONE_WE(), 0);
  CHECK_EQ(DONE_RLO(), 1);
  dispatch(i_imm(3), 0, 0, 0);
  CHECK_EQ(DONE_WE(), 0);
  CHECK_EQ(DONE_RLO(), 0);
  /* compares write the RLO */
  dispatch(i_cmp(BB_OP_CMP, BB_CMP_GT), 0, 0, 0);    /* 5 > 3 */
  CHECK_EQ(DONE_WE(), 1);
  CHECK_EQ(DONE_RLO(), 1);
  dispatch(i_cmp(BB_OP_A_CMP, BB_CMP_LT), 1, 0, 0);  /* 1 AND 5 < 3 */
  CHECK_EQ(DONE_WE(), 1);
  CHECK_EQ(DONE_RLO(), 0);
  dispatch(i_cmp(BB_OP_O_CMP, BB_CMP_LT), 1, 0, 0);  /* 1 OR 5 < 3 */
  CHECK_EQ(DONE_RLO(), 1);
  dispatch(i_cmp(BB_OP_A_CMP, BB_CMP_GT), 0, 0, 0);  /* 0 AND ... */
  CHECK_EQ(DONE_RLO(), 0);
  CHECK_EQ(DONE_WE(), 1);
  /* the RLO of the context is the timer's enable and the counter's pulse */
  dispatch(i_ctr(BB_OP_CU, 2), 1, 0, 0);
  CHECK_EQ(bb_counter_value(&S, 2), 1);
  CHECK_EQ(DONE_WE(), 0);
  CHECK_EQ(DONE_RLO(), 1);
  /* READ writes the RLO too */
  FH.fby_val[0] = 1;
  dispatch(i_ch(BB_OP_READ, 0), 0, 0, 0);
  CHECK_EQ(DONE_WE(), 1);
  CHECK_EQ(DONE_RLO(), 1);
}

static void test_accu_reset_on_new_scan(void) {
  setup();
  dispatch(i_imm(7), 0, 0, 0);
  dispatch(i_imm(8), 0, 0, 0);
  CHECK_EQ(S.accu1, 8);
  CHECK_EQ(S.accu2, 7);
  dispatch(i_imm(9), 0, 1, 0);          /* scan 1: ACCUs 0 before the L */
  CHECK_EQ(S.accu1, 9);
  CHECK_EQ(S.accu2, 0);
  dispatch(i_imm(10), 0, 1, 0);
  CHECK_EQ(S.accu2, 9);
  /* a compare at the start of a scan sees 0, 0 */
  dispatch(i_cmp(BB_OP_CMP, BB_CMP_EQ), 0, 2, 0);
  CHECK_EQ(DONE_RLO(), 1);
  /* the number field wraps from 0xFFFF to 0: a new scan */
  dispatch(i_imm(1), 0, 0xFFFF, 0);
  dispatch(i_imm(2), 0, 0xFFFF, 0);
  dispatch(i_imm(3), 0, 0x10000, 0);
  CHECK_EQ(S.accu2, 0);
  /* FIRST alone decides, whatever the number: set, a new scan ... */
  setup();
  S.accu1 = 11;
  S.accu2 = 12;
  FH.dispatch_instr = i_op(BB_OP_ADD);
  FH.dispatch_ctx = (5u << BB_CTX_SCAN_SHIFT) | BB_CTX_FIRST;
  FH.dispatch_at = 0;
  bb_serial_step(&S);
  CHECK_EQ(S.accu1, 0);
  /* ... clear, the same scan (even with another number: it is not looked at) */
  S.accu1 = 11;
  S.accu2 = 12;
  FH.dispatch_ctx = 6u << BB_CTX_SCAN_SHIFT;
  bb_serial_step(&S);
  CHECK_EQ(S.accu1, 23);
  /* MW, timers, counters survive a new scan */
  setup();
  dispatch(i_imm(42), 0, 0, 0);
  dispatch(BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 3), 0, 0, 0);
  dispatch(BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 3), 0, 1, 0);
  CHECK_EQ(S.accu1, 42);
}

static void test_accu_reset_after_65536_skipped_scans(void) {
  /* issue 15 defect 4: byte instructions in scan 5, none for 65 536 scans, then one in
   * scan 65 541 -- the number field is 5 again, and the scan is still a new one */
  setup();
  dispatch(i_imm(7), 0, 5, 0);
  dispatch(i_imm(8), 0, 5, 0);
  dispatch(i_imm(9), 0, 5 + 65536, 0);
  CHECK_EQ(S.accu1, 9);
  CHECK_EQ(S.accu2, 0);
  dispatch(i_imm(10), 0, 5 + 65536, 0);
  CHECK_EQ(S.accu2, 9);
  /* a compare first in a scan 2 x 65 536 later sees 0, 0 (not 10 and 9) */
  dispatch(i_cmp(BB_OP_CMP, BB_CMP_EQ), 0, 5 + 3 * 65536, 0);
  CHECK_EQ(DONE_RLO(), 1);
  CHECK_EQ(S.accu1, 0);
}

static void test_timer_now_first_clock(void) {
  /* now = TIME_MS in the instruction's first clock (the dispatch clock), not later:
   * 100 clocks per ms; SD dispatched at clock 398 sees now = 3, at 400 now = 4 */
  setup();
  FH.tick_div = 100;
  dispatch(i_imm(4), 1, 0, 0);                            /* preset 4 ms, clocks 0..9 */
  dispatch(i_tmr(BB_OP_SD, 1), 1, 0, 0);                  /* at clock 10: now 0 */
  CHECK_EQ(S.timer[1].start, 0);
  fh_clear_log();
  dispatch(i_tmr(BB_OP_SD, 1), 1, 0, 398);
  /* INSTR at 398, CTX at 399, DISPATCH_MS at 400: TIME_MS is 4 by then, but the
   * snapshot is the dispatch clock's 398 / 100 = 3 */
  CHECK_EQ(FH.disp_clock, 398);
  CHECK_ACCESS(0, BB_BUS_DISPATCH_INSTR, 398);
  CHECK_ACCESS(1, BB_BUS_DISPATCH_CTX, 399);
  CHECK_ACCESS(2, BB_BUS_DISPATCH_MS, 400);
  CHECK_EQ(FH.log[2].data, 3);
  CHECK_EQ(bb_timer_status(&S, 1), 0);                    /* d = 3 - 0 = 3 < 4 */
  CHECK_EQ(bb_timer_elapsed(&S, 1), 3);
  CHECK_EQ(FH.t_status & 2u, 0);
  /* TC_BIT comes before DONE, inside the cost */
  CHECK_ACCESS(3, BB_BUS_TC_BIT, 401);
  CHECK_EQ(FH.log[3].data, 1);                            /* status 0, T1 */
  CHECK_ACCESS(4, BB_BUS_DONE, 407);
  CHECK_EQ(FH.nlog, 5);
  /* (the live TIME_MS in clock 400 would have given 4, d = 4 and status 1) */
  /* the next dispatch takes a new snapshot: at 500 now = 5, d = 5 >= 4 */
  dispatch(i_tmr(BB_OP_SD, 1), 1, 0, 500);
  CHECK_ACCESS(7, BB_BUS_DISPATCH_MS, 502);
  CHECK_EQ(FH.log[7].data, 5);
  CHECK_EQ(bb_timer_status(&S, 1), 1);
  CHECK_EQ(bb_timer_elapsed(&S, 1), 4);                   /* min(d, preset) */
  CHECK_EQ(FH.t_status & 2u, 2u);
  /* a dispatch in the last clock of a ms and one in the first clock of the next:
   * T2 started at 699 (now 6) and run at 799 (now 7, read at 801): d = 1 */
  S.accu1 = 2;
  dispatch(i_tmr(BB_OP_SD, 2), 1, 0, 699);
  CHECK_EQ(S.timer[2].start, 6);
  dispatch(i_tmr(BB_OP_SD, 2), 1, 0, 799);
  CHECK_EQ(bb_timer_elapsed(&S, 2), 1);
  CHECK_EQ(bb_timer_status(&S, 2), 0);                    /* 1 < 2 */
  dispatch(i_tmr(BB_OP_SD, 2), 1, 0, 810);                /* now 8: d = 2 >= 2 */
  CHECK_EQ(bb_timer_elapsed(&S, 2), 2);
  CHECK_EQ(bb_timer_status(&S, 2), 1);
  /* serial mode never reads the live TIME_MS */
  for (unsigned k = 0; k < FH.nlog; k++) CHECK(FH.log[k].addr != BB_BUS_TIME_MS);
}

static void test_timer_at_latch(void) {
  /* the at-latch bit (S7's timers): now = LATCH_MS, the scan's latch time, in place of
   * DISPATCH_MS, in the same clock, so the cost is unchanged */
  setup();
  FH.tick_div = 100;
  FH.latch_ms = 2;                                        /* the scan latched at 2 ms */
  dispatch(i_imm(3), 1, 0, 0);                            /* preset 3 ms */
  fh_clear_log();
  CHECK_EQ(dispatch(i_tmr(BB_OP_SD, 1) | BB_AT_LATCH, 1, 0, 498), 10);
  CHECK_ACCESS(2, BB_BUS_LATCH_MS, 500);                  /* where DISPATCH_MS would be */
  CHECK_EQ(FH.log[2].data, 2);
  CHECK_EQ(S.timer[1].start, 2);                          /* not 4, the dispatch's ms */
  CHECK_ACCESS(3, BB_BUS_TC_BIT, 501);
  CHECK_ACCESS(4, BB_BUS_DONE, 507);
  CHECK_EQ(FH.nlog, 5);
  CHECK_EQ(S.overruns, 0);
  /* the next scan latched at 5 ms: d = 5 - 2 = 3 >= 3, whatever the dispatch's ms */
  FH.latch_ms = 5;
  dispatch(i_tmr(BB_OP_SD, 1) | BB_AT_LATCH, 1, 0, 590);
  CHECK_EQ(bb_timer_status(&S, 1), 1);
  CHECK_EQ(bb_timer_elapsed(&S, 1), 3);
  /* without the bit the same timer takes the dispatch's time */
  S.accu1 = 3;
  dispatch(i_tmr(BB_OP_SD, 2), 1, 0, 698);
  CHECK_EQ(S.timer[2].start, 6);
}

static void test_iw_first_clock(void) {
  /* L IW n in serial mode loads the input word of the instruction's first clock, from
   * DISPATCH_IW, even if the input changes 2 clocks later, i.e. in the very clock the
   * firmware reads it */
  setup();
  FH.iw[3] = 100;
  fh_iw_at(3, 200, 202);
  fh_clear_log();
  CHECK_EQ(dispatch(i_L(BB_AREA_IW, 3), 0, 0, 200), 10);
  CHECK_ACCESS(2, BB_BUS_DISPATCH_IW, 202);
  CHECK_EQ(FH.log[2].data, 100);
  CHECK_EQ(FH.iw[3], 200);                                /* the input did change */
  CHECK_EQ(S.accu1, 100);
  /* the next dispatch samples the new value */
  CHECK_EQ(dispatch(i_L(BB_AREA_IW, 3), 0, 0, 0), 10);
  CHECK_EQ(S.accu1, 200);
  CHECK_EQ(S.accu2, 100);
  /* parallel mode (bb_exec) reads 0x40+n live */
  fh_iw_at(3, 300, FH.clock + 1);
  fh_clear_log();
  ex(i_L(BB_AREA_IW, 3));                                 /* clock 210: still 200 */
  ex(i_L(BB_AREA_IW, 3));                                 /* clock 211: 300 */
  CHECK_EQ(FH.log[0].addr, BB_BUS_IW(3));
  CHECK_EQ(S.accu2, 200);
  CHECK_EQ(S.accu1, 300);
  /* the word is the one bits 3..0 name; the port sign-extends (a raw 0xFFFB is -5) */
  FH.iw[15] = 0xFFFBu;
  FH.iw[0] = 0x7FFFu;
  fh_clear_log();
  dispatch(i_L(BB_AREA_IW, 15), 0, 0, 0);
  CHECK_EQ(FH.log[2].addr, BB_BUS_DISPATCH_IW);
  CHECK_EQ(FH.log[2].data, 0xFFFFFFFBu);
  CHECK_EQ(S.accu1, -5);
  dispatch(i_L(BB_AREA_IW, 0), 0, 0, 0);
  CHECK_EQ(S.accu1, 32767);
  CHECK_EQ(S.accu2, -5);
  /* the change of IW15 in the first clock itself is seen (sampled in that clock) */
  fh_iw_at(15, 9, FH.clock + 4);
  dispatch(i_L(BB_AREA_IW, 15), 0, 0, FH.clock + 4);
  CHECK_EQ(S.accu1, 9);
  for (unsigned k = 0; k < FH.nlog; k++)
    CHECK(FH.log[k].addr < BB_BUS_IW(0) || FH.log[k].addr > BB_BUS_IW(15));
}

static void test_fake_snapshot(void) {
  /* the fake HAL's snapshot behaves as rtl/byte_port.v (tb/test_byte_port.py
   * dispatch_snapshot): 0 after reset, taken when a dispatch begins, held until DONE
   * and the next dispatch, not retaken while the dispatch is pending */
  setup();
  FH.tick_div = 2;
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_MS), 0);
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_IW), 0);
  FH.iw[3] = 0x1111;
  FH.dispatch_instr = 0x8200A003u;                      /* L IW3 */
  FH.dispatch_at = 7;                                   /* ms 3 */
  hal_wait_dispatch(&FH);
  CHECK_EQ(FH.clock, 7);
  FH.iw[3] = 0x2222;
  hal_spend(&FH, 3);                                    /* clock 10: ms 5 */
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_TIME_MS), 5);
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_MS), 3);
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_IW), 0x1111);
  hal_wait_dispatch(&FH);                               /* still pending: no snapshot */
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_MS), 3);
  CHECK_EQ(FH.snapshots, 1);
  hal_bus_write(&FH, BB_BUS_DONE, 0);                   /* clock 14 */
  FH.iw[3] = 0xF000;
  FH.dispatch_at = 0;
  hal_wait_dispatch(&FH);                               /* clock 15: ms 7 */
  CHECK_EQ(FH.snapshots, 2);
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_MS), 7);
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_IW), 0xFFFFF000u);
  /* whatever the instruction: bits 3..0 name the word */
  hal_bus_write(&FH, BB_BUS_DONE, 0);
  FH.iw[5] = 0x0042;
  FH.dispatch_instr = 0x88000005u;                      /* +I, index bits 5 */
  hal_wait_dispatch(&FH);
  CHECK_EQ(hal_bus_read(&FH, BB_BUS_DISPATCH_IW), 0x42);
}

static void test_illegal(void) {
  setup();
  /* unknown opcode: no crash, sticky flag on the bus, cost 1 -> an overrun */
  int taken = dispatch(0xFF123456u, 1, 0, 20);
  CHECK_EQ(S.flags, BB_FLAG_ILLEGAL);
  CHECK_EQ(FH.byte_flags, BB_FLAG_ILLEGAL);
  CHECK_EQ(FH.done_count, 1);
  CHECK_EQ(DONE_WE(), 0);
  CHECK_EQ(DONE_RLO(), 1);
  CHECK_EQ(taken, 4);                   /* INSTR, CTX, BYTE_FLAGS, DONE */
  CHECK_EQ(S.overruns, 1);
  CHECK_EQ(S.last_class, BB_CL_ILLEGAL);
  CHECK_EQ(FH.spent, 0);
  /* a bit instruction dispatched by mistake, an empty word */
  dispatch(0x0A00000Bu, 0, 0, 0);
  dispatch(0x00000000u, 0, 0, 0);
  CHECK_EQ(S.overruns, 3);
  CHECK_EQ(FH.done_count, 3);
  /* both flags are sticky and written as one word */
  L(1);
  L(0);
  ex(i_op(BB_OP_DIV));
  CHECK_EQ(FH.byte_flags, BB_FLAG_ILLEGAL | BB_FLAG_ARITH);
  /* the firmware carries on */
  CHECK_EQ(dispatch(i_imm(5), 0, 0, 0), 10);
  CHECK_EQ(S.accu1, 5);
}

static void test_c320_serial(void) {
  setup();
  CHECK_EQ(bb_set_costs(&S, "c320"), 0);
  uint64_t t0 = 7;
  CHECK_EQ(dispatch(i_imm(5), 0, 0, t0), 57);
  CHECK_EQ(FH.done_clock, t0 + 56);
  CHECK_EQ(FH.spent, 57 - 3);                            /* 2 reads, DONE */
  /* READ in serial: 2 protocol reads + the channel + DONE = 4 of 6, 2 spent */
  FH.fby_val[3] = 1;
  t0 = FH.clock;
  uint64_t spent = FH.spent;
  CHECK_EQ(dispatch(i_ch(BB_OP_READ, 3), 0, 0, t0), 6);
  CHECK_EQ(FH.done_clock, t0 + 5);
  CHECK_EQ(FH.spent, spent + 2);
  CHECK_EQ(S.overruns, 0);
  /* a 2-clock channel stall eats the spare clock: still exactly 6, nothing spent */
  FH.fby_stall[3] = 2;
  spent = FH.spent;
  CHECK_EQ(dispatch(i_ch(BB_OP_READ, 3), 0, 0, 0), 6);
  CHECK_EQ(FH.spent, spent);
  CHECK_EQ(S.overruns, 0);
  /* a 3-clock stall goes past the cost: no negative spend, one overrun */
  FH.fby_stall[3] = 3;
  CHECK_EQ(dispatch(i_ch(BB_OP_READ, 3), 0, 0, 0), 7);
  CHECK_EQ(FH.spent, spent);
  CHECK_EQ(S.overruns, 1);
  /* the default table's READ (cost 1) cannot fit the serial protocol */
  CHECK_EQ(bb_set_costs(&S, "paper"), 0);
  CHECK_EQ(dispatch(i_ch(BB_OP_READ, 3), 0, 0, 0), 4);    /* INSTR, CTX, FBY, DONE */
  CHECK_EQ(S.overruns, 2);
}

void suite_serial(void) {
  RUN(test_exact_cost);
  RUN(test_exact_cost_with_inputs);
  RUN(test_every_class_exact);
  RUN(test_fig5_serial);
  RUN(test_rlo_protocol);
  RUN(test_accu_reset_on_new_scan);
  RUN(test_accu_reset_after_65536_skipped_scans);
  RUN(test_timer_now_first_clock);
  RUN(test_timer_at_latch);
  RUN(test_iw_first_clock);
  RUN(test_fake_snapshot);
  RUN(test_illegal);
  RUN(test_c320_serial);
}
