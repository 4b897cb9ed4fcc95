/*
 * byteproc.h — the byte processor's firmware: public API and state.
 *
 * The byte processor executes the word instructions of docs/isa.md ("Byte
 * instructions") with the semantics of the spec, section 3, and reaches the FPGA part
 * only through hal.h. Nothing here allocates memory except bb_new().
 *
 * Three ways to run instructions:
 *  - bb_serial_step(): serial mode, the whole dispatch protocol (wait for NEXT, read
 *    the instruction and its context, execute, pad to the table cost, write DONE);
 *  - bb_exec() / bb_step(): the bare semantics, for parallel mode, where the byte
 *    processor runs its own program and keeps F_B itself;
 *  - bb_load_program() / bb_run_scan(): parallel mode's byte program (the byte part of
 *    a partitioned program, paper Fig. 11-13), one scan at a time, with the byte-side
 *    jumps JU_B / JC_B / JCN_B on F_B and END_B.
 */
#ifndef BB_BYTEPROC_H
#define BB_BYTEPROC_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Sizes, opcodes, compare codes, areas, flags and the cost classes (enum bb_class):
 * generated from bitbyte/lang/definition.toml. */
#include "bb_isa.h"

/* Instruction word helpers. */
#define BB_INSTR(op, area, index) \
  (((uint32_t)(op) << BB_OPCODE_SHIFT) | (((uint32_t)(area) & BB_AREA_MASK) << BB_AREA_SHIFT) \
   | ((uint32_t)(index) & BB_INDEX_MASK))
#define BB_INSTR_IMM(op, imm24) \
  (((uint32_t)(op) << BB_OPCODE_SHIFT) | ((uint32_t)(imm24) & BB_IMM_MASK))
#define BB_INSTR_JUMP(op, target) \
  (((uint32_t)(op) << BB_OPCODE_SHIFT) | ((uint32_t)(target) & BB_TARGET_MASK))

/* A cost table: clocks per class, in bit-processor clocks. */
typedef struct {
  const char *name;
  uint32_t clocks[BB_NUM_CLASSES];
} bb_costs;

/* One timer: everything SD/SS/SP/SF/R T n share (spec §3 "Timers"). */
typedef struct {
  uint32_t start;     /* now at the last start, in ms */
  int32_t  elapsed;   /* what L T n loads: min(d, preset) while running, else 0 */
  uint8_t  status;    /* what T n reads (also written to TC_BIT) */
  uint8_t  running;
  uint8_t  edge;      /* enable at the last SD/SS/SP/SF */
} bb_timer;

/* One counter: value and the three edge memories. */
typedef struct {
  uint16_t value;     /* 0..32767 */
  uint8_t  cu_edge, cd_edge, s_edge;
} bb_counter;

/* The whole state; plain data, so it can live in static memory. Fields are public for
 * the tests and the harnesses; use the accessors from Python (ctypes). */
typedef struct bb_state {
  int32_t    accu1, accu2;
  int16_t    mw[BB_NUM_MW];
  bb_timer   timer[BB_NUM_TIMERS];
  bb_counter counter[BB_NUM_COUNTERS];
  uint32_t   pool[BB_POOL_WORDS];
  uint32_t   pool_len;
  uint32_t   flags;          /* BB_FLAG_*, sticky */
  const bb_costs *costs;
  int        rlo;            /* F_B: used by bb_exec(rlo == NULL); last RLO in serial */
  int        rlo_written;    /* did the last instruction write the RLO (compare, READ) */
  uint32_t   overruns;       /* instructions that took more clocks than their cost */
  uint64_t   executed;       /* instructions executed */
  uint32_t   last_instr;     /* the last instruction, its class and its clocks */
  int        last_class;
  uint32_t   last_clocks;
  /* parallel mode: the byte program (bb_load_program, bb_run_scan) */
  uint32_t   prog[BB_PROG_WORDS];
  uint32_t   prog_len;
  uint32_t   pc;             /* address of the next instruction of the byte program */
  int        jumped;         /* the last instruction was a taken jump */
  uint32_t   max_steps;      /* instructions a bb_run_scan may execute, END_B included */
  uint32_t   scan_steps;     /* instructions the last bb_run_scan executed */
  int        mw_on_bus;      /* MW n lives in the FPGA at bus address MW(n) (plant core) */
  uint64_t   byte_scans;     /* parallel / free-running: byte scans reported (SCAN_DONE) */
  /* parallel / free-running: the byte program's last completed instruction, as it was
   * when it completed (a host's block status: bitbyte run --status); END_B not noted */
  uint64_t   ret_seq;        /* instructions completed so far */
  uint32_t   ret_pc;         /* its address in the byte program */
  int        ret_rlo;        /* F_B after it */
  int32_t    ret_accu1, ret_accu2;
  void      *hal_ctx;        /* the first argument of every HAL call (bb_set_hal_ctx) */
  /* S7's status bits CC 1 (bit 1) and CC 0 (bit 0) as the last instruction that sets
   * them left them (arithmetic, compares, word logic, shifts; awlsim's rules), read by
   * the status-bit instructions (BB_OP_STATUS); 0 at a scan's start */
  unsigned   cc;
} bb_state;


