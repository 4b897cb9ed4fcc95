/*
 * interp.c — decode, dispatch and cost accounting of the byte processor.
 *
 * bb_classify() decodes an instruction word (docs/isa.md) into its cost class and
 * validates its operand; exec() runs it, with the loads and transfers done here and the
 * other procedures in arith.c, compare.c, timers.c, counters.c and exchange.c.
 * bb_serial_step() wraps one execution in the serial dispatch protocol and pads it to
 * exactly its table cost; bb_step() does the padding for parallel mode, and
 * bb_run_scan() runs parallel mode's byte program (its own jumps, END_B) one scan at a
 * time with bb_step().
 */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "bb_internal.h"
#include "bus_map.h"
#include "hal.h"

/* ------------------------------------------------------------------- set-up */

void bb_init(bb_state *s, const bb_costs *costs) {
  memset(s, 0, sizeof *s);
  s->costs = costs != NULL ? costs : bb_cost_table(NULL);
  s->last_class = BB_CL_ILLEGAL;
  s->max_steps = BB_MAX_STEPS_DEFAULT;
}

void bb_load_pool(bb_state *s, const uint32_t *words, unsigned n) {
  if (words == NULL) n = 0;
  if (n > BB_POOL_WORDS) n = BB_POOL_WORDS;
  if (n > 0) memcpy(s->pool, words, n * sizeof *words);
  s->pool_len = n;
}

int bb_load_program(bb_state *s, const uint32_t *words, unsigned n) {
  if (n > BB_PROG_WORDS || (words == NULL && n > 0)) return -1;
  if (n > 0) memcpy(s->prog, words, n * sizeof *words);
  s->prog_len = n;
  s->pc = 0;
  return 0;
}

void bb_scan_start(bb_state *s) {
  s->accu1 = 0;
  s->accu2 = 0;
  s->cc = 0;
}

bb_state *bb_new(void) {
  bb_state *s = malloc(sizeof *s);   /* the firmware's only allocation (ctypes side) */
  if (s != NULL) bb_init(s, NULL);
  return s;
}

void bb_free(bb_state *s) { free(s); }

void bb_raise_flag(bb_state *s, uint32_t flag) {
  s->flags |= flag;
  hal_bus_write(s->hal_ctx, BB_BUS_BYTE_FLAGS, s->flags);
}

/* ------------------------------------------------------------------- decode */

static int word_operand_ok(unsigned area, unsigned n, int for_load) {
  switch (area) {
    case BB_AREA_IW: return for_load && n < BB_NUM_IW;
    case BB_AREA_QW: return n < BB_NUM_QW;
    case BB_AREA_MW: return n < BB_NUM_MW;
    case BB_AREA_MD: return n + 2u < BB_NUM_MW;   /* MW n and MW n+2 */
    case BB_AREA_T:  return for_load && n < BB_NUM_TIMERS;
    case BB_AREA_C:  return for_load && n < BB_NUM_COUNTERS;
    default:         return 0;
  }
}

