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

int bb_proc_compare(const bb_state *s, unsigned op, int rlo) {
  const unsigned base = op & ~7u;
  const int dint = base == BB_OP_CMP_D || base == BB_OP_A_CMP_D || base == BB_OP_O_CMP_D;
  int r = dint ? bb_cmp32(op & 7u, s->accu2, s->accu1) : bb_cmp16(op & 7u, s->accu2, s->accu1);
  switch (base) {
    case BB_OP_A_CMP: case BB_OP_A_CMP_D: return (rlo != 0) && r;
    case BB_OP_O_CMP: case BB_OP_O_CMP_D: return (rlo != 0) || r;
    default:          return r;            /* BB_OP_CMP */
  }
}
