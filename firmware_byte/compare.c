/*
 * compare.c — ==I <>I >I <I >=I <=I (spec §3): RLO := INT(ACCU2) op INT(ACCU1);
 * the A / O forms AND / OR that result into the RLO (paper Fig. 5, line 13).
 * The accumulators are unchanged; no bus access.
 */
#include "bb_internal.h"

int bb_cmp16(unsigned c, int32_t accu2, int32_t accu1) {
  int32_t a = bb_int16((uint32_t)accu2);
  int32_t b = bb_int16((uint32_t)accu1);
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
  int r = bb_cmp16(op & 7u, s->accu2, s->accu1);
  switch (op & ~7u) {
    case BB_OP_A_CMP: return (rlo != 0) && r;
    case BB_OP_O_CMP: return (rlo != 0) || r;
    default:          return r;            /* BB_OP_CMP */
  }
}
