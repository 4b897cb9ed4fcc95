/*
 * hal_callbacks.c — a HAL implementation that forwards to function pointers, for hosts
 * that cannot define C symbols (Python ctypes, the cocotb bridge). Not part of
 * libbyteproc.{a,so}, which leave hal_* undefined for the host to provide; it is
 * linked only into build/libbyteproc_cb.so. Unset callbacks: reads give 0, the clock
 * stands still.
 */
#include "hal.h"

typedef uint32_t (*bb_hal_read_fn)(uint16_t addr);
typedef void (*bb_hal_write_fn)(uint16_t addr, uint32_t data);
typedef void (*bb_hal_spend_fn)(uint32_t clocks);
typedef void (*bb_hal_wait_fn)(void);
typedef uint64_t (*bb_hal_now_fn)(void);

void bb_hal_set_callbacks(bb_hal_read_fn rd, bb_hal_write_fn wr, bb_hal_spend_fn spend,
                          bb_hal_wait_fn wait, bb_hal_now_fn now);

static bb_hal_read_fn cb_read;
static bb_hal_write_fn cb_write;
static bb_hal_spend_fn cb_spend;
static bb_hal_wait_fn cb_wait;
static bb_hal_now_fn cb_now;

void bb_hal_set_callbacks(bb_hal_read_fn rd, bb_hal_write_fn wr, bb_hal_spend_fn spend,
                          bb_hal_wait_fn wait, bb_hal_now_fn now) {
  cb_read = rd;
  cb_write = wr;
  cb_spend = spend;
  cb_wait = wait;
  cb_now = now;
}

uint32_t hal_bus_read(uint16_t addr) { return cb_read ? cb_read(addr) : 0u; }
void hal_bus_write(uint16_t addr, uint32_t data) { if (cb_write) cb_write(addr, data); }
void hal_spend(uint32_t clocks) { if (cb_spend && clocks) cb_spend(clocks); }
void hal_wait_dispatch(void) { if (cb_wait) cb_wait(); }
uint64_t hal_now(void) { return cb_now ? cb_now() : 0u; }
