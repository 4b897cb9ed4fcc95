/* test_arith.c — L, T, +I -I *I /I MOD, INT(), the constant pool. Expected values
 * worked out by hand from spec §3. */
#include "tt.h"

static void test_load_shifts_accus(void) {
  setup();
  L(1);
  CHECK_EQ(S.accu1, 1);
  CHECK_EQ(S.accu2, 0);
  L(2);
  CHECK_EQ(S.accu1, 2);
  CHECK_EQ(S.accu2, 1);
  L(3);
  CHECK_EQ(S.accu1, 3);
  CHECK_EQ(S.accu2, 2);
  CHECK_EQ(RLO, 0);          /* L leaves the RLO */
  RLO = 1;
  L(4);
  CHECK_EQ(RLO, 1);
  CHECK_EQ(S.rlo_written, 0);
}

static void test_imm24(void) {
  setup();
  ex(0x80FFFFFFu);           /* 16#FFFF assembled as -1: imm24 0xFFFFFF */
  CHECK_EQ(S.accu1, -1);
  ex(0x807FFFFFu);
  CHECK_EQ(S.accu1, 8388607);
  ex(0x80800000u);
  CHECK_EQ(S.accu1, -8388608);
  ex(0x8000FFFFu);           /* the pattern 65535 (32-bit), whose INT is -1 */
  CHECK_EQ(S.accu1, 65535);
  ex(i_T(BB_AREA_MW, 9));
  CHECK_EQ(bb_mw(&S, 9), -1);
  ex(i_imm(-7));
  CHECK_EQ(S.accu1, -7);
  ex(i_imm(0));
  CHECK_EQ(S.accu1, 0);
}

static void test_pool(void) {
  static const uint32_t pool[] = {0x7FFFFFFFu, 0x80000000u, 0xDEADBEEFu, 7200000u};
  setup();
  bb_load_pool(&S, pool, 4);
  CHECK_EQ(ex(BB_INSTR_IMM(BB_OP_L_POOL, 0)), BB_CL_LOAD);
  CHECK_EQ(S.accu1, 2147483647);
  ex(BB_INSTR_IMM(BB_OP_L_POOL, 1));
  CHECK_EQ(S.accu1, INT32_MIN);
  CHECK_EQ(S.accu2, 2147483647);
  ex(BB_INSTR_IMM(BB_OP_L_POOL, 2));
  CHECK_EQ(S.accu1, -559038737);   /* 0xDEADBEEF as int32 */
  ex(BB_INSTR_IMM(BB_OP_L_POOL, 3));
  CHECK_EQ(S.accu1, 7200000);      /* T#2h: does not fit imm24 */
  CHECK_EQ(S.flags, 0);
  /* an index past the pool: illegal, the accumulators stay */
  CHECK_EQ(ex(BB_INSTR_IMM(BB_OP_L_POOL, 4)), BB_CL_ILLEGAL);
  CHECK_EQ(S.accu1, 7200000);
  CHECK_EQ(S.accu2, -559038737);
  CHECK_EQ(S.flags, BB_FLAG_ILLEGAL);
  CHECK_EQ(FH.byte_flags, BB_FLAG_ILLEGAL);
  /* a pool larger than the memory is cut, not overrun */
  static uint32_t big[BB_POOL_WORDS + 5];
  for (unsigned i = 0; i < BB_POOL_WORDS + 5; i++) big[i] = i;
  bb_load_pool(&S, big, BB_POOL_WORDS + 5);
  CHECK_EQ(S.pool_len, BB_POOL_WORDS);
  bb_load_pool(&S, NULL, 3);
  CHECK_EQ(S.pool_len, 0);
}

