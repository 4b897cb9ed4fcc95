/* test_program.c — parallel mode's byte program: bb_load_program(), bb_run_scan(),
 * the jumps JU_B / JC_B / JCN_B on F_B, END_B, the exact clocks of a scan, the
 * ACCU / F_B reset at scan start, running off the end and the runaway guard.
 * Every expected clock count is worked out by hand in the comment next to it
 * ("paper": 10 per word instruction, 1 per READ / WRITE / jump, END_B 0). */
#include <setjmp.h>
#include <string.h>

#include "tt.h"

static uint32_t i_j(unsigned op, unsigned target) { return BB_INSTR_JUMP(op, target); }
#define END_B (i_j(BB_OP_END_B, 0))
#define NWORDS(a) ((unsigned)(sizeof(a) / sizeof((a)[0])))

/* Load a program into S; check it was accepted. */
static void load(const uint32_t *words, unsigned n) {
  CHECK_EQ(bb_load_program(&S, words, n), 0);
  CHECK_EQ(S.prog_len, n);
}

/* A fresh state with the array p loaded (load()), one scan: its cost, the steps it
 * counts and the pc it ends on. */
#define CHECK_SCAN(p, cost, steps, end_pc) do { \
    setup(); \
    load(p, NWORDS(p)); \
    CHECK_EQ(bb_run_scan(&S), cost); \
    CHECK_EQ(S.scan_steps, steps); \
    CHECK_EQ(S.pc, end_pc); \
  } while (0)

/* The byte part of the paper's Fig. 13: L Time; READ FBY 0; SD T1; L SP_cur;
 * L SP_nom; >=I; WRITE FBI 0; END_B — with Time = MW1, SP_cur = IW0, SP_nom = MW0. */
static const uint32_t fig13[] = {
  BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 1),    /* L Time          10 */
  BB_INSTR(BB_OP_READ, BB_AREA_FB, 0),      /* READ FBY 0       1 */
  BB_INSTR(BB_OP_SD, BB_AREA_T, 1),         /* SD T1           10 */
  BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 0),    /* L SP_cur        10 */
  BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 0),    /* L SP_nom        10 */
  (uint32_t)(BB_OP_CMP + BB_CMP_GE) << 24,  /* >=I             10 */
  BB_INSTR(BB_OP_WRITE, BB_AREA_FB, 0),     /* WRITE FBI 0      1 */
  (uint32_t)BB_OP_END_B << 24,              /* END_B            0 */
};

static void test_timer_at_latch_parallel(void) {
  /* the same byte part with SD T1's at-latch bit (S7's timers): LATCH_MS read in
   * TIME_MS's place, in the same clock; the scan's 52 clocks unchanged */
  uint32_t part[NWORDS(fig13)];
  memcpy(part, fig13, sizeof part);
  part[2] |= BB_AT_LATCH;
  setup();
  load(part, NWORDS(part));
  S.mw[1] = 5;
  FH.fby_val[0] = 1;
  FH.clock = 2000;         /* ms 2 */
  FH.latch_ms = 1;         /* the scan latched in ms 1 */
  fh_clear_log();
  CHECK_EQ(bb_run_scan(&S), 52);
  CHECK_ACCESS(1, BB_BUS_LATCH_MS, 2011);
  CHECK_EQ(FH.log[1].data, 1);
  CHECK_EQ(S.timer[1].start, 1);
  CHECK_EQ(S.overruns, 0);
}