/* --- set-up ------------------------------------------------------------------------ */

/* Reset everything to the spec's state after reset (all 0, no byte program,
 * max_steps = BB_MAX_STEPS_DEFAULT, HAL context NULL) and select a cost table (NULL:
 * the default, "paper"). No bus access. */
void bb_init(bb_state *s, const bb_costs *costs);

/* The HAL context of this byte processor: every HAL call the firmware makes for state
 * `s` passes s->hal_ctx as its first argument (hal.h), so a host that runs several
 * byte processors in one process tells their calls apart without globals. Set it
 * after bb_init() / bb_new(), before the first call that can reach the bus. */
void  bb_set_hal_ctx(bb_state *s, void *ctx);
void *bb_hal_ctx(const bb_state *s);

/* Copy the constant pool (PROG.pool.hex); at most BB_POOL_WORDS words are kept. */
void bb_load_pool(bb_state *s, const uint32_t *words, unsigned n);

/* Start of a scan: ACCU1 := ACCU2 := 0 (parallel mode; serial mode does it itself). */
void bb_scan_start(bb_state *s);

/* Copy the byte program (parallel mode: the byte part of a partitioned program),
 * address 0 first. Returns 0, or -1 (nothing changed) if n > BB_PROG_WORDS or words is
 * NULL with n > 0. The program lives in the state (no allocation); PC := 0. */
int bb_load_program(bb_state *s, const uint32_t *words, unsigned n);

/* For the ctypes side: the only allocation. bb_new() returns an initialised state with
 * the default table, or NULL. */
bb_state *bb_new(void);
void bb_free(bb_state *s);
/* Select another table later (NULL: default). Returns 0, or -1 for an unknown name. */
int bb_set_costs(bb_state *s, const char *name);

/* --- cost tables (costs.c) ------------------------------------------------------------- */

/* "paper" (default, also for NULL) or "c320"; NULL for an unknown name. */
const bb_costs *bb_cost_table(const char *name);
/* Clocks of class `cls` in the state's table (0 for a bad class). */
uint32_t bb_cost(const bb_state *s, int cls);
/* The class of an instruction word without executing it (a pool index is checked only
 * by execution). Pure: no state, no bus. */
int bb_classify(uint32_t instr);
const char *bb_class_name(int cls);

/* --- execution ----------------------------------------------------------------------- */

/* Serial mode, one dispatched instruction (the sequence is in README.md):
 *   hal_wait_dispatch(); t0 = hal_now();
 *   read DISPATCH_INSTR (t0), DISPATCH_CTX (t0+1); its FIRST bit -> ACCUs := 0;
 *   execute (its own bus accesses from t0+2; a timer reads DISPATCH_MS, L IW n reads
 *   DISPATCH_IW: the port's snapshot of the first clock; a timer with the at-latch
 *   bit LATCH_MS, the scan's latch time); hal_spend(cost - used - 1)
 *   if positive;
 *   write DONE = RLO | rlo_written << 1 (in the last clock of the cost).
 * JU_B / JC_B / JCN_B / END_B belong to a byte program only: dispatched, they are
 * illegal instructions (flag, the illegal class's cost).
 * Returns the clocks the instruction took (= its cost unless it overran). */
int bb_serial_step(bb_state *s);

