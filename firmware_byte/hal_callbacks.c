/*
 * hal_callbacks.c — the HAL of hal_callbacks.h: every call goes to the callback table
 * its context points to. Not part of libbyteproc.{a,so}, which leave hal_* undefined
 * for the host to provide; it is linked only into build/libbyteproc_cb.so.
 */
#include "hal.h"
#include "hal_callbacks.h"

uint32_t hal_bus_read(void *ctx, uint16_t addr) {
  const bb_hal_callbacks *cb = ctx;
  return cb && cb->bus_read ? cb->bus_read(addr) : 0u;
}

void hal_bus_write(void *ctx, uint16_t addr, uint32_t data) {
  const bb_hal_callbacks *cb = ctx;
  if (cb && cb->bus_write) cb->bus_write(addr, data);
}

void hal_spend(void *ctx, uint32_t clocks) {
  const bb_hal_callbacks *cb = ctx;
  if (cb && cb->spend && clocks) cb->spend(clocks);
}

void hal_wait_dispatch(void *ctx) {
  const bb_hal_callbacks *cb = ctx;
  if (cb && cb->wait_dispatch) cb->wait_dispatch();
}

uint64_t hal_now(void *ctx) {
  const bb_hal_callbacks *cb = ctx;
  return cb && cb->now ? cb->now() : 0u;
}
