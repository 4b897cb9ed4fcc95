/* fake_hal.c — see fake_hal.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../bus_map.h"
#include "../hal.h"
#include "fake_hal.h"

fake_hal FH;

void fh_reset(void) {
  memset(&FH, 0, sizeof FH);
  FH.tick_div = 1000;     /* 1 MHz in the tests: 1000 clocks per ms */
}

void fh_set_ms(uint32_t ms) { FH.clock = (uint64_t)ms * FH.tick_div; }

void fh_clear_log(void) { FH.nlog = 0; }

void fh_iw_at(unsigned n, uint32_t value, uint64_t at) {
  for (unsigned i = 0; i < sizeof FH.iw_change / sizeof FH.iw_change[0]; i++)
    if (!FH.iw_change[i].armed) {
      FH.iw_change[i].at = at;
      FH.iw_change[i].n = n & 0xFu;
      FH.iw_change[i].value = value;
      FH.iw_change[i].armed = 1;
      return;
    }
  fprintf(stderr, "fake_hal: more than 8 pending input-word changes\n");
  abort();
}

/* Bring the inputs up to the current clock: the scheduled IW changes that are due. */
static void sync_inputs(void) {
  for (unsigned i = 0; i < sizeof FH.iw_change / sizeof FH.iw_change[0]; i++)
    if (FH.iw_change[i].armed && FH.iw_change[i].at <= FH.clock) {
      FH.iw[FH.iw_change[i].n] = FH.iw_change[i].value;
      FH.iw_change[i].armed = 0;
    }
}

static uint32_t time_ms(void) { return (uint32_t)(FH.clock / FH.tick_div); }

static uint32_t sext16(uint32_t v) {
  return (v & 0x8000u) ? (0xFFFF0000u | (v & 0xFFFFu)) : (v & 0xFFFFu);
}

static void log_access(uint16_t addr, int write, uint32_t data) {
  if (FH.nlog < FH_LOG_MAX) {
    fh_access *a = &FH.log[FH.nlog++];
    a->addr = addr;
    a->write = (uint8_t)write;
    a->data = data;
    a->clock = FH.clock;
  }
}

static void stall(uint32_t *n) {     /* not-ready clocks before an access completes */
  while (*n > 0) {
    --*n;
    FH.clock++;
    FH.stalls_byte++;
  }
}

uint32_t hal_bus_read(uint16_t addr) {
  uint32_t v = 0;
  if (addr >= 0x20 && addr < 0x28) stall(&FH.fby_stall[addr - 0x20u]);
  sync_inputs();                     /* the value of the clock the access completes in */
  if (addr >= 0x20 && addr < 0x28) {
    unsigned k = addr - 0x20u;
    v = FH.fby_val[k];
    FH.fby_reads[k]++;
  } else if (addr >= 0x40 && addr < 0x50) {
    v = FH.iw[addr - 0x40];
  } else if (addr >= 0x50 && addr < 0x60) {
    v = sext16(FH.qw[addr - 0x50]);
  } else if (addr >= 0x100 && addr < 0x200) {
    v = FH.mw[addr - 0x100];       /* raw 16 bits: the firmware sign-extends */
  } else {
    switch (addr) {
      case BB_BUS_ID:             v = BB_BUS_ID_VALUE; break;
      case BB_BUS_DISPATCH_INSTR: v = FH.dispatch_instr; break;
      case BB_BUS_DISPATCH_CTX:   v = FH.dispatch_ctx; break;
      case BB_BUS_DISPATCH_MS:    v = FH.disp_ms; break;
      case BB_BUS_DISPATCH_IW:    v = sext16(FH.disp_iw); break;
      case BB_BUS_TIME_MS:        v = time_ms(); break;
      case BB_BUS_TICK_DIV:       v = FH.tick_div; break;
      case BB_BUS_CLOCK:          v = (uint32_t)FH.clock; break;
      case BB_BUS_T_STATUS_LO:    v = (uint32_t)FH.t_status; break;
      case BB_BUS_T_STATUS_HI:    v = (uint32_t)(FH.t_status >> 32); break;
      case BB_BUS_C_STATUS_LO:    v = (uint32_t)FH.c_status; break;
      case BB_BUS_C_STATUS_HI:    v = (uint32_t)(FH.c_status >> 32); break;
      case BB_BUS_BYTE_FLAGS:     v = FH.byte_flags; break;
      case BB_BUS_STALLS_BYTE:    v = FH.stalls_byte; break;
      default:                    v = 0; break;
    }
  }
  log_access(addr, 0, v);
  FH.clock++;
  return v;
}

void hal_bus_write(uint16_t addr, uint32_t data) {
  if (addr >= 0x28 && addr < 0x30) {
    unsigned k = addr - 0x28u;
    stall(&FH.fbi_stall[k]);
    FH.fbi_val[k] = data & 1u;
    FH.fbi_writes[k]++;
  } else if (addr >= 0x50 && addr < 0x60) {
    FH.qw[addr - 0x50] = (uint16_t)(data & 0xFFFFu);
  } else if (addr >= 0x100 && addr < 0x200) {
    FH.mw[addr - 0x100] = (uint16_t)(data & 0xFFFFu);
  } else {
    switch (addr) {
      case BB_BUS_DONE:              /* ends the dispatch: the next one snapshots anew */
        FH.pending = 0;
        FH.done_count++;
        FH.done_data = data;
        FH.done_clock = FH.clock;
        break;
      case BB_BUS_TC_BIT: {
        uint64_t bit = 1ull << (data & BB_TC_INDEX_MASK);
        uint64_t *v = (data & BB_TC_COUNTER) ? &FH.c_status : &FH.t_status;
        if (data & BB_TC_VALUE) *v |= bit; else *v &= ~bit;
        break;
      }
      case BB_BUS_TICK_DIV:   FH.tick_div = data; break;
      case BB_BUS_BYTE_FLAGS: FH.byte_flags = data; break;
      default: break;
    }
  }
  log_access(addr, 1, data);
  FH.clock++;
}

void hal_spend(uint32_t clocks) {
  FH.clock += clocks;
  FH.spent += clocks;
  FH.spend_calls++;
}

/* Returns in the dispatch clock. As the port's disp_first (next_i && !pending_q): a
 * dispatch that begins here captures TIME_MS and IW[instr bits 3..0] of this clock. */
void hal_wait_dispatch(void) {
  if (FH.dispatch_at > FH.clock) FH.clock = FH.dispatch_at;
  FH.waits++;
  sync_inputs();
  if (!FH.pending) {
    FH.pending = 1;
    FH.disp_ms = time_ms();
    FH.disp_iw = (uint16_t)(FH.iw[FH.dispatch_instr & 0xFu] & 0xFFFFu);
    FH.disp_clock = FH.clock;
    FH.snapshots++;
  }
}

uint64_t hal_now(void) { return FH.clock; }