int bb_classify(uint32_t instr) {
  const unsigned op = bb_opcode(instr), area = bb_area(instr), n = bb_index(instr);
  switch (op) {
    case BB_OP_L_IMM:
    case BB_OP_L_POOL:
      return BB_CL_LOAD;
    case BB_OP_L_WORD:
      return word_operand_ok(area, n, 1) ? BB_CL_LOAD : BB_CL_ILLEGAL;
    case BB_OP_T_WORD:
      return word_operand_ok(area, n, 0) ? BB_CL_TRANSFER : BB_CL_ILLEGAL;
    case BB_OP_ADD: case BB_OP_SUB: case BB_OP_ADD_D: case BB_OP_SUB_D:
      return BB_CL_ARITH;
    case BB_OP_MUL: case BB_OP_DIV: case BB_OP_MOD:
    case BB_OP_MUL_D: case BB_OP_DIV_D: case BB_OP_MOD_D:
      return BB_CL_MULDIV;
    case BB_OP_AW: case BB_OP_OW: case BB_OP_XOW: case BB_OP_AD: case BB_OP_OD:
    case BB_OP_XOD:
      return BB_CL_ARITH;
    case BB_OP_SLW: case BB_OP_SRW: case BB_OP_SSI: case BB_OP_SLD: case BB_OP_SRD:
    case BB_OP_SSD: case BB_OP_RLD: case BB_OP_RRD:   /* a count 0..255, or from ACCU2 */
      return (n & ~(BB_COUNT_FROM_ACCU2 | 0xFFu)) == 0u ? BB_CL_ARITH : BB_CL_ILLEGAL;
    case BB_OP_SD: case BB_OP_SS: case BB_OP_SP: case BB_OP_SF: case BB_OP_RT:
      return (area == BB_AREA_T && n < BB_NUM_TIMERS) ? BB_CL_TIMER : BB_CL_ILLEGAL;
    case BB_OP_CU: case BB_OP_CD: case BB_OP_SC: case BB_OP_RC:
      return (area == BB_AREA_C && n < BB_NUM_COUNTERS) ? BB_CL_COUNTER : BB_CL_ILLEGAL;
    case BB_OP_READ: case BB_OP_WRITE:
      return (area == BB_AREA_FB && n < BB_NUM_CELLS) ? BB_CL_BINARY : BB_CL_ILLEGAL;
    case BB_OP_STATUS: case BB_OP_STATUS + 1u: case BB_OP_STATUS + 2u:
    case BB_OP_STATUS + 3u:   /* a condition c <= OS, maybe negated, nothing else */
      return ((n & ~(BB_STATUS_NEGATE | BB_STATUS_COND)) == 0u && (n & BB_STATUS_COND) <= BB_CC_OS)
             ? BB_CL_COMPARE : BB_CL_ILLEGAL;
    case BB_OP_JU_B: case BB_OP_JC_B: case BB_OP_JCN_B:
      return BB_CL_BINARY;     /* the target is checked by execution (program length) */
    case BB_OP_END_B:
      return BB_CL_END;
    default:
      break;
  }
  if ((op & ~7u) == BB_OP_CMP || (op & ~7u) == BB_OP_A_CMP || (op & ~7u) == BB_OP_O_CMP
      || (op & ~7u) == BB_OP_CMP_D || (op & ~7u) == BB_OP_A_CMP_D
      || (op & ~7u) == BB_OP_O_CMP_D)
    return (op & 7u) <= BB_CMP_LE ? BB_CL_COMPARE : BB_CL_ILLEGAL;
  return BB_CL_ILLEGAL;
}

/* ------------------------------------------------------------------- load / transfer */

/* L x: the new ACCU1 (the caller shifts ACCU1 into ACCU2). One bus read for IW / QW.
 * Serial mode reads IW n from DISPATCH_IW, the port's copy of it taken in the
 * instruction's first clock: an instruction samples its inputs in its first clock. */
/* Data word MW n, sign-extended (a plant core keeps MW in the FPGA, where its copy
 * engine is). */
static int32_t load_mw(const bb_state *s, unsigned n) {
  return s->mw_on_bus ? bb_int16(hal_bus_read(s->hal_ctx, (uint16_t)BB_BUS_MW(n)))
                      : s->mw[n];
}

static int32_t load_word(const bb_state *s, unsigned area, unsigned n, int serial) {
  switch (area) {
    case BB_AREA_MD: {  /* S7's MD n: MW n the high half, MW n+2 the low half */
      const uint32_t hi = (uint32_t)load_mw(s, n) & 0xFFFFu;
      const uint32_t lo = (uint32_t)load_mw(s, n + 2u) & 0xFFFFu;
      return bb_s32(hi << 16 | lo);
    }
    case BB_AREA_IW:
      return bb_int16(hal_bus_read(s->hal_ctx, serial ? BB_BUS_DISPATCH_IW
                                                      : (uint16_t)BB_BUS_IW(n)));
    case BB_AREA_QW:  /* no copy */
      return bb_int16(hal_bus_read(s->hal_ctx, (uint16_t)BB_BUS_QW(n)));
    case BB_AREA_MW:  return load_mw(s, n);
    case BB_AREA_T:  return s->timer[n].elapsed;
    case BB_AREA_C:  return s->counter[n].value;
    default:         return 0;   /* excluded by bb_classify() */
  }
}

/* One data word MW n := the low 16 bits of v. */
static void store_mw(bb_state *s, unsigned n, uint32_t v) {
  if (s->mw_on_bus)
    hal_bus_write(s->hal_ctx, (uint16_t)BB_BUS_MW(n), v & 0xFFFFu);
  else
    s->mw[n] = (int16_t)bb_int16(v);
}

/* T w: the low 16 bits of ACCU1 (T MD n: all 32, the high half to MW n). One bus
 * write for QW. */
static void transfer_word(bb_state *s, unsigned area, unsigned n) {
  const uint32_t v = (uint32_t)s->accu1;
  if (area == BB_AREA_QW) {
    hal_bus_write(s->hal_ctx, (uint16_t)BB_BUS_QW(n), v & 0xFFFFu);
  } else if (area == BB_AREA_MD) {
    store_mw(s, n, v >> 16);
    store_mw(s, n + 2u, v);
  } else {
    store_mw(s, n, v);
  }
}

