/* test_compare.c — ==I <>I >I <I >=I <=I and their A / O forms. */
#include "tt.h"

/* ACCU2 := a, ACCU1 := b, RLO := rlo_in, then the compare; returns the RLO. */
static int cmp(int32_t a, int32_t b, unsigned base, unsigned c, int rlo_in) {
  L(a);
  L(b);
  RLO = rlo_in;
  fh_clear_log();
  CHECK_EQ(ex(i_cmp(base, c)), BB_CL_COMPARE);
  CHECK_EQ(S.accu2, a);          /* accumulators unchanged */
  CHECK_EQ(S.accu1, b);
  CHECK_EQ(S.rlo_written, 1);
  CHECK_EQ(FH.nlog, 0);          /* no bus access */
  return RLO;
}

static void test_plain(void) {
  /* rows: ACCU2, ACCU1, then the expected ==, <>, >, <, >=, <= */
  static const int32_t rows[][8] = {
    {5, 3, 0, 1, 1, 0, 1, 0},
    {3, 5, 0, 1, 0, 1, 0, 1},
    {4, 4, 1, 0, 0, 0, 1, 1},
    {-1, 1, 0, 1, 0, 1, 0, 1},
    {-32768, 32767, 0, 1, 0, 1, 0, 1},
    {65535, -1, 1, 0, 0, 0, 1, 1},      /* INT(65535) = -1 */
    {70000, 4464, 1, 0, 0, 0, 1, 1},    /* INT(70000) = 4464 */
    {0, -70000, 0, 1, 1, 0, 1, 0},      /* INT(-70000) = -4464 */
  };
  setup();
  for (unsigned r = 0; r < sizeof rows / sizeof rows[0]; r++)
    for (unsigned c = 0; c < 6; c++) {
      /* the RLO before a plain compare does not matter */
      CHECK_EQ(cmp(rows[r][0], rows[r][1], BB_OP_CMP, c, 0), rows[r][2 + c]);
      CHECK_EQ(cmp(rows[r][0], rows[r][1], BB_OP_CMP, c, 1), rows[r][2 + c]);
      CHECK_EQ(bb_cmp16(c, rows[r][0], rows[r][1]), rows[r][2 + c]);
    }
}

static void test_and_or(void) {
  setup();
  /* A cmp: RLO AND result */
  CHECK_EQ(cmp(5, 3, BB_OP_A_CMP, BB_CMP_GT, 1), 1);
  CHECK_EQ(cmp(5, 3, BB_OP_A_CMP, BB_CMP_GT, 0), 0);
  CHECK_EQ(cmp(3, 5, BB_OP_A_CMP, BB_CMP_GT, 1), 0);
  CHECK_EQ(cmp(3, 5, BB_OP_A_CMP, BB_CMP_GT, 0), 0);
  /* O cmp: RLO OR result */
  CHECK_EQ(cmp(5, 3, BB_OP_O_CMP, BB_CMP_LT, 0), 0);
  CHECK_EQ(cmp(5, 3, BB_OP_O_CMP, BB_CMP_LT, 1), 1);
  CHECK_EQ(cmp(3, 5, BB_OP_O_CMP, BB_CMP_LT, 0), 1);
  CHECK_EQ(cmp(3, 5, BB_OP_O_CMP, BB_CMP_LT, 1), 1);
  /* paper Fig. 5: LD Start_Up, L SP_cur, L SP_nom, A >=I */
  CHECK_EQ(cmp(1200, 1200, BB_OP_A_CMP, BB_CMP_GE, 1), 1);
  CHECK_EQ(cmp(1199, 1200, BB_OP_A_CMP, BB_CMP_GE, 1), 0);
  CHECK_EQ(cmp(1300, 1200, BB_OP_A_CMP, BB_CMP_GE, 0), 0);
  /* every code of both forms */
  for (unsigned c = 0; c < 6; c++) {
    int r = bb_cmp16(c, -3, 8);
    CHECK_EQ(cmp(-3, 8, BB_OP_A_CMP, c, 1), r);
    CHECK_EQ(cmp(-3, 8, BB_OP_A_CMP, c, 0), 0);
    CHECK_EQ(cmp(-3, 8, BB_OP_O_CMP, c, 0), r);
    CHECK_EQ(cmp(-3, 8, BB_OP_O_CMP, c, 1), 1);
  }
}

