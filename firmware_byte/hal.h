/*
 * hal.h — the byte processor's only way to the hardware.
 *
 * The firmware (everything in firmware_byte/ but the HAL implementation) calls these
 * five functions and nothing else of the outside world. Implementations: the Verilator
 * C++ harnesses (sim/), the cocotb hosts (through hal_callbacks.c and ctypes) and the
 * fake HAL of the unit tests (tests/fake_hal.c). Clock semantics: docs/byte-bus.md.
 *
 * Every call carries `ctx`, the HAL context of the byte processor that makes it: the
 * pointer its host gave that processor's state with bb_set_hal_ctx() (byteproc.h).
 * The firmware never looks into it; it only hands it back. So one process can run
 * several byte processors (the cores of a plant) on one copy of the firmware, each
 * state with its own context (harness: its core, hal_callbacks.c: its callback table,
 * fake HAL: its fake_hal). The firmware keeps no other state outside its bb_state.
 */
#ifndef BB_HAL_H
#define BB_HAL_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One bus read of word address `addr` (bus_map.h): at least one clock, one more for
 * every clock the port answers "not ready" (the access is repeated). */
uint32_t hal_bus_read(void *ctx, uint16_t addr);

/* One bus write: at least one clock, as hal_bus_read. */
void hal_bus_write(void *ctx, uint16_t addr, uint32_t data);

/* `clocks` clocks of the procedure's own work (no bus access). hal_spend(ctx, 0) is a
 * no-op. */
void hal_spend(void *ctx, uint32_t clocks);

/* Idle until the bit processor dispatches a byte instruction (STATUS.NEXT); returns in
 * the dispatch clock, which is the first clock of the instruction's cost: the idle
 * clocks count for nothing. */
void hal_wait_dispatch(void *ctx);

/* Clocks since clock 0 (scan 0's PII latch). After hal_wait_dispatch() it is the
 * dispatch clock; every bus access and hal_spend() advance it. */
uint64_t hal_now(void *ctx);

#ifdef __cplusplus
}
#endif

#endif /* BB_HAL_H */