/* ------------------------------------------------------------------- execute */

/* One instruction. *rlo is F_B / the RLO in and out. serial: the instruction was
 * dispatched, so `now` and IW come from the port's dispatch snapshot (DISPATCH_MS,
 * DISPATCH_IW, both taken in the instruction's first clock); otherwise a timer reads
 * TIME_MS as its first access. Returns the cost class. */
/* --tc-path status (docs/exchange.md): a timer's enable / a counter's input is bit n of
 * the status buffer's T_ENABLE / C_PULSE (the bit side's `= T n` / `= C n`), read over
 * the bus, instead of F_B; one bus read, inside the class's table cost. F_B is left
 * as it was. lo: the _LO register, _HI follows it (32 bits each). */
static int status_bit(bb_state *s, uint16_t lo, unsigned n) {
  return (int)((hal_bus_read(s->hal_ctx, (uint16_t)(lo + n / 32u)) >> (n % 32u)) & 1u);
}

/* Parallel mode adds BB_STATUS_WAIT: the bit side writes the bit in this scan, maybe
 * after the byte side gets here, so the bit is read through TC_WAIT: a write selects
 * timer / counter n, the read is not ready (a bus stall, as an empty channel's) until
 * the bit side has written it since the scan's latch. The compiler puts the bit row
 * `= T n` right before this instruction's row, so the bit side reaches the write without
 * waiting for anything the byte side does after it: the wait ends (docs/exchange.md). Like a
 * channel read's, the clocks it takes count against the instruction's cost. */
static int status_input(bb_state *s, uint32_t instr, uint16_t lo, unsigned n) {
  if (instr & BB_STATUS_WAIT) {
    const uint32_t counter = lo == BB_BUS_C_PULSE_LO ? BB_TC_COUNTER : 0u;
    hal_bus_write(s->hal_ctx, BB_BUS_TC_WAIT, counter | (n & BB_TC_INDEX_MASK));
    return (int)(hal_bus_read(s->hal_ctx, BB_BUS_TC_WAIT) & 1u);
  }
  return status_bit(s, lo, n);
}

static int is_jump(unsigned op) {
  return op == BB_OP_JU_B || op == BB_OP_JC_B || op == BB_OP_JCN_B;
}

static int exec(bb_state *s, uint32_t instr, int *rlo, int serial) {
  const unsigned op = bb_opcode(instr), area = bb_area(instr), n = bb_index(instr);
  int cls = bb_classify(instr);
  int r = *rlo != 0;
  s->rlo_written = 0;
  s->jumped = 0;
  /* The jumps and END_B belong to a byte program; a dispatched one is illegal. */
  if (serial && (cls == BB_CL_END || is_jump(op))) cls = BB_CL_ILLEGAL;

  switch (cls) {
    case BB_CL_LOAD: {
      int32_t v;
      if (op == BB_OP_L_IMM) {
        v = bb_imm24(instr);
      } else if (op == BB_OP_L_POOL) {
        uint32_t i = instr & BB_IMM_MASK;
        if (i >= s->pool_len) {            /* a pool the program did not bring */
          cls = BB_CL_ILLEGAL;
          bb_raise_flag(s, BB_FLAG_ILLEGAL);
          break;
        }
        v = bb_s32(s->pool[i]);
      } else {
        v = load_word(s, area, n, serial);
      }
      s->accu2 = s->accu1;
      s->accu1 = v;
      break;
    }
    case BB_CL_TRANSFER:
      transfer_word(s, area, n);
      break;
    case BB_CL_ARITH:
    case BB_CL_MULDIV:
      if (bb_is_logic(op) || bb_is_shift(op))
        bb_proc_logic(s, instr);
      else
        bb_proc_arith(s, op);
      break;
    case BB_CL_COMPARE:
      if ((op & ~3u) == BB_OP_STATUS) {       /* a status-bit read: CC unchanged */
        r = bb_proc_status_read(s, op, n, r);
      } else {
        r = bb_proc_compare(s, op, r);
        s->cc = bb_compare_cc(s, op) | (s->cc & BB_SW_OS);   /* OV 0, OS kept */
      }
      s->rlo_written = 1;
      break;
    case BB_CL_TIMER: {
      uint32_t now = 0;
      if (op != BB_OP_RT)                    /* one read either way: the cost is the same */
        now = hal_bus_read(s->hal_ctx, (instr & BB_AT_LATCH) ? BB_BUS_LATCH_MS :
                                       serial ? BB_BUS_DISPATCH_MS : BB_BUS_TIME_MS);
      bb_proc_timer(s, op, n, (instr & BB_FROM_STATUS) ?
                    status_input(s, instr, BB_BUS_T_ENABLE_LO, n) : r, now);
      break;
    }
    case BB_CL_COUNTER:
      bb_proc_counter(s, op, n, (instr & BB_FROM_STATUS) ?
                      status_input(s, instr, BB_BUS_C_PULSE_LO, n) : r);
      break;
    case BB_CL_BINARY:
      if (is_jump(op)) {
        const uint32_t target = instr & BB_TARGET_MASK;   /* bits 23..16 reserved, ignored */
        if (target > s->prog_len) {                /* past the loaded program */
          cls = BB_CL_ILLEGAL;
          bb_raise_flag(s, BB_FLAG_ILLEGAL);
          break;
        }
        if (op == BB_OP_JU_B || (op == BB_OP_JC_B) == (r != 0)) {
          s->pc = target;       /* == prog_len: off the end, the scan's byte part ends */
          s->jumped = 1;
        }
      } else if (op == BB_OP_READ) {
        r = bb_proc_read(s, n);
        s->rlo_written = 1;
      } else {
        bb_proc_write(s, n, r);
      }
      break;
    case BB_CL_END:             /* bb_run_scan() stops on the class */
      break;
    default:
      cls = BB_CL_ILLEGAL;
      bb_raise_flag(s, BB_FLAG_ILLEGAL);
      break;
  }
  *rlo = r;
  s->rlo = r;
  s->executed++;
  s->last_instr = instr;
  s->last_class = cls;
  return cls;
}

