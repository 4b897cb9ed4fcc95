/* test_exchange.c — READ FBY k, WRITE FBI k, stalls and bb_step()'s accounting. */
#include "tt.h"

static void test_read(void) {
  setup();
  FH.fby_val[1] = 1;
  RLO = 0;
  CHECK_EQ(ex(i_ch(BB_OP_READ, 1)), BB_CL_BINARY);
  CHECK_EQ(RLO, 1);
  CHECK_EQ(S.rlo_written, 1);
  CHECK_EQ(FH.fby_reads[1], 1);
  FH.fby_val[1] = 0xFFFFFFFEu;        /* only bit 0 is the condition */
  CHECK_EQ(ex(i_ch(BB_OP_READ, 1)), BB_CL_BINARY);
  CHECK_EQ(RLO, 0);
  FH.fby_val[7] = 3;
  ex(i_ch(BB_OP_READ, 7));
  CHECK_EQ(RLO, 1);
  CHECK_EQ(FH.log[FH.nlog - 1].addr, 0x27);
  /* READ leaves the accumulators */
  CHECK_EQ(S.accu1, 0);
}

static void test_write(void) {
  setup();
  RLO = 1;
  CHECK_EQ(ex(i_ch(BB_OP_WRITE, 2)), BB_CL_BINARY);
  CHECK_EQ(FH.fbi_val[2], 1);
  CHECK_EQ(FH.fbi_writes[2], 1);
  CHECK_EQ(RLO, 1);                   /* WRITE leaves F_B */
  CHECK_EQ(S.rlo_written, 0);
  CHECK_EQ(FH.log[0].addr, 0x2A);
  CHECK_EQ(FH.log[0].data, 1);
  RLO = 0;
  ex(i_ch(BB_OP_WRITE, 2));
  CHECK_EQ(FH.fbi_val[2], 0);
  CHECK_EQ(FH.log[1].data, 0);
}

static void test_cells_past_the_channels(void) {
  /* the marker exchange's cells 8..127 are in the MCELL window (0x80 + k); cells 0..7
   * stay at the channel registers (the hardware serves both there) */
  setup();
  RLO = 1;
  CHECK_EQ(ex(i_ch(BB_OP_READ, 8)), BB_CL_BINARY);
  CHECK_EQ(FH.log[FH.nlog - 1].addr, 0x88);
  CHECK_EQ(FH.log[FH.nlog - 1].write, 0);
  CHECK_EQ(RLO, 0);                   /* the fake HAL's window reads 0 */
  RLO = 1;
  CHECK_EQ(ex(i_ch(BB_OP_WRITE, 127)), BB_CL_BINARY);
  CHECK_EQ(FH.log[FH.nlog - 1].addr, 0xFF);
  CHECK_EQ(FH.log[FH.nlog - 1].write, 1);
  CHECK_EQ(FH.log[FH.nlog - 1].data, 1);
  CHECK_EQ(S.flags, 0);
}

static void test_bad_channel(void) {
  setup();
  RLO = 1;
  CHECK_EQ(ex(i_ch(BB_OP_READ, BB_NUM_CELLS)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(BB_INSTR(BB_OP_WRITE, BB_AREA_MW, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(RLO, 1);
  CHECK_EQ(S.flags, BB_FLAG_ILLEGAL);
  for (unsigned k = 0; k < 8; k++) {
    CHECK_EQ(FH.fby_reads[k], 0);
    CHECK_EQ(FH.fbi_writes[k], 0);
  }
}

static void test_step_exact_cost(void) {
  /* bb_step (parallel mode): bus accesses + hal_spend = the table cost */
  setup();
  FH.clock = 1000;
  int rlo = 0;
  CHECK_EQ(bb_step(&S, i_imm(5), &rlo), 10);     /* no access, spend 10 */
  CHECK_EQ(FH.clock, 1010);
  CHECK_EQ(FH.spent, 10);
  S.accu1 = 3;
  rlo = 1;
  CHECK_EQ(bb_step(&S, i_tmr(BB_OP_SD, 0), &rlo), 10);  /* TIME_MS, TC_BIT, spend 8 */
  CHECK_EQ(FH.clock, 1020);
  CHECK_EQ(FH.spent, 18);
  FH.fby_val[0] = 1;
  rlo = 0;
  CHECK_EQ(bb_step(&S, i_ch(BB_OP_READ, 0), &rlo), 1);  /* the one access is the cost */
  CHECK_EQ(rlo, 1);
  CHECK_EQ(FH.spent, 18);
  CHECK_EQ(bb_step(&S, i_ch(BB_OP_WRITE, 3), &rlo), 1);
  CHECK_EQ(FH.clock, 1022);
  CHECK_EQ(S.overruns, 0);
  /* the paper's parallel byte part (Fig. 13): 10+1+10+10+10+10+1 = 52 clocks */
  setup();
  rlo = 0;
  FH.fby_val[0] = 1;
  uint64_t t0 = FH.clock;
  bb_step(&S, i_L(BB_AREA_MW, 1), &rlo);
  bb_step(&S, i_ch(BB_OP_READ, 0), &rlo);
  bb_step(&S, i_tmr(BB_OP_SD, 1), &rlo);
  bb_step(&S, i_L(BB_AREA_IW, 0), &rlo);
  bb_step(&S, i_L(BB_AREA_MW, 0), &rlo);
  bb_step(&S, i_cmp(BB_OP_CMP, BB_CMP_GE), &rlo);
  bb_step(&S, i_ch(BB_OP_WRITE, 0), &rlo);
  CHECK_EQ(FH.clock - t0, 52);
  CHECK_EQ(S.overruns, 0);
}

static void test_step_stall(void) {
  /* a stalled channel makes the instruction longer: nothing negative is spent */
  setup();
  FH.fby_stall[0] = 3;
  FH.fby_val[0] = 1;
  int rlo = 0;
  CHECK_EQ(bb_step(&S, i_ch(BB_OP_READ, 0), &rlo), 4);  /* 3 not-ready + 1 */
  CHECK_EQ(rlo, 1);
  CHECK_EQ(FH.spent, 0);
  CHECK_EQ(FH.spend_calls, 0);
  CHECK_EQ(S.overruns, 1);
  CHECK_EQ(FH.stalls_byte, 3);
  FH.fbi_stall[1] = 2;
  CHECK_EQ(bb_step(&S, i_ch(BB_OP_WRITE, 1), &rlo), 3);
  CHECK_EQ(S.overruns, 2);
  /* a stall inside a word instruction's budget costs nothing extra */
  bb_set_costs(&S, "c320");
  FH.fby_stall[2] = 4;
  CHECK_EQ(bb_step(&S, i_ch(BB_OP_READ, 2), &rlo), 6);  /* 5 of 6, spend 1 */
  CHECK_EQ(S.overruns, 2);
  CHECK_EQ(FH.spent, 1);
}

void suite_exchange(void) {
  RUN(test_read);
  RUN(test_write);
  RUN(test_cells_past_the_channels);
  RUN(test_bad_channel);
  RUN(test_step_exact_cost);
  RUN(test_step_stall);
}
