/* test_bus.c — the bus accesses each instruction makes, checked against
 * docs/byte-bus.md: address, direction, data and order, for bb_exec() (the bare
 * procedure) and inside the serial protocol. Plus: every opcode with odd operands runs
 * without a crash, and bb_classify() agrees with what execution does. */
#include "tt.h"

#define R 0
#define W 1
#define ANY 0xFFFFFFFFu   /* data not checked */

typedef struct { uint16_t addr; uint8_t write; uint32_t data; } acc;

typedef struct {
  const char *name;
  uint32_t instr;
  int rlo;
  int32_t accu2, accu1;
  unsigned n;             /* expected accesses */
  acc a[3];
} row;

static const row rows[] = {
  {"L 5", 0x80000005u, 0, 0, 0, 0, {{0}}},
  {"L pool[0]", BB_INSTR_IMM(BB_OP_L_POOL, 0), 0, 0, 0, 0, {{0}}},
  {"L IW3", BB_INSTR(BB_OP_L_WORD, BB_AREA_IW, 3), 0, 0, 0, 1, {{0x43, R, ANY}}},
  {"L QW2", BB_INSTR(BB_OP_L_WORD, BB_AREA_QW, 2), 0, 0, 0, 1, {{0x52, R, ANY}}},
  {"L MW7", BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 7), 0, 0, 0, 0, {{0}}},
  {"L T1", BB_INSTR(BB_OP_L_WORD, BB_AREA_T, 1), 0, 0, 0, 0, {{0}}},
  {"L C1", BB_INSTR(BB_OP_L_WORD, BB_AREA_C, 1), 0, 0, 0, 0, {{0}}},
  {"T MW7", BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 7), 0, 0, -2, 0, {{0}}},
  {"T QW15", BB_INSTR(BB_OP_T_WORD, BB_AREA_QW, 15), 0, 0, -2, 1, {{0x5F, W, 0xFFFE}}},
  {"+I", 0x88000000u, 0, 1, 2, 0, {{0}}},
  {"-I", 0x89000000u, 0, 1, 2, 0, {{0}}},
  {"*I", 0x8A000000u, 0, 1, 2, 0, {{0}}},
  {"/I", 0x8B000000u, 0, 1, 2, 0, {{0}}},
  {"MOD", 0x8C000000u, 0, 1, 2, 0, {{0}}},
  {"/I by 0", 0x8B000000u, 0, 1, 0, 1, {{0x62, W, BB_FLAG_ARITH}}},
  {"MOD by 0", 0x8C000000u, 0, 1, 0, 1, {{0x62, W, BB_FLAG_ARITH}}},
  {"==I", 0x90000000u, 0, 1, 2, 0, {{0}}},
  {"A <=I", 0x9D000000u, 1, 1, 2, 0, {{0}}},
  {"O >I", 0xA2000000u, 0, 1, 2, 0, {{0}}},
  {"SD T5 (0)", BB_INSTR(BB_OP_SD, BB_AREA_T, 5), 1, 0, 3, 2,
   {{0x08, R, ANY}, {0x10, W, 0x005}}},
  {"SD T5 (1)", BB_INSTR(BB_OP_SD, BB_AREA_T, 5), 1, 0, 0, 2,
   {{0x08, R, ANY}, {0x10, W, 0x105}}},
  {"SS T6", BB_INSTR(BB_OP_SS, BB_AREA_T, 6), 1, 0, 0, 2, {{0x08, R, ANY}, {0x10, W, 0x106}}},
  {"SP T7", BB_INSTR(BB_OP_SP, BB_AREA_T, 7), 1, 0, 9, 2, {{0x08, R, ANY}, {0x10, W, 0x107}}},
  {"SF T63", BB_INSTR(BB_OP_SF, BB_AREA_T, 63), 1, 0, 9, 2,
   {{0x08, R, ANY}, {0x10, W, 0x13F}}},
  {"R T5", BB_INSTR(BB_OP_RT, BB_AREA_T, 5), 1, 0, 0, 1, {{0x10, W, 0x005}}},
  {"CU C1", BB_INSTR(BB_OP_CU, BB_AREA_C, 1), 1, 0, 0, 1, {{0x10, W, 0x141}}},
  {"CD C2", BB_INSTR(BB_OP_CD, BB_AREA_C, 2), 1, 0, 0, 1, {{0x10, W, 0x042}}},
  {"S C3", BB_INSTR(BB_OP_SC, BB_AREA_C, 3), 1, 0, 9, 1, {{0x10, W, 0x143}}},
  {"R C63", BB_INSTR(BB_OP_RC, BB_AREA_C, 63), 1, 0, 0, 1, {{0x10, W, 0x07F}}},
  {"READ FBY 1", BB_INSTR(BB_OP_READ, BB_AREA_FB, 1), 0, 0, 0, 1, {{0x21, R, ANY}}},
  {"WRITE FBI 2", BB_INSTR(BB_OP_WRITE, BB_AREA_FB, 2), 1, 0, 0, 1, {{0x2A, W, 1}}},
  {"WRITE FBI 3 (0)", BB_INSTR(BB_OP_WRITE, BB_AREA_FB, 3), 0, 0, 0, 1, {{0x2B, W, 0}}},
  {"illegal 0xFF", 0xFF000000u, 0, 0, 0, 1, {{0x62, W, BB_FLAG_ILLEGAL}}},
  {"illegal T IW", BB_INSTR(BB_OP_T_WORD, BB_AREA_IW, 0), 0, 0, 0, 1,
   {{0x62, W, BB_FLAG_ILLEGAL}}},
};

