/*
 * byteproc.h — the byte processor's firmware: public API and state.
 *
 * The byte processor executes the word instructions of docs/isa.md ("Byte
 * instructions") with the semantics of the spec, section 3, and reaches the FPGA part
 * only through hal.h. Nothing here allocates memory except bb_new().
 *
 * Two ways to run an instruction:
 *  - bb_serial_step(): serial mode, the whole dispatch protocol (wait for NEXT, read
 *    the instruction and its context, execute, pad to the table cost, write DONE);
 *  - bb_exec() / bb_step(): the bare semantics, for parallel mode, where the byte
 *    processor runs its own program and keeps F_B itself.
 */
#ifndef BB_BYTEPROC_H
#define BB_BYTEPROC_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Sizes (spec §3 defaults). */
#define BB_NUM_MW        256u
#define BB_NUM_TIMERS    64u
#define BB_NUM_COUNTERS  64u
#define BB_NUM_IW        16u
#define BB_NUM_QW        16u
#define BB_NUM_CHANNELS  8u      /* FBY/FBI k: the bus decodes 0..7 */
#define BB_POOL_WORDS    1024u   /* constant pool (opcode 0x81) */
#define BB_COUNTER_MAX   32767

/* Opcodes (docs/isa.md, "Byte instructions"). */
#define BB_OP_L_IMM      0x80u
#define BB_OP_L_POOL     0x81u
#define BB_OP_L_WORD     0x82u
#define BB_OP_T_WORD     0x83u
#define BB_OP_ADD        0x88u
#define BB_OP_SUB        0x89u
#define BB_OP_MUL        0x8Au
#define BB_OP_DIV        0x8Bu
#define BB_OP_MOD        0x8Cu
#define BB_OP_CMP        0x90u   /* + c: RLO := cmp            */
#define BB_OP_A_CMP      0x98u   /* + c: RLO := RLO AND cmp    */
#define BB_OP_O_CMP      0xA0u   /* + c: RLO := RLO OR  cmp    */
#define BB_OP_SD         0xB0u
#define BB_OP_SS         0xB1u
#define BB_OP_SP         0xB2u
#define BB_OP_SF         0xB3u
#define BB_OP_RT         0xB4u
#define BB_OP_CU         0xB8u
#define BB_OP_CD         0xB9u
#define BB_OP_SC         0xBAu
#define BB_OP_RC         0xBBu
#define BB_OP_READ       0xC0u
#define BB_OP_WRITE      0xC1u

/* Compare codes c. */
#define BB_CMP_EQ 0
#define BB_CMP_NE 1
#define BB_CMP_GT 2
#define BB_CMP_LT 3
#define BB_CMP_GE 4
#define BB_CMP_LE 5

/* Operand areas (bits 15..12 of the word / timer / counter / channel forms). */
#define BB_AREA_T   7u
#define BB_AREA_C   8u
#define BB_AREA_FB  9u
#define BB_AREA_IW  10u
#define BB_AREA_QW  11u
#define BB_AREA_MW  12u

/* Instruction word helpers. */
#define BB_INSTR(op, area, index) \
  (((uint32_t)(op) << 24) | (((uint32_t)(area) & 0xFu) << 12) | ((uint32_t)(index) & 0xFFFu))
#define BB_INSTR_IMM(op, imm24) (((uint32_t)(op) << 24) | ((uint32_t)(imm24) & 0xFFFFFFu))

/* Sticky flags (bb_flags(), also mirrored to the bus register BYTE_FLAGS). */
#define BB_FLAG_ARITH    0x1u    /* /I or MOD by 0 */
#define BB_FLAG_ILLEGAL  0x2u    /* unknown opcode or operand */

/* Cost classes: every instruction falls in one; a cost table gives each its clocks. */
typedef enum {
  BB_CL_LOAD = 0,   /* L constant / word / T / C */
  BB_CL_TRANSFER,   /* T MW / QW */
  BB_CL_ARITH,      /* +I -I */
  BB_CL_MULDIV,     /* *I /I MOD */
  BB_CL_COMPARE,    /* ==I ... , A cmp, O cmp */
  BB_CL_TIMER,      /* SD SS SP SF, R T n */
  BB_CL_COUNTER,    /* CU CD, S C n, R C n */
  BB_CL_BINARY,     /* READ FBY k, WRITE FBI k */
  BB_CL_ILLEGAL,    /* anything else */
  BB_NUM_CLASSES
} bb_class;

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
  uint32_t   last_scan;      /* serial: scan number of the last dispatch ... */
  int        scan_seen;      /* ... valid once one was seen */
  uint32_t   overruns;       /* instructions that took more clocks than their cost */
  uint64_t   executed;       /* instructions executed */
  uint32_t   last_instr;     /* the last instruction, its class and its clocks */
  int        last_class;
  uint32_t   last_clocks;
} bb_state;

/* --- set-up ------------------------------------------------------------------------ */

/* Reset everything to the spec's state after reset (all 0) and select a cost table
 * (NULL: the default, "paper"). No bus access. */
void bb_init(bb_state *s, const bb_costs *costs);

/* Copy the constant pool (PROG.pool.hex); at most BB_POOL_WORDS words are kept. */
void bb_load_pool(bb_state *s, const uint32_t *words, unsigned n);

/* Start of a scan: ACCU1 := ACCU2 := 0 (parallel mode; serial mode does it itself). */
void bb_scan_start(bb_state *s);

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
 *   read DISPATCH_INSTR (t0), DISPATCH_CTX (t0+1); new scan number -> ACCUs := 0;
 *   execute (its own bus accesses from t0+2; a timer reads DISPATCH_MS, L IW n reads
 *   DISPATCH_IW: the port's snapshot of the first clock); hal_spend(cost - used - 1)
 *   if positive;
 *   write DONE = RLO | rlo_written << 1 (in the last clock of the cost).
 * Returns the clocks the instruction took (= its cost unless it overran). */
int bb_serial_step(bb_state *s);

/* The instruction's semantics with its own bus accesses (TIME_MS for SD/SS/SP/SF,
 * IW/QW, all read live; TC_BIT, BYTE_FLAGS, channels), no dispatch protocol and no
 * padding.
 * *rlo is F_B in and out (NULL: s->rlo). Returns the cost class (bb_class). */
int bb_exec(bb_state *s, uint32_t instr, int *rlo);

/* bb_exec() padded to the table cost with hal_spend(): parallel mode's step. Returns
 * the clocks taken (more than the cost only if the bus stalled: counted in overruns). */
int bb_step(bb_state *s, uint32_t instr, int *rlo);

/* --- trace accessors (no bus access) ------------------------------------------------ */

int16_t  bb_mw(const bb_state *s, unsigned n);
int32_t  bb_timer_elapsed(const bb_state *s, unsigned n);
int      bb_timer_status(const bb_state *s, unsigned n);
int      bb_timer_running(const bb_state *s, unsigned n);
int      bb_counter_value(const bb_state *s, unsigned n);
int      bb_counter_status(const bb_state *s, unsigned n);
uint32_t bb_flags(const bb_state *s);
int32_t  bb_accu1(const bb_state *s);
int32_t  bb_accu2(const bb_state *s);
uint32_t bb_overruns(const bb_state *s);
uint64_t bb_executed(const bb_state *s);
int      bb_rlo(const bb_state *s);

#ifdef __cplusplus
}
#endif

#endif /* BB_BYTEPROC_H */
