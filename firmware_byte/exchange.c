/*
 * exchange.c — the byte side of the condition channels (spec §3 "Exchange
 * instructions"): READ FBY k pops channel k of F_bB into F_B, WRITE FBI k pushes F_B
 * into channel k of F_Bb. One bus access each; while the channel is empty (read) or
 * full (write) the port answers "not ready" and the HAL repeats the access, so a stall
 * simply makes the access (and the instruction) longer. With the marker exchange k is
 * a cell of the marker area (up to BB_NUM_CELLS): cells 0..7 answer at the channel
 * registers as well, the others only in the MCELL window, so k < 8 keeps the channel
 * register (one address per k whatever the exchange) and k >= 8 takes the window.
 */
#include "bb_internal.h"
#include "bus_map.h"
#include "hal.h"

int bb_proc_read(bb_state *s, unsigned k) {
  uint16_t a = (uint16_t)(k < BB_BUS_CHANNELS ? BB_BUS_FBY(k) : BB_BUS_MCELL(k));
  return (int)(hal_bus_read(s->hal_ctx, a) & 1u);
}

void bb_proc_write(bb_state *s, unsigned k, int rlo) {
  uint16_t a = (uint16_t)(k < BB_BUS_CHANNELS ? BB_BUS_FBI(k) : BB_BUS_MCELL(k));
  hal_bus_write(s->hal_ctx, a, rlo ? 1u : 0u);
}
