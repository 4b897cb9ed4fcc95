/*
 * hal.h — the byte processor's only way to the hardware.
 *
 * The firmware (everything in firmware_byte/ but the HAL implementation) calls these
 * five functions and nothing else of the outside world. Implementations: the Verilator
 * C++ harness (sim/), the cocotb bridge (through hal_callbacks.c and ctypes) and the
 * fake HAL of the unit tests (tests/fake_hal.c). Clock semantics: docs/byte-bus.md.
 */
#ifndef BB_HAL_H
#define BB_HAL_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One bus read of word address `addr` (bus_map.h): at least one clock, one more for
 * every clock the port answers "not ready" (the access is repeated). */
uint32_t hal_bus_read(uint16_t addr);

/* One bus write: at least one clock, as hal_bus_read. */
void hal_bus_write(uint16_t addr, uint32_t data);

/* `clocks` clocks of the procedure's own work (no bus access). hal_spend(0) is a no-op. */
void hal_spend(uint32_t clocks);

/* Idle until the bit processor dispatches a byte instruction (STATUS.NEXT); returns in
 * the dispatch clock, which is the first clock of the instruction's cost: the idle
 * clocks count for nothing. */
void hal_wait_dispatch(void);

/* Clocks since clock 0 (scan 0's PII latch). After hal_wait_dispatch() it is the
 * dispatch clock; every bus access and hal_spend() advance it. */
uint64_t hal_now(void);

#ifdef __cplusplus
}
#endif

#endif /* BB_HAL_H */