static void test_fig13_straight(void) {
  setup();
  load(fig13, NWORDS(fig13));
  S.mw[1] = 5;             /* Time: 5 ms */
  S.mw[0] = 50;            /* SP_nom */
  FH.iw[0] = 100;          /* SP_cur */
  FH.fby_val[0] = 1;       /* channel full: READ does not stall; FBI 0 ready */
  FH.clock = 2000;         /* ms 2 */
  fh_clear_log();
  /* 5 word instructions x 10 + READ 1 + WRITE 1 + END_B 0 = 52 */
  CHECK_EQ(bb_run_scan(&S), 52);
  CHECK_EQ(FH.clock, 2052);
  CHECK_EQ(S.overruns, 0);
  CHECK_EQ(S.scan_steps, 8);
  CHECK_EQ(S.pc, 8);
  CHECK_EQ(bb_executed(&S), 8);
  CHECK_EQ(S.last_class, BB_CL_END);
  /* bus: READ FBY0 @10, TIME_MS @11, TC_BIT @12, IW0 @21, FBI0 @51 (5 accesses) */
  CHECK_EQ(FH.nlog, 5);
  CHECK_ACCESS(0, BB_BUS_FBY(0), 2010);
  CHECK_ACCESS(1, BB_BUS_TIME_MS, 2011);
  CHECK_EQ(FH.log[1].data, 2);
  CHECK_ACCESS(2, BB_BUS_TC_BIT, 2012);
  CHECK_ACCESS(3, BB_BUS_IW(0), 2021);
  CHECK_ACCESS(4, BB_BUS_FBI(0), 2051);
  CHECK_EQ(FH.log[4].data, 1);
  CHECK_EQ(FH.spent, 52 - 5);
  /* semantics: T1 started with preset 5, not expired; 100 >= 50 -> F_B = 1 */
  CHECK_EQ(bb_timer_running(&S, 1), 1);
  CHECK_EQ(bb_timer_status(&S, 1), 0);
  CHECK_EQ(bb_fb(&S), 1);
  CHECK_EQ(bb_rlo(&S), 1);
  CHECK_EQ(FH.fbi_val[0], 1);
  CHECK_EQ(FH.fbi_writes[0], 1);
  CHECK_EQ(FH.fby_reads[0], 1);
  CHECK_EQ(bb_accu1(&S), 50);
  CHECK_EQ(bb_accu2(&S), 100);
  CHECK_EQ(bb_flags(&S), 0);
  /* the next scan takes the same 52 clocks */
  CHECK_EQ(bb_run_scan(&S), 52);
  CHECK_EQ(FH.clock, 2104);
  CHECK_EQ(S.overruns, 0);
  /* c320: 5 x 57 + 2 x 6 = 297 */
  setup();
  CHECK_EQ(bb_set_costs(&S, "c320"), 0);
  load(fig13, NWORDS(fig13));
  FH.fby_val[0] = 1;
  CHECK_EQ(bb_run_scan(&S), 297);
  CHECK_EQ(S.overruns, 0);
}

/* ACCU2 := 3; ACCU1 := 5; F_B := 3 cmp 5; then jump to 6 (skipping MW0 := 111). */
static int run_cmp_jump(unsigned cmp, unsigned jop) {
  const uint32_t p[] = {
    i_imm(3),                       /* 0  L 3        10 */
    i_imm(5),                       /* 1  L 5        10 */
    i_cmp(BB_OP_CMP, cmp),          /* 2  cmp        10 */
    i_j(jop, 6),                    /* 3  J*_B 6      1 */
    i_imm(111),                     /* 4  L 111      10 */
    i_T(BB_AREA_MW, 0),             /* 5  T MW0      10 */
    i_imm(7),                       /* 6  L 7        10 */
    i_T(BB_AREA_MW, 1),             /* 7  T MW1      10 */
    END_B,                          /* 8  END_B       0 */
  };
  setup();
  load(p, NWORDS(p));
  return bb_run_scan(&S);
}