int bb_exec(bb_state *s, uint32_t instr, int *rlo) {
  int local = s->rlo;
  int *io = rlo != NULL ? rlo : &local;
  int cls = exec(s, instr, io, 0);
  return cls;
}

/* Cost accounting. The table cost covers everything the instruction does on the bus;
 * whatever it leaves is spent with hal_spend(). Bus accesses that stall can make the
 * instruction longer than its cost: never spend a negative amount, count an overrun. */
int bb_step(bb_state *s, uint32_t instr, int *rlo) {
  void *const hal = s->hal_ctx;
  const uint64_t t0 = hal_now(hal);
  const int cls = bb_exec(s, instr, rlo);
  const uint64_t cost = bb_cost(s, cls);
  const uint64_t used = hal_now(hal) - t0;
  if (used < cost) hal_spend(hal, (uint32_t)(cost - used));
  const uint64_t taken = hal_now(hal) - t0;
  if (taken > cost) s->overruns++;
  s->last_clocks = (uint32_t)taken;
  return (int)taken;
}

/* Parallel mode, one scan of the byte program. F_B := 0 at the start: the byte part of
 * a scan must not depend on where the previous one stopped (the same reason the ACCUs
 * are cleared), and a program that wants a condition from the bit side gets it with
 * READ FBY k. The runaway guard is in instructions, not clocks: the hardware watchdog
 * (bit side) bounds the scan time; this only keeps a byte-side loop from hanging the
 * firmware. */
int bb_run_scan(bb_state *s) {
  const uint64_t t0 = hal_now(s->hal_ctx);
  int rlo = 0;
  bb_scan_start(s);
  s->rlo = 0;
  s->pc = 0;
  s->jumped = 0;
  s->scan_steps = 0;
  while (s->pc < s->prog_len) {                  /* off the end: as END_B */
    if (s->scan_steps >= s->max_steps) {
      bb_raise_flag(s, BB_FLAG_RUNAWAY);
      break;
    }
    const uint32_t at = s->pc;
    const uint32_t instr = s->prog[s->pc++];     /* a taken jump overwrites the PC */
    s->scan_steps++;
    bb_step(s, instr, &rlo);
    if (s->last_class == BB_CL_END) break;
    s->ret_pc = at;                              /* the block status's record */
    s->ret_rlo = rlo;
    s->ret_accu1 = s->accu1;
    s->ret_accu2 = s->accu2;
    s->ret_seq++;
  }
  const uint64_t taken = hal_now(s->hal_ctx) - t0;
  return taken > (uint64_t)INT_MAX ? INT_MAX : (int)taken;
}

