/* test_contexts.c — several byte processors in one process (the cores of a plant): each
 * state's HAL calls carry its own context (bb_set_hal_ctx), here a fake_hal of its own,
 * so the processors share nothing, however their calls interleave — one step each in
 * turn, or one processor's steps run from inside the other's HAL calls (as a host's
 * coroutines may). Every run must give each processor exactly the bus traffic, clock
 * and state it has when it runs alone. */
#include <string.h>

#include "tt.h"

static fake_hal HA, HB;      /* the two contexts */
static fake_hal RA, RB;      /* the same processors run alone: the references */
static bb_state A, B;

/* Two byte programs that reach the bus in every way: IW / QW, a timer (TIME_MS,
 * TC_BIT), a counter (TC_BIT), the channels (FBY / FBI), arithmetic, END_B. */
static const uint32_t PROG_A[] = {
  BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 0), BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 1),
  (uint32_t)BB_OP_ADD << 24, BB_INSTR(BB_OP_T_WORD, BB_AREA_QW, 0),
  BB_INSTR_IMM(BB_OP_L_IMM, 5), BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 3),
  BB_INSTR(BB_OP_SD, BB_AREA_T, 1), BB_INSTR(BB_OP_CU, BB_AREA_C, 2),
  BB_INSTR(BB_OP_READ, BB_AREA_FB, 0), BB_INSTR(BB_OP_WRITE, BB_AREA_FB, 1),
  (uint32_t)BB_OP_END_B << 24,
};
static const uint32_t PROG_B[] = {
  BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 2), BB_INSTR_IMM(BB_OP_L_IMM, 10),
  (uint32_t)BB_OP_MUL << 24, BB_INSTR(BB_OP_T_WORD, BB_AREA_QW, 1),
  BB_INSTR(BB_OP_L_WORD, BB_AREA_QW, 1), BB_INSTR(BB_OP_T_WORD, BB_AREA_QW, 2),
  BB_INSTR(BB_OP_CD, BB_AREA_C, 3), BB_INSTR(BB_OP_SS, BB_AREA_T, 4),
  BB_INSTR(BB_OP_READ, BB_AREA_FB, 2), BB_INSTR(BB_OP_WRITE, BB_AREA_FB, 0),
  (uint32_t)BB_OP_END_B << 24,
};
#define N_A (sizeof PROG_A / sizeof PROG_A[0])
#define N_B (sizeof PROG_B / sizeof PROG_B[0])

/* Different inputs for the two, so that a call reaching the wrong context shows. */
static void fresh(fake_hal *h, int which) {
  fh_init(h);
  for (unsigned n = 0; n < 16; n++) h->iw[n] = which ? 1000u + 7u * n : 11u * n + 3u;
  h->fby_val[0] = 1;
  h->fby_val[2] = (uint32_t)which;
  h->fby_stall[0] = which ? 0u : 2u;       /* A's channel 0 is not ready for 2 clocks */
  h->tick_div = which ? 10u : 1000u;
}

static void fresh_state(bb_state *s, fake_hal *h, const uint32_t *prog, unsigned n) {
  bb_init(s, NULL);
  bb_set_hal_ctx(s, h);
  CHECK_EQ(bb_load_program(s, prog, n), 0);
}

/* What the processor did on its bus: every access (address, direction, data, clock),
 * the clock, the outputs and the status it left. */
static void same_bus(const fake_hal *got, const fake_hal *want) {
  CHECK_EQ(got->nlog, want->nlog);
  for (unsigned i = 0; i < got->nlog && i < want->nlog; i++) {
    CHECK_EQ(got->log[i].addr, want->log[i].addr);
    CHECK_EQ(got->log[i].write, want->log[i].write);
    CHECK_EQ(got->log[i].data, want->log[i].data);
    CHECK_EQ(got->log[i].clock, want->log[i].clock);
  }
  CHECK_EQ(got->clock, want->clock);
  CHECK_EQ(got->spent, want->spent);
  CHECK_EQ(got->done_count, want->done_count);
  CHECK_EQ(got->t_status, want->t_status);
  CHECK_EQ(got->c_status, want->c_status);
  CHECK(memcmp(got->qw, want->qw, sizeof got->qw) == 0);
  CHECK(memcmp(got->fbi_val, want->fbi_val, sizeof got->fbi_val) == 0);
}

static void same_state(const bb_state *got, const bb_state *want) {
  CHECK_EQ(bb_accu1(got), bb_accu1(want));
  CHECK_EQ(bb_accu2(got), bb_accu2(want));
  CHECK_EQ(bb_fb(got), bb_fb(want));
  CHECK_EQ(bb_executed(got), bb_executed(want));
  CHECK_EQ(bb_byte_scans(got), bb_byte_scans(want));
  CHECK_EQ(bb_mw(got, 3), bb_mw(want, 3));
  CHECK_EQ(bb_counter_value(got, 2), bb_counter_value(want, 2));
  CHECK_EQ(bb_timer_running(got, 1), bb_timer_running(want, 1));
  CHECK_EQ(bb_timer_running(got, 4), bb_timer_running(want, 4));
}

