/* test_costs.c — the cost tables, bb_classify(), set-up and the accessors. */
#include <string.h>

#include "tt.h"

static void test_tables(void) {
  const bb_costs *p = bb_cost_table("paper");
  CHECK(p != NULL);
  CHECK(bb_cost_table(NULL) == p);       /* the default */
  CHECK(strcmp(p->name, "paper") == 0);
  for (int c = BB_CL_LOAD; c <= BB_CL_COUNTER; c++) CHECK_EQ(p->clocks[c], 10);
  CHECK_EQ(p->clocks[BB_CL_BINARY], 1);
  CHECK_EQ(p->clocks[BB_CL_ILLEGAL], 1);
  const bb_costs *q = bb_cost_table("c320");
  CHECK(q != NULL);
  CHECK(strcmp(q->name, "c320") == 0);
  for (int c = BB_CL_LOAD; c <= BB_CL_COUNTER; c++) CHECK_EQ(q->clocks[c], 57);
  CHECK_EQ(q->clocks[BB_CL_BINARY], 6);
  CHECK_EQ(q->clocks[BB_CL_ILLEGAL], 1);
  CHECK(bb_cost_table("s7") == NULL);
  CHECK(bb_cost_table("") == NULL);
  /* a serial word instruction must fit its protocol: 3 reads + 1 access + DONE */
  for (int c = BB_CL_LOAD; c <= BB_CL_COUNTER; c++) CHECK(q->clocks[c] >= 5);

  setup();
  CHECK(S.costs == p);
  CHECK_EQ(bb_cost(&S, BB_CL_TIMER), 10);
  CHECK_EQ(bb_cost(&S, -1), 0);
  CHECK_EQ(bb_cost(&S, BB_NUM_CLASSES), 0);
  CHECK_EQ(bb_set_costs(&S, "nope"), -1);
  CHECK(S.costs == p);
  CHECK_EQ(bb_set_costs(&S, "c320"), 0);
  CHECK_EQ(bb_cost(&S, BB_CL_COMPARE), 57);
  bb_init(&S, q);
  CHECK(S.costs == q);
  CHECK(bb_hal_ctx(&S) == NULL);             /* bb_init() forgets the HAL context */
  bb_set_hal_ctx(&S, &FH);
  CHECK(strcmp(bb_class_name(BB_CL_TIMER), "timer") == 0);
  CHECK(strcmp(bb_class_name(99), "?") == 0);
}