static void test_bad_codes(void) {
  static const unsigned ops[] = {0x96, 0x97, 0x9E, 0x9F, 0xA6, 0xA7};
  for (unsigned i = 0; i < sizeof ops / sizeof ops[0]; i++) {
    setup();
    L(1);
    L(1);
    RLO = 1;
    CHECK_EQ(ex(i_op(ops[i])), BB_CL_ILLEGAL);
    CHECK_EQ(RLO, 1);
    CHECK_EQ(S.rlo_written, 0);
    CHECK_EQ(S.flags, BB_FLAG_ILLEGAL);
  }
}

/* S7's status bits (awlsim's rules, worked by hand): which CC 1 CC 0 each kind of
 * instruction leaves, and the conditions read from them. */
static int cc_read(unsigned f, unsigned c, int negate, int rlo) {
  RLO = rlo;
  ex(BB_INSTR(BB_OP_STATUS + f, 0, c | (negate ? BB_STATUS_NEGATE : 0u)));
  return RLO;
}

#define CC (S.cc & 3u)                  /* CC 1 CC 0; OV and OS are S.cc's bits 2, 3 */
#define OV ((S.cc >> 2) & 1u)
#define OS ((S.cc >> 3) & 1u)

static void test_status_bits(void) {
  setup();
  CHECK_EQ(S.cc, 0u);
  S.accu2 = 5; S.accu1 = -5; ex(i_op(BB_OP_ADD));               /* 0 */
  CHECK_EQ(S.cc, 0u);
  CHECK_EQ(cc_read(0, BB_CC_ZERO, 0, 0), 1);
  CHECK_EQ(cc_read(0, BB_CC_NONZERO, 0, 1), 0);
  CHECK_EQ(cc_read(0, BB_CC_ZERO, 1, 1), 0);                    /* LDN ==0 */
  CHECK_EQ(cc_read(0, BB_CC_OV, 0, 1), 0);
  CHECK_EQ(cc_read(0, BB_CC_OS, 1, 0), 1);                      /* LDN OS */
  S.accu2 = 32767; S.accu1 = 1; ex(i_op(BB_OP_ADD));            /* wraps: negative */
  CHECK_EQ(CC, 1u);
  CHECK_EQ(OV, 1u);                                              /* 32768: overflow */
  CHECK_EQ(OS, 1u);
  CHECK_EQ(cc_read(0, BB_CC_NEG, 0, 0), 1);
  CHECK_EQ(cc_read(1, BB_CC_POS, 0, 1), 0);                     /* A >0 */
  CHECK_EQ(cc_read(2, BB_CC_POSZ, 0, 0), 0);                    /* O >=0 */
  CHECK_EQ(cc_read(3, BB_CC_NEGZ, 0, 1), 0);                    /* X <=0: 1 ^ 1 */
  CHECK_EQ(cc_read(1, BB_CC_OV, 0, 1), 1);                      /* A OV */
  CHECK_EQ(cc_read(3, BB_CC_OS, 0, 1), 0);                      /* X OS: 1 ^ 1 */
  S.accu2 = 2; S.accu1 = 3; ex(i_op(BB_OP_SUB));                /* -1: no overflow, */
  CHECK_EQ(CC, 1u);                                              /* OS stays */
  CHECK_EQ(OV, 0u);
  CHECK_EQ(OS, 1u);
  CHECK_EQ(cc_read(0, BB_CC_OV, 0, 1), 0);
  CHECK_EQ(cc_read(0, BB_CC_OS, 0, 0), 1);
  bb_scan_start(&S);
  S.accu2 = 256; S.accu1 = 256; ex(i_op(BB_OP_MUL));            /* 65536 -> 0, CC of */
  CHECK_EQ(S.accu1, 0);                                          /* the exact product */
  CHECK_EQ(CC, 2u);
  CHECK_EQ(OV, 1u);
  S.accu2 = -181; S.accu1 = 181; ex(i_op(BB_OP_MUL));           /* -32761: fits */
  CHECK_EQ(CC, 1u);
  CHECK_EQ(OV, 0u);
  CHECK_EQ(OS, 1u);
  bb_scan_start(&S);
  S.accu2 = 7; S.accu1 = 0; ex(i_op(BB_OP_DIV));                /* unordered */
  CHECK_EQ(S.cc, 3u | BB_SW_OV | BB_SW_OS);
  CHECK_EQ(cc_read(0, BB_CC_UO, 0, 0), 1);
  CHECK_EQ(cc_read(0, BB_CC_NONZERO, 0, 0), 1);
  CHECK_EQ(cc_read(0, BB_CC_POS, 0, 0), 0);
  bb_scan_start(&S);
  S.accu2 = -32768; S.accu1 = -1; ex(i_op(BB_OP_DIV));          /* exact 32768 */
  CHECK_EQ(CC, 2u);
  CHECK_EQ(OV, 1u);
  bb_scan_start(&S);
  S.accu2 = INT32_MIN; S.accu1 = -1; ex(i_op(BB_OP_DIV_D));
  CHECK_EQ(CC, 2u);
  CHECK_EQ(OV, 1u);
  S.accu2 = INT32_MAX; S.accu1 = 1; ex(i_op(BB_OP_ADD_D));       /* DINT overflow */
  CHECK_EQ(OV, 1u);
  S.accu2 = 40000; S.accu1 = 40000; ex(i_op(BB_OP_MUL_D));      /* 1.6e9 fits DINT */
  CHECK_EQ(OV, 0u);
  S.accu2 = -7; S.accu1 = 2; ex(i_op(BB_OP_MOD_D));             /* remainder -1 */
  CHECK_EQ(CC, 1u);
  CHECK_EQ(OV, 0u);
  S.accu2 = 7; S.accu1 = 0; ex(i_op(BB_OP_MOD));                /* MOD by 0 */
  CHECK_EQ(OV, 1u);
  S.accu2 = 3; S.accu1 = 9; ex(i_cmp(BB_OP_CMP, BB_CMP_EQ));    /* ACCU1 > ACCU2 */
  CHECK_EQ(CC, 1u);
  CHECK_EQ(OV, 0u);                                              /* compares: OV 0, */
  CHECK_EQ(OS, 1u);                                              /* OS kept */
  S.accu2 = 9; S.accu1 = 3; ex(i_cmp(BB_OP_CMP_D, BB_CMP_LT));
  CHECK_EQ(CC, 2u);
  ex(i_cmp(BB_OP_CMP, BB_CMP_NE));
  S.accu2 = 0x10000; S.accu1 = 0; ex(i_cmp(BB_OP_CMP, BB_CMP_EQ));   /* INT: equal */
  CHECK_EQ(CC, 0u);
  S.accu2 = 7; S.accu1 = 0; ex(i_op(BB_OP_DIV));                /* OV 1 again */
  S.accu2 = 0x0F00; S.accu1 = 0x00F0; ex(i_op(BB_OP_AW));       /* 0: CC 1 = 0 */
  CHECK_EQ(S.cc, BB_SW_OS);                                      /* word logic: OV 0 */
  S.accu2 = 0x10000; S.accu1 = 0x10000; ex(i_op(BB_OP_AW));     /* the word is 0 */
  CHECK_EQ(CC, 0u);
  S.accu1 = 0x10000; ex(i_op(BB_OP_AD));                         /* the dword is not */
  CHECK_EQ(CC, 2u);
  S.accu2 = 7; S.accu1 = 0; ex(i_op(BB_OP_DIV));                /* OV 1 again */
  S.accu1 = 0x8001; ex(BB_INSTR(BB_OP_SLW, 0, 1));              /* bit 15 out */
  CHECK_EQ(S.cc, 2u | BB_SW_OS);                                 /* a shift: OV 0 */
  S.accu2 = 7; S.accu1 = 0; ex(i_op(BB_OP_DIV));                /* OV 1 again */
  S.accu1 = 0x8001; ex(BB_INSTR(BB_OP_SLW, 0, 0));              /* count 0: unchanged */
  CHECK_EQ(S.cc, 3u | BB_SW_OV | BB_SW_OS);
  S.accu1 = 0x8001; ex(BB_INSTR(BB_OP_SRW, 0, 2));              /* bit 1 out */
  CHECK_EQ(CC, 0u);
  S.accu1 = 1; ex(BB_INSTR(BB_OP_RRD, 0, 1));                   /* bit 31 of the result */
  CHECK_EQ(CC, 2u);
  /* L and T leave them; a new scan clears them */
  L(5); ex(i_T(BB_AREA_MW, 0));
  CHECK_EQ(S.cc, 2u | BB_SW_OS);
  bb_scan_start(&S);
  CHECK_EQ(S.cc, 0u);
  /* bad status reads are illegal */
  CHECK_EQ(ex(BB_INSTR(BB_OP_STATUS, 0, 9)), BB_CL_ILLEGAL);    /* no condition 9 */
  CHECK_EQ(ex(BB_INSTR(BB_OP_STATUS, 0, 32)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(BB_INSTR(BB_OP_STATUS + 4u, 0, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(BB_INSTR(BB_OP_STATUS + 3u, 0, BB_CC_OS | BB_STATUS_NEGATE)), BB_CL_COMPARE);
}

void suite_compare(void) {
  RUN(test_status_bits);
  RUN(test_plain);
  RUN(test_and_or);
  RUN(test_bad_codes);
}