static void test_words(void) {
  setup();
  FH.iw[3] = 0xFFFFFFFBu;          /* -5, sign-extended by the port */
  FH.iw[15] = 0x00001234u;
  ex(i_L(BB_AREA_IW, 3));
  CHECK_EQ(S.accu1, -5);
  ex(i_L(BB_AREA_IW, 15));
  CHECK_EQ(S.accu1, 0x1234);
  CHECK_EQ(S.accu2, -5);
  FH.iw[0] = 0x0000FFFFu;          /* a port that does not sign-extend: still -1 */
  ex(i_L(BB_AREA_IW, 0));
  CHECK_EQ(S.accu1, -1);

  /* T QW: low 16 bits onto the bus; L QW reads the port back (no firmware copy) */
  L(0x12345);
  ex(i_T(BB_AREA_QW, 2));
  CHECK_EQ(FH.qw[2], 0x2345);
  FH.qw[2] = 0x8001;               /* the RTL is the truth */
  ex(i_L(BB_AREA_QW, 2));
  CHECK_EQ(S.accu1, -32767);
  L(-1);
  ex(i_T(BB_AREA_QW, 15));
  CHECK_EQ(FH.qw[15], 0xFFFF);
  ex(i_L(BB_AREA_QW, 15));
  CHECK_EQ(S.accu1, -1);

  /* MW: 16-bit, sign-extended on load, MW0 and MW1 distinct, all 256 */
  L(70000);                        /* INT(70000) = 70000 - 65536 = 4464 */
  ex(i_T(BB_AREA_MW, 0));
  L(-2);
  ex(i_T(BB_AREA_MW, 1));
  L(32767);
  ex(i_T(BB_AREA_MW, 255));
  CHECK_EQ(bb_mw(&S, 0), 4464);
  CHECK_EQ(bb_mw(&S, 1), -2);
  CHECK_EQ(bb_mw(&S, 255), 32767);
  CHECK_EQ(bb_mw(&S, 256), 0);     /* out of range accessor: 0, no crash */
  ex(i_L(BB_AREA_MW, 1));
  CHECK_EQ(S.accu1, -2);
  CHECK_EQ(S.accu2, 32767);
  /* T leaves the accumulators */
  ex(i_T(BB_AREA_MW, 2));
  CHECK_EQ(S.accu1, -2);
  CHECK_EQ(S.accu2, 32767);

  /* bad operands are illegal and change nothing */
  CHECK_EQ(ex(i_L(BB_AREA_MW, 256)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(i_L(BB_AREA_IW, 16)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(i_T(BB_AREA_IW, 0)), BB_CL_ILLEGAL);   /* T IW: not a target */
  CHECK_EQ(ex(i_T(BB_AREA_T, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(ex(i_L(0, 0)), BB_CL_ILLEGAL);
  CHECK_EQ(S.accu1, -2);
  CHECK_EQ(S.accu2, 32767);
  CHECK(S.flags & BB_FLAG_ILLEGAL);
}

static void test_add_sub(void) {
  setup();
  CHECK_EQ(arith(10, BB_OP_SUB, 3), 7);
  CHECK_EQ(S.accu2, 10);                       /* ACCU2 unchanged */
  CHECK_EQ(arith(2, BB_OP_ADD, 3), 5);
  CHECK_EQ(arith(32767, BB_OP_ADD, 1), -32768);  /* wrap */
  CHECK_EQ(arith(-32768, BB_OP_SUB, 1), 32767);
  CHECK_EQ(arith(-32768, BB_OP_ADD, -32768), 0);
  CHECK_EQ(arith(3, BB_OP_SUB, 10), -7);
  /* INT() of 32-bit accumulators: INT(70000) = 4464, INT(-70000) = -4464 */
  CHECK_EQ(arith(70000, BB_OP_ADD, 1), 4465);
  CHECK_EQ(S.accu2, 70000);                    /* ACCU2 keeps its 32 bits */
  CHECK_EQ(arith(1, BB_OP_SUB, -70000), 4465); /* 1 - (-4464) */
  CHECK_EQ(arith(65535, BB_OP_ADD, 0), -1);
  CHECK_EQ(S.flags, 0);
}

static void test_mul(void) {
  setup();
  CHECK_EQ(arith(6, BB_OP_MUL, 7), 42);
  CHECK_EQ(arith(-6, BB_OP_MUL, 7), -42);
  CHECK_EQ(arith(300, BB_OP_MUL, 300), 24464);    /* 90000 - 65536 */
  CHECK_EQ(arith(200, BB_OP_MUL, -200), 25536);   /* -40000 + 65536 */
  CHECK_EQ(arith(-32768, BB_OP_MUL, -1), -32768); /* 32768 wraps */
  CHECK_EQ(arith(-32768, BB_OP_MUL, -32768), 0);  /* 2^30 wraps to 0 */
  CHECK_EQ(arith(181, BB_OP_MUL, 181), 32761);
  CHECK_EQ(arith(256, BB_OP_MUL, 128), -32768);
}

static void test_div_mod(void) {
  setup();
  CHECK_EQ(arith(7, BB_OP_DIV, 2), 3);
  CHECK_EQ(arith(-7, BB_OP_DIV, 2), -3);          /* toward zero */
  CHECK_EQ(arith(7, BB_OP_DIV, -2), -3);
  CHECK_EQ(arith(-7, BB_OP_DIV, -2), 3);
  CHECK_EQ(arith(-32768, BB_OP_DIV, -1), -32768); /* 32768 wraps */
  CHECK_EQ(arith(1, BB_OP_DIV, 2), 0);
  CHECK_EQ(arith(7, BB_OP_MOD, 2), 1);
  CHECK_EQ(arith(-7, BB_OP_MOD, 2), -1);          /* sign of the dividend */
  CHECK_EQ(arith(7, BB_OP_MOD, -2), 1);
  CHECK_EQ(arith(-7, BB_OP_MOD, -2), -1);
  CHECK_EQ(arith(-32768, BB_OP_MOD, -1), 0);
  CHECK_EQ(arith(6, BB_OP_MOD, 3), 0);
  CHECK_EQ(S.flags, 0);
  CHECK_EQ(FH.byte_flags, 0);
}

static void test_div_by_zero(void) {
  setup();
  fh_clear_log();
  CHECK_EQ(arith(7, BB_OP_DIV, 0), 0);
  CHECK_EQ(S.accu2, 7);
  CHECK_EQ(S.flags, BB_FLAG_ARITH);
  CHECK_EQ(FH.byte_flags, BB_FLAG_ARITH);        /* mirrored on the bus */
  CHECK_EQ(FH.nlog, 1);
  CHECK_EQ(FH.log[0].addr, BB_BUS_BYTE_FLAGS);
  CHECK_EQ(FH.log[0].write, 1);
  /* sticky: a good division later does not clear it */
  CHECK_EQ(arith(8, BB_OP_DIV, 2), 4);
  CHECK_EQ(S.flags, BB_FLAG_ARITH);
  setup();
  CHECK_EQ(arith(-7, BB_OP_MOD, 0), 0);
  CHECK_EQ(S.flags, BB_FLAG_ARITH);
  CHECK_EQ(FH.byte_flags, BB_FLAG_ARITH);
  /* INT(ACCU1) = 0 although ACCU1 is not: 65536 */
  setup();
  CHECK_EQ(arith(5, BB_OP_DIV, 65536), 0);
  CHECK_EQ(S.flags, BB_FLAG_ARITH);
  /* the pure function */
  int d0 = 0;
  CHECK_EQ(bb_arith16(BB_OP_MOD, 9, 0, &d0), 0);
  CHECK_EQ(d0, 1);
  CHECK_EQ(bb_arith16(BB_OP_MOD, 9, 4, &d0), 1);
  CHECK_EQ(d0, 0);
}

/* spec §3 worked examples, byte part */
static void test_worked_examples(void) {
  setup();
  L(10); L(3); ex(i_op(BB_OP_SUB)); ex(i_T(BB_AREA_MW, 0));
  L(5); L(3); ex(i_cmp(BB_OP_CMP, BB_CMP_GT));
  CHECK_EQ(bb_mw(&S, 0), 7);
  CHECK_EQ(RLO, 1);

  setup();
  ex(0x80FFFFFFu); ex(i_T(BB_AREA_MW, 1));             /* L 16#FFFF, T MW1 */
  L(32767); L(1); ex(i_op(BB_OP_ADD)); ex(i_T(BB_AREA_MW, 2));
  L(-7); L(2); ex(i_op(BB_OP_DIV)); ex(i_T(BB_AREA_MW, 3));
  L(-7); L(2); ex(i_op(BB_OP_MOD)); ex(i_T(BB_AREA_MW, 4));
  CHECK_EQ(bb_mw(&S, 1), -1);
  CHECK_EQ(bb_mw(&S, 2), -32768);
  CHECK_EQ(bb_mw(&S, 3), -3);
  CHECK_EQ(bb_mw(&S, 4), -1);
  CHECK_EQ(S.flags, 0);
}

/* ACCU2 := a; ACCU1 := b (any 32-bit values: the pool's job, set directly); then op. */
static int32_t arith32(int32_t a, unsigned op, int32_t b) {
  S.accu2 = a;
  S.accu1 = b;
  ex(i_op(op));
  return S.accu1;
}

/* DINT (docs/isa.md): +D -D *D /D MODD over 32 bits, wrapped; the expected values
 * are S7's (awlsim's insn_pl_d ... insn_mod), worked by hand. */
static void test_dint_arith(void) {
  setup();
  CHECK_EQ(arith(100000, BB_OP_ADD_D, 70000), 170000);        /* no 16-bit wrap */
  CHECK_EQ(arith32(INT32_MAX, BB_OP_ADD_D, 1), INT32_MIN);      /* 32-bit wrap */
  CHECK_EQ(arith32(INT32_MIN, BB_OP_SUB_D, 1), INT32_MAX);
  CHECK_EQ(arith(3, BB_OP_SUB_D, 100000), -99997);
  CHECK_EQ(arith(1000, BB_OP_MUL_D, -3000), -3000000);
  CHECK_EQ(arith(65536, BB_OP_MUL_D, 65536), 0);              /* 2^32 wraps to 0 */
  CHECK_EQ(arith(-100001, BB_OP_DIV_D, 7), -14285);           /* toward zero */
  CHECK_EQ(arith(100001, BB_OP_DIV_D, -7), -14285);
  CHECK_EQ(arith32(INT32_MIN, BB_OP_DIV_D, -1), INT32_MIN);     /* 2^31 wraps */
  CHECK_EQ(arith(-100001, BB_OP_MOD_D, 7), -6);               /* sign of the dividend */
  CHECK_EQ(arith(100001, BB_OP_MOD_D, -7), 6);
  CHECK_EQ(arith32(INT32_MIN, BB_OP_MOD_D, -1), 0);
  CHECK_EQ(S.flags, 0);
  CHECK_EQ(arith(5, BB_OP_DIV_D, 65536), 0);                  /* not INT(ACCU1) = 0 */
  CHECK_EQ(S.flags, 0);
  CHECK_EQ(arith(5, BB_OP_MOD_D, 0), 0);
  CHECK_EQ(S.flags, BB_FLAG_ARITH);
  /* DINT compares read all 32 bits: 65536 == 0 as INT, not as DINT */
  setup();
  L(65536); L(0);
  ex(i_cmp(BB_OP_CMP, BB_CMP_EQ));
  CHECK_EQ(RLO, 1);
  ex(i_cmp(BB_OP_CMP_D, BB_CMP_EQ));
  CHECK_EQ(RLO, 0);
  ex(i_cmp(BB_OP_CMP_D, BB_CMP_GT));
  CHECK_EQ(RLO, 1);
  L(-70000); L(-69999);
  ex(i_cmp(BB_OP_CMP_D, BB_CMP_LT));
  CHECK_EQ(RLO, 1);
  ex(i_cmp(BB_OP_A_CMP_D, BB_CMP_GE));                        /* 1 AND 0 */
  CHECK_EQ(RLO, 0);
  ex(i_cmp(BB_OP_O_CMP_D, BB_CMP_LE));                        /* 0 OR 1 */
  CHECK_EQ(RLO, 1);
}

/* MD n: MW n the high half, MW n+2 the low half; MW n+1 untouched */
static void test_double_words(void) {
  setup();
  L(7); ex(i_T(BB_AREA_MW, 11));
  L(-100000);                      /* 0xFFFE7960 */
  ex(i_T(BB_AREA_MD, 10));
  CHECK_EQ(bb_mw(&S, 10), -2);     /* 0xFFFE */
  CHECK_EQ(bb_mw(&S, 12), 0x7960);
  CHECK_EQ(bb_mw(&S, 11), 7);
  L(0);
  ex(i_L(BB_AREA_MD, 10));
  CHECK_EQ(S.accu1, -100000);
  L(-1); ex(i_T(BB_AREA_MW, 20)); L(-32768); ex(i_T(BB_AREA_MW, 22));
  ex(i_L(BB_AREA_MD, 20));         /* 0xFFFF8000: the low half not sign-extended */
  CHECK_EQ(S.accu1, -32768);
  L(0); ex(i_T(BB_AREA_MW, 20));
  ex(i_L(BB_AREA_MD, 20));         /* 0x00008000 */
  CHECK_EQ(S.accu1, 32768);
  CHECK_EQ(ex(i_L(BB_AREA_MD, 253)), BB_CL_LOAD);
  CHECK_EQ(ex(i_L(BB_AREA_MD, 254)), BB_CL_ILLEGAL);           /* MW 256 is not there */
  CHECK_EQ(ex(i_T(BB_AREA_MD, 254)), BB_CL_ILLEGAL);
}

/* Word logic and shifts (docs/isa.md): S7's results as awlsim computes them
 * (insn_uw.py ... insn_rrd.py), worked by hand. */
static int32_t shift(int32_t a, unsigned op, unsigned n) {
  S.accu1 = a;
  S.accu2 = 77;
  ex(BB_INSTR(op, 0, n));
  CHECK_EQ(S.accu2, 77);                                     /* ACCU2 unchanged */
  return S.accu1;
}

static void test_word_logic(void) {
  setup();
  CHECK_EQ(arith32(0x00F0, BB_OP_AW, 0x3C3C), 0x0030);
  CHECK_EQ(arith32(0x00F0, BB_OP_OW, 0x3C3C), 0x3CFC);
  CHECK_EQ(arith32(0x00F0, BB_OP_XOW, 0x3C3C), 0x3CCC);
  CHECK_EQ(arith32(-1, BB_OP_AW, 0x12348000), -32768);        /* INT, sign-extended */
  CHECK_EQ(arith32(0x0F0F0000, BB_OP_AD, 0x00FF00FF), 0x000F0000);
  CHECK_EQ(arith32(0x0F0F0000, BB_OP_OD, 0x00FF00FF), 0x0FFF00FF);
  CHECK_EQ(arith32(INT32_MIN, BB_OP_XOD, -1), INT32_MAX);
  CHECK_EQ(S.flags, 0);
}

static void test_shifts(void) {
  setup();
  CHECK_EQ(shift(0x1234, BB_OP_SLW, 4), 0x2340);
  CHECK_EQ(shift(0x1234, BB_OP_SLW, 3), -28256);             /* 0x91A0 */
  CHECK_EQ(shift(0x1234, BB_OP_SLW, 16), 0);
  CHECK_EQ(shift(0x1234, BB_OP_SLW, 255), 0);
  CHECK_EQ(shift(0x71234, BB_OP_SLW, 0), 0x71234);           /* count 0: unchanged */
  CHECK_EQ(shift(-32768, BB_OP_SRW, 1), 0x4000);              /* zeros in */
  CHECK_EQ(shift(-32768, BB_OP_SSI, 1), -16384);              /* the sign in */
  CHECK_EQ(shift(-32768, BB_OP_SSI, 16), -1);
  CHECK_EQ(shift(-32768, BB_OP_SSI, 200), -1);
  CHECK_EQ(shift(0x4000, BB_OP_SSI, 20), 0);
  CHECK_EQ(shift(0x40000001, BB_OP_SLD, 1), INT32_MIN + 2);
  CHECK_EQ(shift(-1, BB_OP_SLD, 32), 0);
  CHECK_EQ(shift(INT32_MIN, BB_OP_SRD, 31), 1);
  CHECK_EQ(shift(INT32_MIN, BB_OP_SSD, 31), -1);
  CHECK_EQ(shift(INT32_MIN, BB_OP_SSD, 33), -1);
  CHECK_EQ(shift(0x40000000, BB_OP_SSD, 40), 0);
  CHECK_EQ(shift(INT32_MIN + 1, BB_OP_RLD, 1), 3);
  CHECK_EQ(shift(3, BB_OP_RRD, 1), INT32_MIN + 1);
  CHECK_EQ(shift(0x12345678, BB_OP_RLD, 32), 0x12345678);
  CHECK_EQ(shift(0x12345678, BB_OP_RRD, 8), 0x78123456);
  /* the count from ACCU2's low byte */
  S.accu2 = 0x104;                                           /* low byte 4 */
  S.accu1 = 0x1234;
  ex(BB_INSTR(BB_OP_SLW, 0, 0) | BB_COUNT_FROM_ACCU2);
  CHECK_EQ(S.accu1, 0x2340);
  CHECK_EQ(S.flags, 0);
}

static void test_int16(void) {
  CHECK_EQ(bb_int16(0x7FFFu), 32767);
  CHECK_EQ(bb_int16(0x8000u), -32768);
  CHECK_EQ(bb_int16(0xFFFFFFFFu), -1);
  CHECK_EQ(bb_int16(0x12345678u), 0x5678);
  CHECK_EQ(bb_int16(0x0001FFFFu), -1);
  CHECK_EQ(bb_s32(0xFFFFFFFFu), -1);
  CHECK_EQ(bb_s32(0x80000000u), INT32_MIN);
  CHECK_EQ(bb_imm24(0x00FFFFFFu), -1);
  CHECK_EQ(bb_imm24(0xFF7FFFFFu), 8388607);
}

void suite_arith(void) {
  RUN(test_load_shifts_accus);
  RUN(test_imm24);
  RUN(test_pool);
  RUN(test_words);
  RUN(test_add_sub);
  RUN(test_mul);
  RUN(test_div_mod);
  RUN(test_div_by_zero);
  RUN(test_worked_examples);
  RUN(test_dint_arith);
  RUN(test_double_words);
  RUN(test_word_logic);
  RUN(test_shifts);
  RUN(test_int16);
}
