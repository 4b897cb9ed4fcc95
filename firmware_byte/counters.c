/*
 * counters.c — CU CD, S C n, R C n (spec §3 "Counters").
 *
 * A counter holds 0..32767 and saturates at both ends. CU / CD count on a 0->1 change
 * of the RLO against their own edge memory, S C n loads clamp(INT(ACCU1), 0, 32767)
 * on a 0->1 change against the S edge memory; each edge memory takes the RLO whenever
 * its instruction executes. R C n with RLO = 1 clears the value and leaves the edge
 * memories alone. Every execution writes the status (value > 0) to TC_BIT.
 */
#include "bb_internal.h"
#include "bus_map.h"
#include "hal.h"

void bb_counter_update(bb_counter *c, unsigned op, int rlo, int32_t accu1) {
  const uint8_t r = rlo != 0;
  switch (op) {
    case BB_OP_CU:
      if (r && !c->cu_edge && c->value < BB_COUNTER_MAX) c->value++;
      c->cu_edge = r;
      break;
    case BB_OP_CD:
      if (r && !c->cd_edge && c->value > 0) c->value--;
      c->cd_edge = r;
      break;
    case BB_OP_SC:
      if (r && !c->s_edge) {
        int32_t v = bb_int16((uint32_t)accu1);
        c->value = (uint16_t)(v < 0 ? 0 : v);   /* INT(x) <= 32767 already */
      }
      c->s_edge = r;
      break;
    case BB_OP_RC:
      if (r) c->value = 0;
      break;
    default:
      break;
  }
}

void bb_proc_counter(bb_state *s, unsigned op, unsigned n, int rlo) {
  bb_counter *c = &s->counter[n];
  bb_counter_update(c, op, rlo, s->accu1);
  hal_bus_write(s->hal_ctx, BB_BUS_TC_BIT,
                (c->value > 0 ? BB_TC_VALUE : 0u) | BB_TC_COUNTER | (n & BB_TC_INDEX_MASK));
}
