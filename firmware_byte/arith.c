/*
 * arith.c — +I -I *I /I MOD (spec §3): ACCU1 := INT(ACCU2) op INT(ACCU1), wrapped to
 * 16 bits and sign-extended; ACCU2 unchanged. /I truncates toward zero and MOD takes
 * the sign of the dividend (both are C99's / and %); a divisor of 0 gives 0 and sets
 * the sticky arithmetic-error flag, which is also written to BYTE_FLAGS.
 */
#include "bb_internal.h"

int32_t bb_arith16(unsigned op, int32_t accu2, int32_t accu1, int *div0) {
  /* Both operands are in -32768..32767, so every intermediate fits int32_t
   * (|a*b| <= 2^30, -32768 / -1 = 32768) and no C overflow can happen. */
  int32_t a = bb_int16((uint32_t)accu2);
  int32_t b = bb_int16((uint32_t)accu1);
  int32_t r = 0;
  *div0 = 0;
  switch (op) {
    case BB_OP_ADD: r = a + b; break;
    case BB_OP_SUB: r = a - b; break;
    case BB_OP_MUL: r = a * b; break;
    case BB_OP_DIV:
      if (b == 0) *div0 = 1; else r = a / b;
      break;
    case BB_OP_MOD:
      if (b == 0) *div0 = 1; else r = a % b;
      break;
    default: break;
  }
  return bb_int16((uint32_t)r);
}

void bb_proc_arith(bb_state *s, unsigned op) {
  int div0;
  s->accu1 = bb_arith16(op, s->accu2, s->accu1, &div0);
  if (div0) bb_raise_flag(s, BB_FLAG_ARITH);
}
