/*
 * bb_internal.h — the procedures interp.c dispatches to. Not part of the public API;
 * the unit tests use it to test the pure parts (no bus) directly.
 */
#ifndef BB_INTERNAL_H
#define BB_INTERNAL_H

#include <stdint.h>
#include "byteproc.h"

/* INT(v): the low 16 bits of v, signed (no implementation-defined conversion).
 * Pass an int32_t as (uint32_t)v: that conversion is defined (modulo 2^32). */
static inline int32_t bb_int16(uint32_t v) {
  uint32_t u = v & 0xFFFFu;
  return u >= 0x8000u ? (int32_t)u - 0x10000 : (int32_t)u;
}

/* A 32-bit pattern as int32_t, without the implementation-defined conversion. */
static inline int32_t bb_s32(uint32_t u) {
  return u >= 0x80000000u ? (int32_t)(u - 0x80000000u) - INT32_MAX - 1 : (int32_t)u;
}

/* Instruction fields. */
static inline unsigned bb_opcode(uint32_t instr) { return (unsigned)(instr >> 24); }
static inline unsigned bb_area(uint32_t instr)   { return (unsigned)(instr >> 12) & 0xFu; }
static inline unsigned bb_index(uint32_t instr)  { return (unsigned)instr & 0xFFFu; }
static inline int32_t  bb_imm24(uint32_t instr) {
  uint32_t u = instr & 0xFFFFFFu;
  return u >= 0x800000u ? (int32_t)u - 0x1000000 : (int32_t)u;
}

/* arith.c — ACCU1 := INT(ACCU2) op INT(ACCU1), wrapped; *div0 set for /I, MOD by 0. */
int32_t bb_arith16(unsigned op, int32_t accu2, int32_t accu1, int *div0);
int32_t bb_arith32(unsigned op, int32_t accu2, int32_t accu1, int *div0);
void    bb_proc_arith(bb_state *s, unsigned op);          /* BYTE_FLAGS write on div0 */

/* compare.c — c 0..5; the RLO after a plain / A / O compare. */
int32_t bb_logic(unsigned op, int32_t accu2, int32_t accu1);
int32_t bb_shift(unsigned op, int32_t accu1, unsigned count, unsigned *cc);
int bb_is_logic(unsigned op);
int bb_is_shift(unsigned op);
void bb_proc_logic(bb_state *s, uint32_t instr);
int bb_cmp16(unsigned c, int32_t accu2, int32_t accu1);
unsigned bb_cc_of(int64_t v);
/* bb_state.cc: CC 0 (bit 0), CC 1 (bit 1), and S7's OV and OS (awlsim's rules) */
#define BB_SW_OV 4u
#define BB_SW_OS 8u
unsigned bb_compare_cc(const bb_state *s, unsigned op);
int bb_proc_status_read(const bb_state *s, unsigned op, unsigned index, int rlo);
int bb_cmp32(unsigned c, int32_t accu2, int32_t accu1);
int bb_proc_compare(const bb_state *s, unsigned op, int rlo);

/* timers.c — the pure state update, and the procedure (update + TC_BIT write). */
void bb_timer_update(bb_timer *t, unsigned op, int en, int32_t preset, uint32_t now);
void bb_proc_timer(bb_state *s, unsigned op, unsigned n, int rlo, uint32_t now);

/* counters.c */
void bb_counter_update(bb_counter *c, unsigned op, int rlo, int32_t accu1);
void bb_proc_counter(bb_state *s, unsigned op, unsigned n, int rlo);

/* exchange.c */
int  bb_proc_read(bb_state *s, unsigned k);              /* READ FBY k: the new F_B */
void bb_proc_write(bb_state *s, unsigned k, int rlo);    /* WRITE FBI k */

/* interp.c: sets a sticky flag and mirrors the flag word to BYTE_FLAGS (one write). */
void bb_raise_flag(bb_state *s, uint32_t flag);

#endif /* BB_INTERNAL_H */