static void test_jump_on_compare(void) {
  /* taken: 0 1 2 3 6 7 8 = 3x10 + 1 + 2x10 + 0 = 51; not taken: all = 30+1+40 = 71 */
  static const struct { unsigned cmp, jop; int taken; } c[] = {
    {BB_CMP_LT, BB_OP_JC_B, 1},     /* 3 < 5: F_B = 1 */
    {BB_CMP_GT, BB_OP_JC_B, 0},     /* 3 > 5: F_B = 0 */
    {BB_CMP_LT, BB_OP_JCN_B, 0},
    {BB_CMP_GT, BB_OP_JCN_B, 1},
    {BB_CMP_GT, BB_OP_JU_B, 1},     /* JU_B jumps whatever F_B is */
    {BB_CMP_LT, BB_OP_JU_B, 1},
  };
  for (unsigned i = 0; i < NWORDS(c); i++) {
    int clocks = run_cmp_jump(c[i].cmp, c[i].jop);
    CHECK_EQ(clocks, c[i].taken ? 51 : 71);
    CHECK_EQ(S.scan_steps, c[i].taken ? 7u : 9u);
    CHECK_EQ(bb_mw(&S, 0), c[i].taken ? 0 : 111);
    CHECK_EQ(bb_mw(&S, 1), 7);
    CHECK_EQ(bb_fb(&S), c[i].cmp == BB_CMP_LT);     /* a jump leaves F_B */
    CHECK_EQ(S.overruns, 0);
    CHECK_EQ(bb_flags(&S), 0);
  }
}

static void test_jump_on_read(void) {
  /* READ FBY 2 (1), J*_B 4 (1), [L 1 (10), T MW2 (10)], END_B: 2 taken, 22 not */
  for (unsigned jc = 0; jc < 2; jc++)
    for (unsigned v = 0; v < 2; v++) {
      const uint32_t p[] = {
        i_ch(BB_OP_READ, 2), i_j(jc ? BB_OP_JC_B : BB_OP_JCN_B, 4), i_imm(1),
        i_T(BB_AREA_MW, 2), END_B,
      };
      setup();
      load(p, NWORDS(p));
      FH.fby_val[2] = v;
      const int taken = jc ? v == 1 : v == 0;
      CHECK_EQ(bb_run_scan(&S), taken ? 2 : 22);
      CHECK_EQ(bb_mw(&S, 2), taken ? 0 : 1);
      CHECK_EQ(bb_fb(&S), (int)v);
      CHECK_EQ(S.scan_steps, taken ? 3u : 5u);
      CHECK_EQ(FH.fby_reads[2], 1);
    }
  /* a stalled READ (3 not-ready clocks) delays the scan, it does not change the path:
   * 4 + 1 = 5 clocks, one overrun */
  const uint32_t p[] = {
    i_ch(BB_OP_READ, 2), i_j(BB_OP_JC_B, 4), i_imm(1), i_T(BB_AREA_MW, 2), END_B,
  };
  setup();
  load(p, NWORDS(p));
  FH.fby_val[2] = 1;
  FH.fby_stall[2] = 3;
  CHECK_EQ(bb_run_scan(&S), 5);
  CHECK_EQ(S.overruns, 1);
  CHECK_EQ(bb_mw(&S, 2), 0);
}

/* MW0 := 0; do MW0 := MW0 + 1 until MW0 >= 3 (JC_B out, JU_B back). */
static const uint32_t loop3[] = {
  BB_INSTR_IMM(BB_OP_L_IMM, 0),             /* 0  L 0         10 */
  BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 0),    /* 1  T MW0       10 */
  BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 0),    /* 2  L MW0       10   <- loop */
  BB_INSTR_IMM(BB_OP_L_IMM, 1),             /* 3  L 1         10 */
  (uint32_t)BB_OP_ADD << 24,                /* 4  +I          10 */
  BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 0),    /* 5  T MW0       10 */
  BB_INSTR_IMM(BB_OP_L_IMM, 3),             /* 6  L 3         10 */
  (uint32_t)(BB_OP_CMP + BB_CMP_GE) << 24,  /* 7  >=I         10 */
  BB_INSTR_JUMP(BB_OP_JC_B, 10),            /* 8  JC_B 10      1 */
  BB_INSTR_JUMP(BB_OP_JU_B, 2),             /* 9  JU_B 2       1 */
  (uint32_t)BB_OP_END_B << 24,              /* 10 END_B        0 */
};

