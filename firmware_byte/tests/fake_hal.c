/* fake_hal.c — see fake_hal.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../bus_map.h"
#include "../hal.h"
#include "fake_hal.h"

fake_hal FH;

void fh_init(fake_hal *h) {
  memset(h, 0, sizeof *h);
  h->tick_div = 1000;     /* 1 MHz in the tests: 1000 clocks per ms */
}

void fh_reset(void) { fh_init(&FH); }

/* The HAL context of a call: a fake_hal. NULL means the firmware lost the context it
 * was given (bb_set_hal_ctx): fail loudly instead of guessing a global. */
static fake_hal *fh_of(void *ctx) {
  if (ctx == NULL) {
    fprintf(stderr, "fake_hal: HAL call with a NULL context\n");
    abort();
  }
  return (fake_hal *)ctx;
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
static void sync_inputs(fake_hal *h) {
  for (unsigned i = 0; i < sizeof h->iw_change / sizeof h->iw_change[0]; i++)
    if (h->iw_change[i].armed && h->iw_change[i].at <= h->clock) {
      h->iw[h->iw_change[i].n] = h->iw_change[i].value;
      h->iw_change[i].armed = 0;
    }
}

static uint32_t time_ms(const fake_hal *h) { return (uint32_t)(h->clock / h->tick_div); }

/* addr in the bus window of n registers starting at first (bus_map.h) */
static int in_window(uint16_t addr, unsigned first, unsigned n) {
  return addr >= first && addr < first + n;
}

static uint32_t sext16(uint32_t v) {
  return (v & 0x8000u) ? (0xFFFF0000u | (v & 0xFFFFu)) : (v & 0xFFFFu);
}

static void log_access(fake_hal *h, uint16_t addr, int write, uint32_t data) {
  if (h->nlog < FH_LOG_MAX) {
    fh_access *a = &h->log[h->nlog++];
    a->addr = addr;
    a->write = (uint8_t)write;
    a->data = data;
    a->clock = h->clock;
  }
}

static void stall(fake_hal *h, uint32_t *n) {  /* not-ready clocks before an access completes */
  while (*n > 0) {
    --*n;
    h->clock++;
    h->stalls_byte++;
  }
}

uint32_t hal_bus_read(void *ctx, uint16_t addr) {
  fake_hal *h = fh_of(ctx);
  uint32_t v = 0;
  if (in_window(addr, BB_BUS_FBY(0), BB_BUS_CHANNELS)) stall(h, &h->fby_stall[addr - BB_BUS_FBY(0)]);
  sync_inputs(h);                     /* the value of the clock the access completes in */
  if (in_window(addr, BB_BUS_FBY(0), BB_BUS_CHANNELS)) {
    unsigned k = addr - BB_BUS_FBY(0);
    v = h->fby_val[k];
    h->fby_reads[k]++;
  } else if (in_window(addr, BB_BUS_IW(0), BB_BUS_IW_WORDS)) {
    v = h->iw[addr - BB_BUS_IW(0)];
  } else if (in_window(addr, BB_BUS_QW(0), BB_BUS_QW_WORDS)) {
    v = sext16(h->qw[addr - BB_BUS_QW(0)]);
  } else if (in_window(addr, BB_BUS_MW(0), BB_BUS_MW_WORDS)) {
    v = h->mw[addr - BB_BUS_MW(0)];       /* raw 16 bits: the firmware sign-extends */
  } else {
    switch (addr) {
      case BB_BUS_ID:             v = BB_BUS_ID_VALUE; break;
      case BB_BUS_DISPATCH_INSTR: v = h->dispatch_instr; break;
      case BB_BUS_DISPATCH_CTX:   v = h->dispatch_ctx; break;
      case BB_BUS_DISPATCH_MS:    v = h->disp_ms; break;
      case BB_BUS_DISPATCH_IW:    v = sext16(h->disp_iw); break;
      case BB_BUS_TIME_MS:        v = time_ms(h); break;
      case BB_BUS_LATCH_MS:       v = h->latch_ms; break;
      case BB_BUS_TICK_DIV:       v = h->tick_div; break;
      case BB_BUS_CLOCK:          v = (uint32_t)h->clock; break;
      case BB_BUS_T_STATUS_LO:    v = (uint32_t)h->t_status; break;
      case BB_BUS_T_STATUS_HI:    v = (uint32_t)(h->t_status >> 32); break;
      case BB_BUS_C_STATUS_LO:    v = (uint32_t)h->c_status; break;
      case BB_BUS_C_STATUS_HI:    v = (uint32_t)(h->c_status >> 32); break;
      case BB_BUS_T_ENABLE_LO:    v = (uint32_t)h->t_enable; h->tc_in_reads++; break;
      case BB_BUS_T_ENABLE_HI:    v = (uint32_t)(h->t_enable >> 32); h->tc_in_reads++; break;
      case BB_BUS_C_PULSE_LO:     v = (uint32_t)h->c_pulse; h->tc_in_reads++; break;
      case BB_BUS_C_PULSE_HI:     v = (uint32_t)(h->c_pulse >> 32); h->tc_in_reads++; break;
      case BB_BUS_T_WRITTEN_LO:   v = (uint32_t)h->t_written; break;
      case BB_BUS_T_WRITTEN_HI:   v = (uint32_t)(h->t_written >> 32); break;
      case BB_BUS_C_WRITTEN_LO:   v = (uint32_t)h->c_written; break;
      case BB_BUS_C_WRITTEN_HI:   v = (uint32_t)(h->c_written >> 32); break;
      case BB_BUS_TC_WAIT: {      /* not ready until the selected bit is written */
        const int cnt = (h->tc_wait_sel & BB_TC_COUNTER) != 0;
        const unsigned n = h->tc_wait_sel & BB_TC_INDEX_MASK;
        while (!(((cnt ? h->c_written : h->t_written) >> n) & 1u)) {
          h->clock++;
          h->stalls_byte++;
          h->tc_wait_stalls++;
          if (h->after_access) h->after_access(h->after_access_arg);
        }
        v = (uint32_t)(((cnt ? h->c_pulse : h->t_enable) >> n) & 1u);
        h->tc_in_reads++;
        break;
      }
      case BB_BUS_BYTE_FLAGS:     v = h->byte_flags; break;
      case BB_BUS_STALLS_BYTE:    v = h->stalls_byte; break;
      default:                    v = 0; break;
    }
  }
  log_access(h, addr, 0, v);
  h->clock++;
  if (h->after_access) h->after_access(h->after_access_arg);
  return v;
}

void hal_bus_write(void *ctx, uint16_t addr, uint32_t data) {
  fake_hal *h = fh_of(ctx);
  if (in_window(addr, BB_BUS_FBI(0), BB_BUS_CHANNELS)) {
    unsigned k = addr - BB_BUS_FBI(0);
    stall(h, &h->fbi_stall[k]);
    h->fbi_val[k] = data & 1u;
    h->fbi_writes[k]++;
  } else if (in_window(addr, BB_BUS_QW(0), BB_BUS_QW_WORDS)) {
    h->qw[addr - BB_BUS_QW(0)] = (uint16_t)(data & 0xFFFFu);
  } else if (in_window(addr, BB_BUS_MW(0), BB_BUS_MW_WORDS)) {
    h->mw[addr - BB_BUS_MW(0)] = (uint16_t)(data & 0xFFFFu);
  } else {
    switch (addr) {
      case BB_BUS_DONE:              /* ends the dispatch: the next one snapshots anew */
        h->pending = 0;
        h->done_count++;
        h->done_data = data;
        h->done_clock = h->clock;
        break;
      case BB_BUS_TC_BIT: {
        uint64_t bit = 1ull << (data & BB_TC_INDEX_MASK);
        uint64_t *v = (data & BB_TC_COUNTER) ? &h->c_status : &h->t_status;
        if (data & BB_TC_VALUE) *v |= bit; else *v &= ~bit;
        break;
      }
      case BB_BUS_TICK_DIV:   h->tick_div = data; break;
      case BB_BUS_TC_WAIT:    h->tc_wait_sel = data; break;
      case BB_BUS_BYTE_FLAGS: h->byte_flags = data; break;
      default: break;
    }
  }
  log_access(h, addr, 1, data);
  h->clock++;
  if (h->after_access) h->after_access(h->after_access_arg);
}

void hal_spend(void *ctx, uint32_t clocks) {
  fake_hal *h = fh_of(ctx);
  h->clock += clocks;
  h->spent += clocks;
  h->spend_calls++;
}

/* Returns in the dispatch clock. As the port's disp_first (next_i && !pending_q): a
 * dispatch that begins here captures TIME_MS and IW[instr bits 3..0] of this clock. */
void hal_wait_dispatch(void *ctx) {
  fake_hal *h = fh_of(ctx);
  if (h->dispatch_at > h->clock) h->clock = h->dispatch_at;
  h->waits++;
  sync_inputs(h);
  if (!h->pending) {
    h->pending = 1;
    h->disp_ms = time_ms(h);
    h->disp_iw = (uint16_t)(h->iw[h->dispatch_instr & 0xFu] & 0xFFFFu);
    h->disp_clock = h->clock;
    h->snapshots++;
  }
}

uint64_t hal_now(void *ctx) { return fh_of(ctx)->clock; }
