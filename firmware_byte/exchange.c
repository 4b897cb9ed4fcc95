/*
 * exchange.c — the byte side of the condition channels (spec §3 "Exchange
 * instructions"): READ FBY k pops channel k of F_bB into F_B, WRITE FBI k pushes F_B
 * into channel k of F_Bb. One bus access each; while the channel is empty (read) or
 * full (write) the port answers "not ready" and the HAL repeats the access, so a stall
 * simply makes the access (and the instruction) longer.
 */
#include "bb_internal.h"
#include "bus_map.h"
#include "hal.h"

int bb_proc_read(bb_state *s, unsigned k) {
  return (int)(hal_bus_read(s->hal_ctx, (uint16_t)BB_BUS_FBY(k)) & 1u);
}

void bb_proc_write(bb_state *s, unsigned k, int rlo) {
  hal_bus_write(s->hal_ctx, (uint16_t)BB_BUS_FBI(k), rlo ? 1u : 0u);
}
