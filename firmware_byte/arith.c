/*
 * arith.c — +I -I *I /I MOD (spec §3), and +D -D *D /D MODD (docs/isa.md, DINT) below.
 * +I ...: ACCU1 := INT(ACCU2) op INT(ACCU1), wrapped to
 * 16 bits and sign-extended; ACCU2 unchanged. /I truncates toward zero and MOD takes
 * the sign of the dividend (both are C99's / and %); a divisor of 0 gives 0 and sets
 * the sticky arithmetic-error flag, which is also written to BYTE_FLAGS.
 */
#include <stdint.h>
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

/* +D -D *D /D MODD: ACCU1 := ACCU2 op ACCU1 over all 32 bits, wrapped (S7's DINT
 * arithmetic; -2^31 / -1 wraps to -2^31 as in awlsim). The operations run on uint32_t,
 * where wrapping is defined; / and % on magnitudes, the signs put back: truncation
 * toward zero, the remainder with the dividend's sign. A divisor of 0 gives 0 and sets
 * the sticky flag, as /I. */
int32_t bb_arith32(unsigned op, int32_t accu2, int32_t accu1, int *div0) {
  const uint32_t a = (uint32_t)accu2, b = (uint32_t)accu1;
  const uint32_t amag = accu2 < 0 ? 0u - a : a, bmag = accu1 < 0 ? 0u - b : b;
  uint32_t r = 0;
  *div0 = 0;
  switch (op) {
    case BB_OP_ADD_D: r = a + b; break;
    case BB_OP_SUB_D: r = a - b; break;
    case BB_OP_MUL_D: r = a * b; break;
    case BB_OP_DIV_D:
      if (b == 0u) { *div0 = 1; break; }
      r = amag / bmag;
      if ((accu2 < 0) != (accu1 < 0)) r = 0u - r;
      break;
    case BB_OP_MOD_D:
      if (b == 0u) { *div0 = 1; break; }
      r = amag % bmag;
      if (accu2 < 0) r = 0u - r;
      break;
    default: break;
  }
  return bb_s32(r);
}

static int is_dint(unsigned op) {
  return op == BB_OP_ADD_D || op == BB_OP_SUB_D || op == BB_OP_MUL_D
      || op == BB_OP_DIV_D || op == BB_OP_MOD_D;
}

/* CC 1 CC 0 after an arithmetic instruction (awlsim): of the wrapped result for + and
 * -, of the exact product / quotient / remainder for * / MOD (S7 keeps CC of the exact
 * value and flags the overflow in OV), 11 (unordered) after a division by 0. */
static unsigned arith_cc(unsigned op, int32_t accu2, int32_t accu1, int32_t result) {
  const int dint = is_dint(op);
  const int64_t a = dint ? accu2 : bb_int16((uint32_t)accu2);
  const int64_t b = dint ? accu1 : bb_int16((uint32_t)accu1);
  switch (op) {
    case BB_OP_MUL: case BB_OP_MUL_D:
      return bb_cc_of(a * b);
    case BB_OP_DIV: case BB_OP_DIV_D:
      return b == 0 ? 3u : bb_cc_of(a / b);
    case BB_OP_MOD: case BB_OP_MOD_D:
      return b == 0 ? 3u : bb_cc_of(a % b);
    default:
      return bb_cc_of(result);
  }
}

/* OV after an arithmetic instruction (awlsim): the exact sum, difference, product or
 * quotient outside INT (DINT for the D forms), or a division by 0; MOD only by 0. */
static int arith_ov(unsigned op, int32_t accu2, int32_t accu1) {
  const int dint = is_dint(op);
  const int64_t a = dint ? accu2 : bb_int16((uint32_t)accu2);
  const int64_t b = dint ? accu1 : bb_int16((uint32_t)accu1);
  const int64_t lo = dint ? INT32_MIN : -32768, hi = dint ? INT32_MAX : 32767;
  int64_t v;
  switch (op) {
    case BB_OP_ADD: case BB_OP_ADD_D: v = a + b; break;
    case BB_OP_SUB: case BB_OP_SUB_D: v = a - b; break;
    case BB_OP_MUL: case BB_OP_MUL_D: v = a * b; break;
    case BB_OP_DIV: case BB_OP_DIV_D: if (b == 0) return 1; v = a / b; break;
    default:                          return b == 0;     /* MOD, MODD */
  }
  return v < lo || v > hi;
}

void bb_proc_arith(bb_state *s, unsigned op) {
  int div0;
  const int32_t a2 = s->accu2, a1 = s->accu1;
  const unsigned ov = arith_ov(op, a2, a1) ? BB_SW_OV | BB_SW_OS : 0u;
  s->accu1 = is_dint(op) ? bb_arith32(op, s->accu2, s->accu1, &div0)
                         : bb_arith16(op, s->accu2, s->accu1, &div0);
  s->cc = arith_cc(op, a2, a1, s->accu1) | ov | (s->cc & BB_SW_OS);
  if (div0) bb_raise_flag(s, BB_FLAG_ARITH);
}