static void test_backward_loop(void) {
  /* 20 (0,1) + 2 x 62 (MW0 = 1, 2: 2..9) + 61 (MW0 = 3: 2..8) + 0 = 205 clocks;
   * 2 + 2 x 8 + 7 + 1 = 26 instructions */
  setup();
  load(loop3, NWORDS(loop3));
  CHECK_EQ(bb_run_scan(&S), 205);
  CHECK_EQ(S.scan_steps, 26);
  CHECK_EQ(bb_mw(&S, 0), 3);
  CHECK_EQ(bb_fb(&S), 1);
  CHECK_EQ(S.pc, 11);
  CHECK_EQ(S.overruns, 0);
  CHECK_EQ(bb_flags(&S), 0);
  /* again: the program clears MW0 itself, same path */
  CHECK_EQ(bb_run_scan(&S), 205);
  CHECK_EQ(bb_mw(&S, 0), 3);
  /* max_steps = 26 is just enough; 25 stops before END_B: 205 + 1 (BYTE_FLAGS) */
  setup();
  load(loop3, NWORDS(loop3));
  S.max_steps = 26;
  CHECK_EQ(bb_run_scan(&S), 205);
  CHECK_EQ(bb_flags(&S), 0);
  S.max_steps = 25;
  CHECK_EQ(bb_run_scan(&S), 206);
  CHECK_EQ(bb_flags(&S), BB_FLAG_RUNAWAY);
  CHECK_EQ(S.scan_steps, 25);
  CHECK_EQ(S.pc, 10);
  CHECK_EQ(bb_mw(&S, 0), 3);
}

static void test_runaway(void) {
  setup();
  CHECK_EQ(S.max_steps, BB_MAX_STEPS_DEFAULT);
  CHECK_EQ(BB_MAX_STEPS_DEFAULT, 1000000u);
  const uint32_t spin[] = { i_j(BB_OP_JU_B, 0), END_B };
  load(spin, NWORDS(spin));
  /* 1 000 000 JU_B x 1 clock + 1 BYTE_FLAGS write */
  CHECK_EQ(bb_run_scan(&S), 1000001);
  CHECK_EQ(bb_flags(&S), BB_FLAG_RUNAWAY);
  CHECK_EQ(FH.byte_flags, BB_FLAG_RUNAWAY);
  CHECK_EQ(S.scan_steps, 1000000u);
  CHECK_EQ(FH.nlog, 1);
  CHECK_ACCESS(0, BB_BUS_BYTE_FLAGS, 1000000);
  CHECK_EQ(S.overruns, 0);
  /* a smaller limit; JCN_B 0 spins too, because F_B is 0 at scan start */
  setup();
  S.max_steps = 1000;
  const uint32_t spin_n[] = { i_j(BB_OP_JCN_B, 0) };
  load(spin_n, NWORDS(spin_n));
  CHECK_EQ(bb_run_scan(&S), 1001);
  CHECK_EQ(bb_flags(&S), BB_FLAG_RUNAWAY);
  /* sticky: a good scan afterwards keeps it, and the flag word carries both bits */
  const uint32_t good[] = { i_imm(1), i_j(BB_OP_JU_B, 7) /* past the end: illegal */ };
  load(good, NWORDS(good));
  CHECK_EQ(bb_run_scan(&S), 11);                  /* 10 + illegal 1 (its flag write) */
  CHECK_EQ(bb_flags(&S), BB_FLAG_RUNAWAY | BB_FLAG_ILLEGAL);
  CHECK_EQ(FH.byte_flags, BB_FLAG_RUNAWAY | BB_FLAG_ILLEGAL);
  /* max_steps = 0: not even END_B runs */
  setup();
  S.max_steps = 0;
  const uint32_t only_end[] = { END_B };
  load(only_end, NWORDS(only_end));
  CHECK_EQ(bb_run_scan(&S), 1);
  CHECK_EQ(bb_flags(&S), BB_FLAG_RUNAWAY);
  CHECK_EQ(S.scan_steps, 0);
}