/* The instruction's semantics with its own bus accesses (TIME_MS for SD/SS/SP/SF, or
 * LATCH_MS with the at-latch bit,
 * IW/QW, all read live; TC_BIT, BYTE_FLAGS, channels), no dispatch protocol and no
 * padding.
 * *rlo is F_B in and out (NULL: s->rlo). Returns the cost class (bb_class).
 * A jump sets s->pc := target when taken (s->jumped says whether it was); a target
 * past the loaded program (> prog_len) is illegal. END_B does nothing here (class
 * BB_CL_END): bb_run_scan() stops on it. */
int bb_exec(bb_state *s, uint32_t instr, int *rlo);

/* bb_exec() padded to the table cost with hal_spend(): parallel mode's step. Returns
 * the clocks taken (more than the cost only if the bus stalled: counted in overruns). */
int bb_step(bb_state *s, uint32_t instr, int *rlo);

/* Parallel mode, one scan of the byte program (README.md, "Parallel mode"):
 *   ACCU1 := ACCU2 := 0 and F_B := 0 (every scan starts from the same state, as serial
 *   mode's ACCUs and the bit side's RLO do); PC := 0;
 *   then bb_step() instruction by instruction (each takes exactly its table cost when
 *   its bus accesses fit: jumps 1 clock with "paper", taken or not, END_B 0) until
 *   END_B is executed or the PC reaches the end of the program (counts as END_B).
 * A jump to an address past the program (target > program length) is illegal (flag,
 * no jump); a jump to exactly the program length ends the scan.
 * More than s->max_steps instructions (END_B included) without reaching the end:
 * sticky BB_FLAG_RUNAWAY (one BYTE_FLAGS write) and return.
 * Returns the clocks the scan took. */
int bb_run_scan(bb_state *s);

/* The firmware's main loop, the same for every host (the hosts implement only hal.h).
 * bb_run_step() is one turn of it:
 *   serial    bb_serial_step(): one dispatched instruction;
 *   parallel  hal_wait_dispatch() (NEXT = the scan's latch clock), bb_run_scan(), then
 *             SCAN_DONE: the bit side's END may complete;
 *   free      bb_run_scan(), then SCAN_DONE, without waiting for the bit side.
 * The parallel and free turns count s->byte_scans after their SCAN_DONE write.
 * Returns the clocks of the turn's work (the wait for NEXT not counted), or -1 for an
 * unknown mode. bb_run() turns forever: a host stops it from inside a HAL call
 * (longjmp, a coroutine it no longer resumes, a thread it leaves blocked). */
int  bb_run_step(bb_state *s, bb_mode mode);
void bb_run(bb_state *s, bb_mode mode);

/* A core of a multi-core plant (docs/multicore.md) keeps its word markers in the FPGA,
 * next to the copy engine that moves shared words: with on != 0, L MW n / T MW n are
 * one bus access of BB_BUS_MW(n) each (the mw[] array is then unused; bb_mw() reads
 * it, so a plant's harness reads MW from the FPGA). Off after bb_init(). */
void bb_set_mw_bus(bb_state *s, int on);

/* --- trace accessors (no bus access) ------------------------------------------------ */

int16_t  bb_mw(const bb_state *s, unsigned n);
int32_t  bb_timer_elapsed(const bb_state *s, unsigned n);
int      bb_timer_status(const bb_state *s, unsigned n);
int      bb_timer_running(const bb_state *s, unsigned n);
int      bb_counter_value(const bb_state *s, unsigned n);
int      bb_counter_status(const bb_state *s, unsigned n);
uint32_t bb_flags(const bb_state *s);   /* BB_FLAG_ARITH | ILLEGAL | RUNAWAY */
int32_t  bb_accu1(const bb_state *s);
int32_t  bb_accu2(const bb_state *s);
/* The byte program's last completed instruction (parallel / free-running): how many
 * have completed, its address, F_B and the accumulators right after it. */
uint64_t bb_ret_seq(const bb_state *s);
uint32_t bb_ret_pc(const bb_state *s);
int      bb_ret_rlo(const bb_state *s);
int32_t  bb_ret_accu1(const bb_state *s);
int32_t  bb_ret_accu2(const bb_state *s);
uint32_t bb_overruns(const bb_state *s);
uint64_t bb_executed(const bb_state *s);
uint64_t bb_byte_scans(const bb_state *s);
int      bb_rlo(const bb_state *s);
int      bb_fb(const bb_state *s);     /* F_B, the byte side's RLO (= bb_rlo) */

#ifdef __cplusplus
}
#endif

#endif /* BB_BYTEPROC_H */