static void prepare(const row *r) {
  static const uint32_t pool[] = {123};
  setup();
  bb_load_pool(&S, pool, 1);
  S.accu2 = r->accu2;
  S.accu1 = r->accu1;
  RLO = r->rlo;
  FH.clock = 5000;
}

static void check_accesses(const row *r, unsigned first, unsigned n, uint64_t clock0) {
  CHECK_EQ(n, r->n);
  for (unsigned i = 0; i < r->n && i < n; i++) {
    const fh_access *a = &FH.log[first + i];
    if (a->addr != r->a[i].addr || a->write != r->a[i].write ||
        (r->a[i].data != ANY && a->data != r->a[i].data))
      fprintf(stderr, "  %s: access %u is %s 0x%02X data 0x%X\n", r->name, i,
              a->write ? "W" : "R", a->addr, a->data);
    CHECK_EQ(a->addr, r->a[i].addr);
    CHECK_EQ(a->write, r->a[i].write);
    if (r->a[i].data != ANY) CHECK_EQ(a->data, r->a[i].data);
    CHECK_EQ(a->clock, clock0 + i);      /* one clock each, back to back */
  }
}

static void test_exec_accesses(void) {
  for (unsigned i = 0; i < sizeof rows / sizeof rows[0]; i++) {
    const row *r = &rows[i];
    prepare(r);
    ex(r->instr);
    check_accesses(r, 0, FH.nlog, 5000);
    CHECK_EQ(FH.clock, 5000 + r->n);     /* bb_exec itself spends nothing */
  }
}

static void test_serial_accesses(void) {
  /* inside the serial protocol: DISPATCH_INSTR (t0), DISPATCH_CTX (t0+1), the
   * instruction's own accesses from t0+2 on, with the dispatch snapshot in place of the
   * live inputs (a timer reads DISPATCH_MS instead of TIME_MS, L IW n DISPATCH_IW
   * instead of 0x40+n), then DONE in the cost's last clock */
  for (unsigned i = 0; i < sizeof rows / sizeof rows[0]; i++) {
    const row *r = &rows[i];
    prepare(r);
    FH.iw[r->instr & 0xFu] = 0x8001u;    /* raw 16 bits: DISPATCH_IW sign-extends */
    FH.dispatch_instr = r->instr;
    FH.dispatch_ctx = (uint32_t)r->rlo;  /* FIRST clear: the prepared ACCUs stay */
    FH.dispatch_at = 6000;               /* TIME_MS 6 (1000 clocks per ms) */
    bb_serial_step(&S);
    CHECK(FH.nlog >= 3);
    if (FH.nlog < 3) continue;
    CHECK_EQ(FH.log[0].addr, BB_BUS_DISPATCH_INSTR);
    CHECK_EQ(FH.log[0].write, 0);
    CHECK_EQ(FH.log[0].clock, 6000);
    CHECK_EQ(FH.log[1].addr, BB_BUS_DISPATCH_CTX);
    CHECK_EQ(FH.log[1].write, 0);
    CHECK_EQ(FH.log[1].clock, 6001);
    row own = *r;
    for (unsigned k = 0; k < own.n; k++) {
      if (!own.a[k].write && own.a[k].addr == BB_BUS_TIME_MS) {
        own.a[k].addr = BB_BUS_DISPATCH_MS;
        own.a[k].data = 6;
      } else if (!own.a[k].write && own.a[k].addr >= BB_BUS_IW(0) &&
                 own.a[k].addr <= BB_BUS_IW(15)) {
        own.a[k].addr = BB_BUS_DISPATCH_IW;
        own.a[k].data = 0xFFFF8001u;
      }
    }
    check_accesses(&own, 2, FH.nlog - 3, 6002);
    const fh_access *d = &FH.log[FH.nlog - 1];
    CHECK_EQ(d->addr, BB_BUS_DONE);
    CHECK_EQ(d->write, 1);
    uint32_t cost = bb_cost(&S, bb_classify(r->instr));
    CHECK_EQ(d->clock, 6000 + (cost > 3 + own.n ? cost : 3 + own.n) - 1);
    for (unsigned k = 0; k < FH.nlog; k++) {
      CHECK(FH.log[k].addr != BB_BUS_STATUS);
      CHECK(FH.log[k].addr != BB_BUS_TIME_MS);                 /* the snapshot only */
      CHECK(FH.log[k].addr < BB_BUS_IW(0) || FH.log[k].addr > BB_BUS_IW(15));
    }
  }
}

