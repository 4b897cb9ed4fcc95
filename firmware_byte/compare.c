/*
 * compare.c — ==I <>I >I <I >=I <=I (spec §3): RLO := INT(ACCU2) op INT(ACCU1), and
 * ==D ... <=D (docs/isa.md, DINT) over all 32 bits;
 * the A / O forms AND / OR that result into the RLO (paper Fig. 5, line 13).
 * The accumulators are unchanged; no bus access.
 */
#include "bb_internal.h"

int bb_cmp16(unsigned c, int32_t accu2, int32_t accu1) {
  return bb_cmp32(c, bb_int16((uint32_t)accu2), bb_int16((uint32_t)accu1));
}

/* ==D ... <=D: the codes over all 32 bits (the INT compares over INT(.)). */
int bb_cmp32(unsigned c, int32_t a, int32_t b) {
  switch (c) {
    case BB_CMP_EQ: return a == b;
    case BB_CMP_NE: return a != b;
    case BB_CMP_GT: return a > b;
    case BB_CMP_LT: return a < b;
    case BB_CMP_GE: return a >= b;
    case BB_CMP_LE: return a <= b;
    default: return 0;
  }
}

/* S7's CC 1 CC 0 of a value (awlsim): 0 -> 00, negative -> 01, positive -> 10. */
unsigned bb_cc_of(int64_t v) {
  return v == 0 ? 0u : v < 0 ? 1u : 2u;
}

/* LD/A/O/X [N] cond: the condition of CC 1 (A1) and CC 0 (A0) as awlsim reads it
 * (==0: 00; <>0: not 00; >0: 10; <0: 01; >=0: A0 = 0; <=0: A1 = 0; UO: 11) or OV, OS, negated
 * by index bit BB_STATUS_NEGATE, then loaded or combined as the opcode's f says. */
int bb_proc_status_read(const bb_state *s, unsigned op, unsigned index, int rlo) {
  const unsigned a1 = (s->cc >> 1) & 1u, a0 = s->cc & 1u;
  unsigned cond;
  switch (index & BB_STATUS_COND) {
    case BB_CC_ZERO:    cond = !a1 && !a0; break;
    case BB_CC_NONZERO: cond = a1 || a0; break;
    case BB_CC_POS:     cond = a1 && !a0; break;
    case BB_CC_NEG:     cond = a0 && !a1; break;
    case BB_CC_POSZ:    cond = !a0; break;
    case BB_CC_NEGZ:    cond = !a1; break;
    case BB_CC_UO:      cond = a1 && a0; break;
    case BB_CC_OV:      cond = (s->cc & BB_SW_OV) != 0u; break;
    default:            cond = (s->cc & BB_SW_OS) != 0u; break;     /* BB_CC_OS */
  }
  if (index & BB_STATUS_NEGATE) cond = !cond;
  switch (op - BB_OP_STATUS) {
    case 1u:  return (rlo != 0) && cond;
    case 2u:  return (rlo != 0) || cond;
    case 3u:  return (rlo != 0) != (cond != 0);
    default:  return (int)cond;
  }
}

static int is_dint_compare(unsigned op) {
  const unsigned base = op & ~7u;
  return base == BB_OP_CMP_D || base == BB_OP_A_CMP_D || base == BB_OP_O_CMP_D;
}

/* A compare's CC 1 CC 0 (awlsim): equal 00, ACCU1 > ACCU2 01, ACCU1 < ACCU2 10. */
unsigned bb_compare_cc(const bb_state *s, unsigned op) {
  const int32_t a1 = is_dint_compare(op) ? s->accu1 : bb_int16((uint32_t)s->accu1);
  const int32_t a2 = is_dint_compare(op) ? s->accu2 : bb_int16((uint32_t)s->accu2);
  return a1 == a2 ? 0u : a1 > a2 ? 1u : 2u;
}

int bb_proc_compare(const bb_state *s, unsigned op, int rlo) {
  const unsigned base = op & ~7u;
  const int dint = is_dint_compare(op);
  int r = dint ? bb_cmp32(op & 7u, s->accu2, s->accu1) : bb_cmp16(op & 7u, s->accu2, s->accu1);
  switch (base) {
    case BB_OP_A_CMP: case BB_OP_A_CMP_D: return (rlo != 0) && r;
    case BB_OP_O_CMP: case BB_OP_O_CMP_D: return (rlo != 0) || r;
    default:          return r;            /* BB_OP_CMP */
  }
}