static void test_scan_start_reset(void) {
  /* 0 JC_B 7 (taken only if F_B survived the last scan); 1 +I; 2 T MW0 (0 only if the
   * ACCUs were cleared); 3 L 20; 4 L 20; 5 ==I (F_B := 1); 6 T MW1; 7 END_B.
   * 1 + 6 x 10 = 61 clocks */
  const uint32_t p[] = {
    i_j(BB_OP_JC_B, 7), i_op(BB_OP_ADD), i_T(BB_AREA_MW, 0), i_imm(20), i_imm(20),
    i_cmp(BB_OP_CMP, BB_CMP_EQ), i_T(BB_AREA_MW, 1), END_B,
  };
  setup();
  load(p, NWORDS(p));
  S.accu1 = 1000;            /* left over from anything: cleared by the scan */
  S.accu2 = 7;
  S.rlo = 1;
  S.mw[0] = 99;
  CHECK_EQ(bb_run_scan(&S), 61);
  CHECK_EQ(bb_mw(&S, 0), 0);
  CHECK_EQ(bb_mw(&S, 1), 20);
  CHECK_EQ(bb_fb(&S), 1);
  CHECK_EQ(bb_accu1(&S), 20);
  CHECK_EQ(bb_accu2(&S), 20);
  S.mw[0] = 99;
  CHECK_EQ(bb_run_scan(&S), 61);     /* F_B = 1 and ACCUs = 20 at the end of scan 1 */
  CHECK_EQ(bb_mw(&S, 0), 0);
  CHECK_EQ(S.scan_steps, 8);
  CHECK_EQ(bb_fb(&S), 1);
}

static void test_end_by_jump(void) {
  /* 0 L 5 (10); 1 JU_B 4 (1); 2 L 6; 3 T MW0; 4 END_B (0); 5 L 7; 6 T MW1 */
  const uint32_t p[] = {
    i_imm(5), i_j(BB_OP_JU_B, 4), i_imm(6), i_T(BB_AREA_MW, 0), END_B, i_imm(7),
    i_T(BB_AREA_MW, 1),
  };
  CHECK_SCAN(p, 11, 3, 5);
  CHECK_EQ(bb_executed(&S), 3);
  CHECK_EQ(bb_mw(&S, 0), 0);
  CHECK_EQ(bb_mw(&S, 1), 0);          /* nothing after END_B runs */
  CHECK_EQ(bb_accu1(&S), 5);
  CHECK_EQ(bb_flags(&S), 0);
  /* reserved bits 23..16 of a jump are ignored */
  const uint32_t q[] = { i_j(BB_OP_JU_B, 2) | 0x00FF0000u, i_imm(1), END_B };
  load(q, NWORDS(q));
  CHECK_EQ(bb_run_scan(&S), 1);
  CHECK_EQ(bb_accu1(&S), 0);
  CHECK_EQ(bb_flags(&S), 0);
}

static void test_off_the_end(void) {
  /* no END_B: L 9 (10), T MW3 (10) = 20 */
  const uint32_t a[] = { i_imm(9), i_T(BB_AREA_MW, 3) };
  CHECK_SCAN(a, 20, 2, 2);
  CHECK_EQ(bb_mw(&S, 3), 9);
  CHECK_EQ(bb_flags(&S), 0);
  /* a jump to the program length (4) ends the scan: L 1 (10) + JU_B (1) = 11 */
  const uint32_t b[] = { i_imm(1), i_j(BB_OP_JU_B, 4), i_imm(2), i_T(BB_AREA_MW, 0) };
  CHECK_SCAN(b, 11, 2, 4);
  CHECK_EQ(bb_mw(&S, 0), 0);
  CHECK_EQ(bb_flags(&S), 0);
  /* a jump past it (5 > 4) is illegal: flag, no jump, illegal cost (1, its flag write
   * included), the program goes on: 1 + 1 + 10 + 10 = 22 */
  const uint32_t c[] = {
    i_j(BB_OP_JC_B, 5), i_j(BB_OP_JU_B, 5), i_imm(4), i_T(BB_AREA_MW, 0),
  };
  setup();
  load(c, NWORDS(c));
  CHECK_EQ(bb_run_scan(&S), 1 + 1 + 10 + 10);  /* JC_B 5 is checked even when F_B = 0 */
  CHECK_EQ(bb_flags(&S), BB_FLAG_ILLEGAL);
  CHECK_EQ(bb_mw(&S, 0), 4);
  CHECK_EQ(S.overruns, 0);
  /* no program at all: 0 clocks, no access */
  setup();
  CHECK_EQ(bb_run_scan(&S), 0);
  CHECK_EQ(S.scan_steps, 0);
  CHECK_EQ(FH.nlog, 0);
  /* a full program: 4096 x JCN_B i+1 (F_B = 0: all taken, the last to 4096 = the
   * end) = 4096 clocks */
  static uint32_t full[BB_PROG_WORDS];
  for (unsigned i = 0; i < BB_PROG_WORDS; i++) full[i] = i_j(BB_OP_JCN_B, i + 1);
  CHECK_SCAN(full, 4096, 4096, 4096);
  CHECK_EQ(bb_flags(&S), 0);
}