static void test_no_crash_any_opcode(void) {
  /* every opcode with a spread of operand fields: no crash, and execution's class is
   * bb_classify()'s (pool index, jump target aside), an illegal one sets the flag and
   * nothing else */
  static const uint32_t operands[] = {
    0x000000u, 0x000001u, 0x007003u, 0x00703Fu, 0x007040u, 0x008005u, 0x009003u,
    0x009008u, 0x00A00Fu, 0x00A010u, 0x00B00Fu, 0x00C0FFu, 0x00C100u, 0x00F000u,
    0xFFFFFFu, 0x800000u, 0x123456u,
  };
  for (unsigned op = 0; op < 256; op++)
    for (unsigned j = 0; j < sizeof operands / sizeof operands[0]; j++) {
      uint32_t instr = ((uint32_t)op << 24) | operands[j];
      setup();
      FH.fby_val[0] = 1;
      int cls = ex(instr);
      CHECK(cls >= 0 && cls < BB_NUM_CLASSES);
      int want = bb_classify(instr);
      if (op == BB_OP_L_POOL) want = BB_CL_ILLEGAL;   /* the pool is empty here */
      const int jump = op == BB_OP_JU_B || op == BB_OP_JC_B || op == BB_OP_JCN_B;
      if (jump && (instr & 0xFFFFu) > 0) want = BB_CL_ILLEGAL;  /* no byte program */
      CHECK_EQ(cls, want);
      CHECK_EQ((S.flags & BB_FLAG_ILLEGAL) != 0, cls == BB_CL_ILLEGAL);
      if (op < 0x80) CHECK_EQ(cls, BB_CL_ILLEGAL);   /* bit instructions */
    }
}

/* A plant core: MW lives in the FPGA; L / T MW n are one bus access each, values and
 * sign as with the firmware's own array. */
static void test_mw_on_bus(void) {
  setup();
  bb_set_mw_bus(&S, 1);
  FH.mw[7] = 0xFFFEu;                       /* -2 */
  int rlo = 0;
  fh_clear_log();
  bb_exec(&S, BB_INSTR(BB_OP_L_WORD, BB_AREA_MW, 7), &rlo);
  CHECK_EQ(FH.nlog, 1u);
  CHECK_EQ(FH.log[0].addr, BB_BUS_MW(7));
  CHECK_EQ(bb_accu1(&S), -2);
  bb_exec(&S, BB_INSTR_IMM(BB_OP_L_IMM, 0x12345), &rlo);
  bb_exec(&S, BB_INSTR(BB_OP_T_WORD, BB_AREA_MW, 255), &rlo);
  CHECK_EQ(FH.mw[255], 0x2345u);            /* the low 16 bits */
  CHECK_EQ(bb_mw(&S, 255), 0);              /* the firmware's array is not used */
  CHECK_EQ(FH.log[FH.nlog - 1].addr, BB_BUS_MW(255));
  CHECK_EQ(FH.log[FH.nlog - 1].write, 1);
}

void suite_bus(void) {
  RUN(test_mw_on_bus);
  RUN(test_exec_accesses);
  RUN(test_serial_accesses);
  RUN(test_no_crash_any_opcode);
}