static void test_classify(void) {
  CHECK_EQ(bb_classify(0x80FFFFFFu), BB_CL_LOAD);
  CHECK_EQ(bb_classify(0x81000000u), BB_CL_LOAD);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 15)), BB_CL_LOAD);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_L_WORD, BB_AREA_FB, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 255)), BB_CL_TRANSFER);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_T_WORD, BB_AREA_C, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(0x88000000u), BB_CL_ARITH);
  CHECK_EQ(bb_classify(0x89000000u), BB_CL_ARITH);
  CHECK_EQ(bb_classify(0x8A000000u), BB_CL_MULDIV);
  CHECK_EQ(bb_classify(0x8C000000u), BB_CL_MULDIV);
  CHECK_EQ(bb_classify(0x84000000u), BB_CL_ARITH);      /* +D */
  CHECK_EQ(bb_classify(0x85000000u), BB_CL_ARITH);      /* -D */
  CHECK_EQ(bb_classify(0x86000000u), BB_CL_MULDIV);     /* *D */
  CHECK_EQ(bb_classify(0x87000000u), BB_CL_MULDIV);     /* /D */
  CHECK_EQ(bb_classify(0x8D000000u), BB_CL_MULDIV);     /* MODD */
  CHECK_EQ(bb_classify(0x8E000000u), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_L_WORD, BB_AREA_MD, 253)), BB_CL_LOAD);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_T_WORD, BB_AREA_MD, 254)), BB_CL_ILLEGAL);
  for (unsigned c = 0; c < 8; c++) {
    int want = c < 6 ? BB_CL_COMPARE : BB_CL_ILLEGAL;
    CHECK_EQ(bb_classify((0x90u + c) << 24), want);
    CHECK_EQ(bb_classify((0x98u + c) << 24), want);
    CHECK_EQ(bb_classify((0xA0u + c) << 24), want);
    CHECK_EQ(bb_classify((0xD0u + c) << 24), want);     /* ==D ... */
    CHECK_EQ(bb_classify((0xD8u + c) << 24), want);
    CHECK_EQ(bb_classify((0xE0u + c) << 24), want);
  }
  CHECK_EQ(bb_classify(0xE8000000u), BB_CL_ARITH);      /* AW */
  CHECK_EQ(bb_classify(0xED000000u), BB_CL_ARITH);      /* XOD */
  CHECK_EQ(bb_classify(0xEE000000u), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(0xF00000FFu), BB_CL_ARITH);      /* SLW 255 */
  CHECK_EQ(bb_classify(0xF7000800u), BB_CL_ARITH);      /* RRD, count from ACCU2 */
  CHECK_EQ(bb_classify(0xF0000100u), BB_CL_ILLEGAL);    /* SLW 256 */
  CHECK_EQ(bb_classify(0xF8000000u), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_RT, BB_AREA_T, 0)), BB_CL_TIMER);
  CHECK_EQ(bb_classify(BB_INSTR(0xB5, BB_AREA_T, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_RC, BB_AREA_C, 0)), BB_CL_COUNTER);
  CHECK_EQ(bb_classify(BB_INSTR(BB_OP_READ, BB_AREA_FB, 7)), BB_CL_BINARY);
  CHECK_EQ(bb_classify(BB_INSTR(0xC2, BB_AREA_FB, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(bb_classify(0x00000000u), BB_CL_ILLEGAL);
}

static void test_new_free_accessors(void) {
  bb_state *s = bb_new();
  CHECK(s != NULL);
  if (s == NULL) return;
  CHECK(s->costs == bb_cost_table(NULL));
  CHECK(bb_hal_ctx(s) == NULL);
  CHECK_EQ(bb_accu1(s), 0);
  CHECK_EQ(bb_accu2(s), 0);
  CHECK_EQ(bb_flags(s), 0);
  CHECK_EQ(bb_overruns(s), 0);
  CHECK_EQ(bb_executed(s), 0);
  for (unsigned n = 0; n < BB_NUM_MW; n++) CHECK_EQ(bb_mw(s, n), 0);
  for (unsigned n = 0; n < BB_NUM_TIMERS; n++) {
    CHECK_EQ(bb_timer_status(s, n), 0);
    CHECK_EQ(bb_timer_elapsed(s, n), 0);
  }
  for (unsigned n = 0; n < BB_NUM_COUNTERS; n++) CHECK_EQ(bb_counter_value(s, n), 0);
  fh_reset();
  bb_set_hal_ctx(s, &FH);
  CHECK(bb_hal_ctx(s) == &FH);
  int rlo = 1;
  bb_exec(s, 0x80000007u, &rlo);
  bb_exec(s, 0x80000009u, NULL);           /* NULL: the state's own F_B */
  CHECK_EQ(bb_accu1(s), 9);
  CHECK_EQ(bb_accu2(s), 7);
  CHECK_EQ(bb_rlo(s), 1);
  CHECK_EQ(bb_executed(s), 2);
  CHECK_EQ(bb_timer_elapsed(s, 1000), 0);
  CHECK_EQ(bb_counter_status(s, 1000), 0);
  CHECK_EQ(bb_timer_running(s, 1000), 0);
  bb_free(s);
  bb_free(NULL);
}

/* bb_classify() gives every opcode of the definition (bb_isa.h's BB_BYTE_OPCODES,
 * generated from bitbyte/lang/definition.toml) the class the definition names, for an
 * operand in range: the firmware's decoder and the definition agree. */
static uint32_t valid_operand(unsigned op, int cls) {
  switch (cls) {
    case BB_CL_TIMER:   return BB_INSTR(op, BB_AREA_T, BB_NUM_TIMERS - 1);
    case BB_CL_COUNTER: return BB_INSTR(op, BB_AREA_C, BB_NUM_COUNTERS - 1);
    case BB_CL_LOAD:
    case BB_CL_TRANSFER:
      return op == BB_OP_L_IMM || op == BB_OP_L_POOL ? BB_INSTR_IMM(op, 0)
                                                     : BB_INSTR(op, BB_AREA_MW, BB_NUM_MW - 1);
    case BB_CL_BINARY:
      return op == BB_OP_READ || op == BB_OP_WRITE
             ? BB_INSTR(op, BB_AREA_FB, BB_NUM_CHANNELS - 1) : BB_INSTR_JUMP(op, 0);
    default:            return BB_INSTR(op, 0, 0);
  }
}

static void test_definition_classes(void) {
  unsigned n = 0;
#define CHECK_CLASS(op, cls) \
  do { CHECK_EQ(bb_classify(valid_operand(op, cls)), cls); n++; } while (0);
  BB_BYTE_OPCODES(CHECK_CLASS)
#undef CHECK_CLASS
  CHECK(n >= 20);
  for (unsigned c = BB_CMP_EQ; c <= BB_CMP_LE; c++) {
    CHECK_EQ(bb_classify(BB_INSTR(BB_OP_CMP + c, 0, 0)), BB_CL_COMPARE);
    CHECK_EQ(bb_classify(BB_INSTR(BB_OP_A_CMP + c, 0, 0)), BB_CL_COMPARE);
    CHECK_EQ(bb_classify(BB_INSTR(BB_OP_O_CMP + c, 0, 0)), BB_CL_COMPARE);
  }
}

void suite_costs(void) {
  RUN(test_tables);
  RUN(test_classify);
  RUN(test_definition_classes);
  RUN(test_new_free_accessors);
}