static void test_load_program(void) {
  static uint32_t big[BB_PROG_WORDS + 1];
  const uint32_t p[] = { i_imm(3), END_B };
  setup();
  CHECK_EQ(BB_PROG_WORDS, 4096u);
  CHECK_EQ(S.prog_len, 0);
  CHECK_EQ(bb_load_program(&S, p, 2), 0);
  CHECK_EQ(S.prog_len, 2);
  CHECK_EQ(S.prog[0], i_imm(3));
  CHECK_EQ(S.prog[1], 0xCF000000u);
  /* too long / NULL with words: refused, the loaded program stays */
  CHECK_EQ(bb_load_program(&S, big, BB_PROG_WORDS + 1), -1);
  CHECK_EQ(bb_load_program(&S, NULL, 1), -1);
  CHECK_EQ(S.prog_len, 2);
  CHECK_EQ(S.prog[0], i_imm(3));
  CHECK_EQ(bb_run_scan(&S), 10);
  CHECK_EQ(bb_accu1(&S), 3);
  CHECK_EQ(bb_load_program(&S, NULL, 0), 0);   /* empty */
  CHECK_EQ(S.prog_len, 0);
  CHECK_EQ(bb_load_program(&S, big, BB_PROG_WORDS), 0);
  CHECK_EQ(S.prog_len, BB_PROG_WORDS);
  /* bb_init drops the program */
  bb_init(&S, NULL);
  CHECK_EQ(S.prog_len, 0);
  CHECK_EQ(S.max_steps, BB_MAX_STEPS_DEFAULT);
  bb_set_hal_ctx(&S, &FH);
}

static void test_classify_and_step(void) {
  CHECK_EQ(bb_classify(i_j(BB_OP_JU_B, 0)), BB_CL_BINARY);
  CHECK_EQ(bb_classify(i_j(BB_OP_JC_B, 0xFFFF)), BB_CL_BINARY);
  CHECK_EQ(bb_classify(i_j(BB_OP_JCN_B, 12)), BB_CL_BINARY);
  CHECK_EQ(bb_classify(END_B), BB_CL_END);
  for (unsigned op = 0xCB; op <= 0xCE; op++)
    CHECK_EQ(bb_classify(op << 24), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(0xC7000000u), BB_CL_ILLEGAL);
  CHECK_EQ(bb_cost_table("paper")->clocks[BB_CL_END], 0);
  CHECK_EQ(bb_cost_table("c320")->clocks[BB_CL_END], 0);
  CHECK_EQ(bb_cost_table("paper")->clocks[BB_CL_BINARY], 1);
  CHECK(strcmp(bb_class_name(BB_CL_END), "end") == 0);
  /* bb_step: END_B takes 0 clocks (no spend at all); a jump 1, taken or not */
  setup();
  const uint32_t p[] = { END_B, END_B, END_B };
  load(p, NWORDS(p));
  int rlo = 1;
  CHECK_EQ(bb_step(&S, END_B, &rlo), 0);
  CHECK_EQ(FH.spend_calls, 0);
  CHECK_EQ(rlo, 1);
  CHECK_EQ(bb_step(&S, i_j(BB_OP_JC_B, 2), &rlo), 1);
  CHECK_EQ(S.jumped, 1);
  CHECK_EQ(S.pc, 2);
  CHECK_EQ(bb_step(&S, i_j(BB_OP_JCN_B, 3), &rlo), 1);
  CHECK_EQ(S.jumped, 0);
  CHECK_EQ(S.pc, 2);
  CHECK_EQ(FH.clock, 2);
  CHECK_EQ(FH.nlog, 0);                         /* jumps have no bus access */
  CHECK_EQ(bb_flags(&S), 0);
}

