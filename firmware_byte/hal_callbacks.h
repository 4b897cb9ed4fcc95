/*
 * hal_callbacks.h — a HAL that forwards to function pointers (hal_callbacks.c), for
 * hosts that cannot define C symbols (Python ctypes: bitbyte/sim/cocotb_driver.py,
 * bitbyte/sim/cocotb_plant.py). Only in build/libbyteproc_cb.so.
 *
 * A host fills one bb_hal_callbacks per byte processor and makes it that state's HAL
 * context: bb_set_hal_ctx(state, &table). hal_bus_read(ctx, ...) and the others call
 * the table ctx points to, so several states in one process (the cores of a plant)
 * each reach their own callbacks: no globals, one loaded library for all of them.
 * A NULL context or a NULL entry: reads give 0, writes are dropped, the clock stands
 * still.
 */
#ifndef BB_HAL_CALLBACKS_H
#define BB_HAL_CALLBACKS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct bb_hal_callbacks {
  uint32_t (*bus_read)(uint16_t addr);
  void     (*bus_write)(uint16_t addr, uint32_t data);
  void     (*spend)(uint32_t clocks);
  void     (*wait_dispatch)(void);
  uint64_t (*now)(void);
} bb_hal_callbacks;

#ifdef __cplusplus
}
#endif

#endif /* BB_HAL_CALLBACKS_H */