/* Parallel mode, three scans each: alone, then taking turns scan by scan. */
static void test_two_states_take_turns(void) {
  static bb_state refA, refB;
  fresh(&RA, 0);
  fresh(&RB, 1);
  fresh_state(&refA, &RA, PROG_A, N_A);
  fresh_state(&refB, &RB, PROG_B, N_B);
  for (int i = 0; i < 3; i++) bb_run_step(&refA, BB_MODE_PARALLEL);
  for (int i = 0; i < 3; i++) bb_run_step(&refB, BB_MODE_PARALLEL);
  CHECK_EQ(bb_byte_scans(&refA), 3);
  CHECK(RA.nlog > 20 && RB.nlog > 20);
  CHECK_EQ(RA.qw[0], 3 + 14);              /* IW0 + IW1 of A's inputs */
  CHECK_EQ(RB.qw[2], 1014 * 10);           /* IW2 * 10 of B's, through QW1 */

  fresh(&HA, 0);
  fresh(&HB, 1);
  fresh_state(&A, &HA, PROG_A, N_A);
  fresh_state(&B, &HB, PROG_B, N_B);
  for (int i = 0; i < 3; i++) {
    bb_run_step(&B, BB_MODE_PARALLEL);
    bb_run_step(&A, BB_MODE_PARALLEL);
  }
  same_bus(&HA, &RA);
  same_bus(&HB, &RB);
  same_state(&A, &refA);
  same_state(&B, &refB);
}

/* Serial mode: dispatched instructions, alternating between the two. */
static void test_two_states_serial(void) {
  static bb_state refA, refB;
  fresh(&RA, 0);
  fresh(&RB, 1);
  fresh_state(&refA, &RA, NULL, 0);
  fresh_state(&refB, &RB, NULL, 0);
  for (unsigned i = 0; i + 1 < N_A; i++) {
    RA.dispatch_instr = PROG_A[i];
    bb_serial_step(&refA);
  }
  for (unsigned i = 0; i + 1 < N_B; i++) {
    RB.dispatch_instr = PROG_B[i];
    bb_serial_step(&refB);
  }
  CHECK_EQ(RA.done_count, N_A - 1);

  fresh(&HA, 0);
  fresh(&HB, 1);
  fresh_state(&A, &HA, NULL, 0);
  fresh_state(&B, &HB, NULL, 0);
  for (unsigned i = 0; i + 1 < N_A || i + 1 < N_B; i++) {
    if (i + 1 < N_A) {
      HA.dispatch_instr = PROG_A[i];
      bb_serial_step(&A);
    }
    if (i + 1 < N_B) {
      HB.dispatch_instr = PROG_B[i];
      bb_serial_step(&B);
    }
  }
  same_bus(&HA, &RA);
  same_bus(&HB, &RB);
  same_state(&A, &refA);
  same_state(&B, &refB);
}

/* B's instructions run from inside A's bus accesses, two after each: the firmware is
 * re-entered for another state in the middle of a step, and neither notices. */
static unsigned b_next;
static void step_b(void *arg) {
  (void)arg;
  for (int i = 0; i < 2 && b_next < N_B; i++) bb_step(&B, PROG_B[b_next++], NULL);
}

static void test_one_state_inside_the_others_hal(void) {
  static bb_state refA, refB;
  fresh(&RA, 0);
  fresh(&RB, 1);
  fresh_state(&refA, &RA, PROG_A, N_A);
  fresh_state(&refB, &RB, NULL, 0);
  bb_run_step(&refA, BB_MODE_PARALLEL);
  for (unsigned i = 0; i < N_B; i++) bb_step(&refB, PROG_B[i], NULL);

  fresh(&HA, 0);
  fresh(&HB, 1);
  fresh_state(&A, &HA, PROG_A, N_A);
  fresh_state(&B, &HB, NULL, 0);
  b_next = 0;
  HA.after_access = step_b;
  bb_run_step(&A, BB_MODE_PARALLEL);
  HA.after_access = NULL;
  CHECK_EQ(b_next, N_B);                   /* A made enough accesses for all of B */
  same_bus(&HA, &RA);
  same_bus(&HB, &RB);
  same_state(&A, &refA);
  same_state(&B, &refB);
}

void suite_contexts(void) {
  RUN(test_two_states_take_turns);
  RUN(test_two_states_serial);
  RUN(test_one_state_inside_the_others_hal);
}