/* Dispatch one instruction in serial mode at the current clock. */
static int dispatch(uint32_t instr) {
  FH.dispatch_instr = instr;
  FH.dispatch_ctx = 1u;                         /* scan 0, RLO 1 */
  FH.dispatch_at = FH.clock;
  return bb_serial_step(&S);
}

static void test_serial_rejects(void) {
  /* the byte program's instructions are illegal when dispatched: INSTR, CTX,
   * BYTE_FLAGS, DONE = 4 clocks (over the illegal cost of 1); the RLO comes back */
  const uint32_t ins[] = {
    i_j(BB_OP_JU_B, 0), i_j(BB_OP_JC_B, 0), i_j(BB_OP_JCN_B, 0), END_B,
  };
  for (unsigned i = 0; i < NWORDS(ins); i++) {
    setup();
    CHECK_EQ(dispatch(ins[i]), 4);
    CHECK_EQ(S.last_class, BB_CL_ILLEGAL);
    CHECK_EQ(bb_flags(&S), BB_FLAG_ILLEGAL);
    CHECK_EQ(FH.done_data, 1u);                 /* RLO 1, not written */
    CHECK_EQ(S.jumped, 0);
    CHECK_EQ(S.pc, 0);
  }
}

/* bb_run_step(): the firmware's own main loop in each mode, against the fake HAL. */
static void test_run_step_modes(void) {
  /* serial: one dispatched instruction, exactly bb_serial_step()'s protocol */
  setup();
  FH.dispatch_instr = BB_INSTR_IMM(BB_OP_L_IMM, 7);
  FH.dispatch_ctx = 0;
  FH.dispatch_at = 40;
  fh_clear_log();
  CHECK_EQ(bb_run_step(&S, BB_MODE_SERIAL), 10);
  CHECK_EQ(FH.waits, 1);
  CHECK_EQ(FH.done_count, 1);
  CHECK_EQ(FH.clock, 50);
  CHECK_EQ(S.accu1, 7);
  CHECK_EQ(bb_byte_scans(&S), 0);            /* no scan reported in serial mode */
  CHECK_EQ(FH.log[FH.nlog - 1].addr, BB_BUS_DONE);

  /* parallel: wait for the latch (NEXT), the byte part, then SCAN_DONE */
  setup();
  load(fig13, NWORDS(fig13));
  FH.fby_val[0] = 1;
  FH.dispatch_at = 100;
  fh_clear_log();
  CHECK_EQ(bb_run_step(&S, BB_MODE_PARALLEL), 53);   /* 52 of the part + SCAN_DONE */
  CHECK_EQ(FH.waits, 1);
  CHECK_EQ(FH.clock, 153);
  CHECK_EQ(FH.log[FH.nlog - 1].addr, BB_BUS_SCAN_DONE);
  CHECK_EQ(FH.log[FH.nlog - 1].write, 1);
  CHECK_EQ(FH.log[FH.nlog - 1].clock, 152);          /* the clock after the part */
  CHECK_EQ(bb_byte_scans(&S), 1);

  /* free-running: no wait at all, scan after scan */
  setup();
  load(fig13, NWORDS(fig13));
  FH.fby_val[0] = 1;
  FH.dispatch_at = 1000;                             /* would be waited for: is not */
  CHECK_EQ(bb_run_step(&S, BB_MODE_FREE), 53);
  CHECK_EQ(bb_run_step(&S, BB_MODE_FREE), 53);
  CHECK_EQ(FH.waits, 0);
  CHECK_EQ(FH.clock, 106);
  CHECK_EQ(bb_byte_scans(&S), 2);

  CHECK_EQ(bb_run_step(&S, (bb_mode)7), -1);         /* an unknown mode does nothing */
  CHECK_EQ(FH.clock, 106);
  bb_run(&S, (bb_mode)7);                            /* ... and bb_run returns */
}

