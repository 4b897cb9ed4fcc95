/*
 * timers.c — SD SS SP SF and R T n (spec §3 "Timers", IEC function-block style).
 *
 * now  = TIME_MS in the instruction's first clock (interp.c reads it and passes it
 *        in: DISPATCH_MS, the port's snapshot, in serial mode; TIME_MS as the first
 *        access in parallel mode; the timer procedure itself needs no time but that);
 *        with the word's at-latch bit (S7's timers) LATCH_MS, the scan's latch time;
 * en   = the RLO; preset = ACCU1's full 32-bit value in ms (negative counts as 0),
 *        re-read at every execution;
 * d    = now - start (modulo 2^32, so the 49-day wrap of TIME_MS is harmless).
 * One edge memory per timer, shared by all four kinds and set to en after each of
 * them; "rising" = en && !edge, "falling" = !en && edge. Status and elapsed change
 * only here. After the update the procedure writes the status bit to TC_BIT (one bus
 * write), so the bit processor's `T n` reads what this execution left.
 */
#include "bb_internal.h"
#include "bus_map.h"
#include "hal.h"

static void start(bb_timer *t, uint32_t now) {
  t->start = now;
  t->running = 1;
}

void bb_timer_update(bb_timer *t, unsigned op, int en, int32_t preset, uint32_t now) {
  const int64_t p = preset < 0 ? 0 : (int64_t)preset;
  en = en != 0;
  if (op == BB_OP_RT) {                   /* R T n: only with RLO = 1 */
    if (en) {
      t->status = 0;
      t->elapsed = 0;
      t->running = 0;
      t->edge = 0;                        /* the next enabled execution is rising */
    }
    return;
  }
  const int rising = en && !t->edge;
  const int falling = !en && t->edge;
#define D ((int64_t)(uint32_t)(now - t->start))
  switch (op) {
    case BB_OP_SD:                        /* on-delay (TON) */
      if (rising) start(t, now);
      if (!en) t->running = 0;
      t->status = (uint8_t)(en && t->running && D >= p);
      break;
    case BB_OP_SS:                        /* retentive on-delay: restart on a rising */
      if (rising) start(t, now);          /* execution, running or not; stop: R only */
      if (t->running && D >= p) t->status = 1;
      break;
    case BB_OP_SP:                        /* pulse (TP): no retrigger while d < preset */
      if (rising && !(t->running && D < p)) start(t, now);
      if (t->running && !en && D >= p) t->running = 0;
      t->status = (uint8_t)(t->running && D < p);
      break;
    case BB_OP_SF:                        /* off-delay (TOF) */
      if (en) {
        t->running = 0;
        t->status = 1;
      } else {
        if (falling) start(t, now);
        if (t->running && D >= p) t->status = 0;
      }
      break;
    default:
      return;
  }
  t->elapsed = t->running ? (int32_t)(D < p ? D : p) : 0;
#undef D
  t->edge = (uint8_t)en;
}

void bb_proc_timer(bb_state *s, unsigned op, unsigned n, int rlo, uint32_t now) {
  bb_timer *t = &s->timer[n];
  bb_timer_update(t, op, rlo, s->accu1, now);
  hal_bus_write(s->hal_ctx, BB_BUS_TC_BIT,
                (t->status ? BB_TC_VALUE : 0u) | (n & BB_TC_INDEX_MASK));
}