int bb_serial_step(bb_state *s) {
  void *const hal = s->hal_ctx;
  hal_wait_dispatch(hal);
  const uint64_t t0 = hal_now(hal);                              /* the dispatch clock */
  const uint32_t instr = hal_bus_read(hal, BB_BUS_DISPATCH_INSTR); /* t0 */
  const uint32_t ctx = hal_bus_read(hal, BB_BUS_DISPATCH_CTX);     /* t0 + 1 */
  /* the scan's first byte instruction: ACCUs := 0. The RTL's flag, not a change of the
   * scan number: that field has 16 bits, and a program whose byte instructions are
   * skipped for a multiple of 65 536 scans would keep its accumulators. */
  if (ctx & BB_CTX_FIRST) bb_scan_start(s);
  int rlo = (ctx & BB_CTX_RLO) != 0;
  const int cls = exec(s, instr, &rlo, 1);
  const uint64_t cost = bb_cost(s, cls);
  const uint64_t used = hal_now(hal) - t0;
  if (used + 1 < cost) hal_spend(hal, (uint32_t)(cost - used - 1)); /* leave 1 for DONE */
  hal_bus_write(hal, BB_BUS_DONE,
                (rlo ? BB_DONE_RLO : 0u) | (s->rlo_written ? BB_DONE_RLO_WE : 0u));
  const uint64_t taken = hal_now(hal) - t0;
  if (taken > cost) s->overruns++;
  s->last_clocks = (uint32_t)taken;
  return (int)taken;
}

/* ------------------------------------------------------------------- accessors */

void bb_set_mw_bus(bb_state *s, int on) { s->mw_on_bus = on != 0; }
void bb_set_hal_ctx(bb_state *s, void *ctx) { s->hal_ctx = ctx; }
void *bb_hal_ctx(const bb_state *s) { return s->hal_ctx; }
int16_t bb_mw(const bb_state *s, unsigned n) { return n < BB_NUM_MW ? s->mw[n] : 0; }

int32_t bb_timer_elapsed(const bb_state *s, unsigned n) {
  return n < BB_NUM_TIMERS ? s->timer[n].elapsed : 0;
}

int bb_timer_status(const bb_state *s, unsigned n) {
  return n < BB_NUM_TIMERS ? s->timer[n].status : 0;
}

int bb_timer_running(const bb_state *s, unsigned n) {
  return n < BB_NUM_TIMERS ? s->timer[n].running : 0;
}

int bb_counter_value(const bb_state *s, unsigned n) {
  return n < BB_NUM_COUNTERS ? s->counter[n].value : 0;
}

int bb_counter_status(const bb_state *s, unsigned n) {
  return n < BB_NUM_COUNTERS ? s->counter[n].value > 0 : 0;
}

uint32_t bb_flags(const bb_state *s) { return s->flags; }
int32_t bb_accu1(const bb_state *s) { return s->accu1; }
int32_t bb_accu2(const bb_state *s) { return s->accu2; }
uint64_t bb_ret_seq(const bb_state *s) { return s->ret_seq; }
uint32_t bb_ret_pc(const bb_state *s) { return s->ret_pc; }
int bb_ret_rlo(const bb_state *s) { return s->ret_rlo; }
int32_t bb_ret_accu1(const bb_state *s) { return s->ret_accu1; }
int32_t bb_ret_accu2(const bb_state *s) { return s->ret_accu2; }
uint32_t bb_overruns(const bb_state *s) { return s->overruns; }
uint64_t bb_executed(const bb_state *s) { return s->executed; }
uint64_t bb_byte_scans(const bb_state *s) { return s->byte_scans; }
int bb_rlo(const bb_state *s) { return s->rlo; }
int bb_fb(const bb_state *s) { return s->rlo; }

/* ------------------------------------------------------------------- main loop */

int bb_run_step(bb_state *s, bb_mode mode) {
  switch (mode) {
    case BB_MODE_SERIAL:
      return bb_serial_step(s);
    case BB_MODE_PARALLEL:
      hal_wait_dispatch(s->hal_ctx);       /* NEXT: this scan's latch clock */
      break;
    case BB_MODE_FREE:                     /* its own scans, back to back */
      break;
    default:
      return -1;
  }
  const uint64_t t0 = hal_now(s->hal_ctx);
  bb_run_scan(s);
  ++s->byte_scans;                         /* counted as it is announced: a host that
                                              stops in the SCAN_DONE write sees it */
  hal_bus_write(s->hal_ctx, BB_BUS_SCAN_DONE, 1);   /* the byte part of this scan is done */
  return (int)(hal_now(s->hal_ctx) - t0);
}

void bb_run(bb_state *s, bb_mode mode) {
  for (;;)
    if (bb_run_step(s, mode) < 0) return;
}