/* bb_run(): the loop that never returns on its own, in each mode. The fake HAL stops
 * it (longjmp out of a bus access) once it has written `stop_after` times to
 * `stop_reg` (DONE in serial mode, SCAN_DONE otherwise). */
static jmp_buf run_stop;
static uint16_t stop_reg;
static unsigned stop_after, stop_seen;

static void stop_run(void *arg) {
  (void)arg;
  const fh_access *a = &FH.log[FH.nlog - 1];
  if (a->write && a->addr == stop_reg && ++stop_seen == stop_after) longjmp(run_stop, 1);
}

static void run_until(bb_mode mode, uint16_t reg, unsigned writes) {
  stop_reg = reg;
  stop_after = writes;
  stop_seen = 0;
  FH.after_access = stop_run;
  if (setjmp(run_stop) == 0) {
    bb_run(&S, mode);
    CHECK(0);                                        /* bb_run returned: it must not */
  }
  FH.after_access = NULL;
}

/* Fig. 13's byte part (FBY 0 = 1) until its `scans`-th SCAN_DONE; a latch would come
 * at clock `latch_at` */
static void run_fig13(bb_mode mode, uint64_t latch_at, unsigned scans) {
  setup();
  load(fig13, NWORDS(fig13));
  FH.fby_val[0] = 1;
  FH.dispatch_at = latch_at;
  run_until(mode, BB_BUS_SCAN_DONE, scans);
}

static void test_run_modes(void) {
  /* serial: three dispatched L 7, each 10 clocks after its dispatch at clock 40 */
  setup();
  FH.dispatch_instr = BB_INSTR_IMM(BB_OP_L_IMM, 7);
  FH.dispatch_at = 40;
  run_until(BB_MODE_SERIAL, BB_BUS_DONE, 3);
  CHECK_EQ(FH.done_count, 3);
  CHECK_EQ(FH.waits, 3);
  CHECK_EQ(S.accu1, 7);
  CHECK_EQ(S.accu2, 7);
  CHECK_EQ(bb_byte_scans(&S), 0);

  /* parallel: each scan waits for its latch (dispatch_at 100, then at once), runs the
   * 52-clock part and writes SCAN_DONE: 100 + 53, + 53 */
  run_fig13(BB_MODE_PARALLEL, 100, 2);
  CHECK_EQ(FH.waits, 2);
  CHECK_EQ(FH.clock, 206);
  CHECK_EQ(bb_byte_scans(&S), 2);                    /* counted as announced */

  /* free-running: never waits, three scans back to back from clock 0 */
  run_fig13(BB_MODE_FREE, 1000, 3);
  CHECK_EQ(FH.waits, 0);
  CHECK_EQ(FH.clock, 159);
  CHECK_EQ(bb_byte_scans(&S), 3);
}

void suite_program(void) {
  RUN(test_fig13_straight);
  RUN(test_timer_at_latch_parallel);
  RUN(test_jump_on_compare);
  RUN(test_jump_on_read);
  RUN(test_backward_loop);
  RUN(test_runaway);
  RUN(test_scan_start_reset);
  RUN(test_end_by_jump);
  RUN(test_off_the_end);
  RUN(test_load_program);
  RUN(test_classify_and_step);
  RUN(test_serial_rejects);
  RUN(test_run_step_modes);
  RUN(test_run_modes);
}
