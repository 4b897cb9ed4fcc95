/*
 * fake_hal.h — the unit tests' HAL: the registers of docs/byte-bus.md the firmware
 * uses, one clock per access (plus programmable not-ready clocks on the channels), a
 * clock counter and a log of every access.
 *
 * The dispatch snapshot is modelled as rtl/byte_port.v does it: a dispatch begins in
 * the clock hal_wait_dispatch() returns in, unless the previous one is still pending
 * (no DONE yet); in that first clock DISPATCH_MS := TIME_MS and DISPATCH_IW := IW n,
 * n = bits 3..0 of dispatch_instr (whatever the instruction), and both hold until the
 * next dispatch begins. Input words can be scheduled to change at a given clock
 * (fh_iw_at), so a test can change one in the middle of an instruction.
 */
#ifndef FAKE_HAL_H
#define FAKE_HAL_H

#include <stdint.h>

#define FH_LOG_MAX 4096

typedef struct {
  uint16_t addr;
  uint8_t  write;     /* 1: write, 0: read */
  uint32_t data;      /* written, or returned */
  uint64_t clock;     /* the clock the access completed in */
} fh_access;

typedef struct {
  uint64_t clock;            /* hal_now() */
  uint32_t tick_div;         /* TIME_MS = clock / tick_div */
  uint16_t mw[256];          /* a plant core's word markers, BB_BUS_MW(n) */
  /* serial dispatch */
  uint32_t dispatch_instr, dispatch_ctx;
  uint64_t dispatch_at;      /* hal_wait_dispatch(): the clock it returns in (if later) */
  unsigned waits;
  /* dispatch snapshot (the port's disp_ms_q / disp_iw_q / pending_q) */
  int      pending;          /* a dispatch began and DONE has not come */
  uint32_t disp_ms;          /* TIME_MS in the dispatch's first clock */
  uint16_t disp_iw;          /* IW (instr bits 3..0) in that clock; read sign-extended */
  uint64_t disp_clock;       /* the clock the snapshot was taken in */
  uint32_t latch_ms;         /* LATCH_MS: TIME_MS at the last latch (set by the test) */
  unsigned snapshots;
  /* DONE */
  unsigned done_count;
  uint32_t done_data;
  uint64_t done_clock;
  /* word I/O */
  uint32_t iw[16];           /* returned as read by 0x40+n (the RTL sign-extends) */
  /* scheduled input-word changes: iw[n] := value from clock `at` on */
  struct { uint64_t at; unsigned n; uint32_t value; int armed; } iw_change[8];
  uint16_t qw[16];
  /* status buffer, as the RTL's tc_status keeps it */
  uint64_t t_status, c_status;
  /* the enable / pulse half, written by the bit side (`= T n` / `= C n`) */
  uint64_t t_enable, c_pulse;
  unsigned tc_in_reads;      /* reads of T_ENABLE_* / C_PULSE_* */
  /* written this scan (T_WRITTEN / C_WRITTEN); TC_WAIT: the selection its last write
   * made, and the not-ready clocks its reads took (after_access runs after each) */
  uint64_t t_written, c_written;
  uint32_t tc_wait_sel;
  unsigned tc_wait_stalls;
  uint32_t byte_flags;
  /* channels: FBY k (read) returns fby_val[k] after fby_stall[k] not-ready clocks;
   * FBI k (write) takes fbi_stall[k] not-ready clocks, stores fbi_val[k] */
  uint32_t fby_val[8];
  uint32_t fby_stall[8], fbi_stall[8];
  uint32_t fbi_val[8];
  unsigned fby_reads[8], fbi_writes[8];
  uint32_t stalls_byte;
  uint64_t spent;            /* clocks given to hal_spend() */
  unsigned spend_calls;
  /* log */
  fh_access log[FH_LOG_MAX];
  unsigned nlog;
  /* called after every bus access (test_contexts.c: another state's step inside) */
  void (*after_access)(void *arg);
  void *after_access_arg;
} fake_hal;

/* The tests' default instance: setup() (tt.h) makes it the HAL context of S. Any
 * fake_hal can be a context (bb_set_hal_ctx): each is a separate bus and clock. */
extern fake_hal FH;

void fh_init(fake_hal *h);     /* a fresh fake HAL: no log, clock 0, 1000 clocks per ms */
void fh_reset(void);           /* fh_init(&FH) */
/* These act on FH. */
void fh_set_ms(uint32_t ms);   /* clock := ms * tick_div */
void fh_clear_log(void);
/* From clock `at` on, IW n reads `value` (0x40+n live; DISPATCH_IW if a dispatch
 * begins then). Up to 8 changes may be pending. */
void fh_iw_at(unsigned n, uint32_t value, uint64_t at);

#endif
