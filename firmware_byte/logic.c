/*
 * logic.c — word logic and shifts (docs/isa.md, "Word logic and shifts"; S7's UW OW
 * XOW UD OD XOD, SLW SRW SSI SLD SRD SSD RLD RRD, with awlsim's results). ACCU2 is
 * unchanged. The 16-bit forms work on INT(ACCU1) (and INT(ACCU2)) and leave ACCU1
 * sign-extended from 16 bits, as the INT arithmetic does; the 32-bit forms use all of
 * ACCU1. A shift count is 0..255 (S7's range), a count past the width acting as the
 * width: a count of 0 leaves ACCU1 as it is, in every form. No bus access.
 */
#include "bb_internal.h"

/* AW OW XOW AD OD XOD: ACCU1 := ACCU1 op ACCU2. */
int32_t bb_logic(unsigned op, int32_t accu2, int32_t accu1) {
  const uint32_t a = (uint32_t)accu1, b = (uint32_t)accu2;
  switch (op) {
    case BB_OP_AW:  return bb_int16(a & b);
    case BB_OP_OW:  return bb_int16(a | b);
    case BB_OP_XOW: return bb_int16(a ^ b);
    case BB_OP_AD:  return bb_s32(a & b);
    case BB_OP_OD:  return bb_s32(a | b);
    case BB_OP_XOD: return bb_s32(a ^ b);
    default:        return accu1;
  }
}

/* The bit a shift moves out last (awlsim's CC 1 after it; CC 0 is 0); a rotation's
 * CC 1 is the bit that came round (RLD: bit 0 of the result, RRD: bit 31). */
static unsigned shifted_out(unsigned op, uint32_t w, uint32_t d, unsigned c16,
                            unsigned c32, uint32_t result) {
  switch (op) {
    case BB_OP_SLW: return (w >> (16u - c16)) & 1u;
    case BB_OP_SRW: case BB_OP_SSI: return (w >> (c16 - 1u)) & 1u;
    case BB_OP_SLD: return c32 == 32u ? d & 1u : (d >> (32u - c32)) & 1u;
    case BB_OP_SRD: case BB_OP_SSD: return (d >> (c32 - 1u)) & 1u;
    case BB_OP_RLD: return result & 1u;
    default:        return result >> 31;              /* BB_OP_RRD */
  }
}

static int32_t shift_value(unsigned op, int32_t accu1, unsigned c16, unsigned c32);

/* SLW ... RRD: ACCU1 shifted or rotated by count (0..255); *cc the CC 1 CC 0 after it
 * (a count of 0 changes neither). */
int32_t bb_shift(unsigned op, int32_t accu1, unsigned count, unsigned *cc) {
  const uint32_t w = (uint32_t)accu1 & 0xFFFFu, d = (uint32_t)accu1;
  const unsigned c16 = count > 16u ? 16u : count, c32 = count > 32u ? 32u : count;
  int32_t r;
  if (count == 0u) return accu1;
  r = shift_value(op, accu1, c16, c32);
  *cc = shifted_out(op, w, d, c16, c32, (uint32_t)r) << 1;
  return r;
}

static int32_t shift_value(unsigned op, int32_t accu1, unsigned c16, unsigned c32) {
  const uint32_t w = (uint32_t)accu1 & 0xFFFFu, d = (uint32_t)accu1;
  switch (op) {
    case BB_OP_SLW: return c16 == 16u ? 0 : bb_int16(w << c16);
    case BB_OP_SRW: return c16 == 16u ? 0 : bb_int16(w >> c16);
    case BB_OP_SSI: {   /* the sign bit copied in: c16 - 1 <= 15 keeps the shift defined */
      const uint32_t fill = (w & 0x8000u) ? 0xFFFF0000u : 0u;
      return bb_int16((w | fill) >> (c16 - 1u) >> 1);
    }
    case BB_OP_SLD: return c32 == 32u ? 0 : bb_s32(d << c32);
    case BB_OP_SRD: return c32 == 32u ? 0 : bb_s32(d >> c32);
    case BB_OP_SSD: {
      const uint32_t fill = (d & 0x80000000u) ? ~(0xFFFFFFFFu >> (c32 - 1u) >> 1) : 0u;
      return bb_s32((d >> (c32 - 1u) >> 1) | fill);
    }
    case BB_OP_RLD: return c32 == 32u ? accu1 : bb_s32(d << c32 | d >> (32u - c32));
    case BB_OP_RRD: return c32 == 32u ? accu1 : bb_s32(d >> c32 | d << (32u - c32));
    default:        return accu1;
  }
}

static int is_logic(unsigned op) {
  return op == BB_OP_AW || op == BB_OP_OW || op == BB_OP_XOW
      || op == BB_OP_AD || op == BB_OP_OD || op == BB_OP_XOD;
}

int bb_is_shift(unsigned op) {
  return op >= BB_OP_SLW && op <= BB_OP_RRD;
}

int bb_is_logic(unsigned op) { return is_logic(op); }

void bb_proc_logic(bb_state *s, uint32_t instr) {
  const unsigned op = bb_opcode(instr);
  if (is_logic(op)) {
    const int wide = op == BB_OP_AD || op == BB_OP_OD || op == BB_OP_XOD;
    s->accu1 = bb_logic(op, s->accu2, s->accu1);
    /* CC 1: the result is not 0 (of the word for the 16-bit forms); CC 0 = 0 */
    s->cc = (((wide ? (uint32_t)s->accu1 : (uint32_t)s->accu1 & 0xFFFFu) != 0u) ? 2u : 0u)
            | (s->cc & BB_SW_OS);                           /* OV 0, OS kept */
  } else {
    const unsigned count = (instr & BB_COUNT_FROM_ACCU2) ? (uint32_t)s->accu2 & 0xFFu
                                                         : bb_index(instr) & 0xFFu;
    unsigned cc = s->cc;
    s->accu1 = bb_shift(op, s->accu1, count, &cc);
    if (count != 0u) s->cc = cc | (s->cc & BB_SW_OS);       /* OV 0, OS kept */
  }
}
