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

void suite_compare(void) {
  RUN(test_plain);
  RUN(test_and_or);
  RUN(test_bad_codes);
}
