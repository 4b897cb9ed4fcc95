/*
 * costs.c — cost tables: clocks per instruction class, in bit-processor clocks
 * (spec §5). In serial mode a byte instruction takes exactly its table cost when its
 * bus accesses fit in it (interp.c pads with hal_spend()).
 *
 * "paper" (the default): the weights the seed paper uses for its Fig. 5 example, the
 * Siemens S7-315-2DP's 0.1 us per binary and 1 us per word instruction. With one bit
 * instruction = one clock, every word instruction (load, transfer, arithmetic,
 * compare, timer, counter) costs 10 clocks and a byte-side binary instruction (READ,
 * WRITE) 1.
 *
 * "c320": the paper's own bit-byte CPU, whose byte processor is an 80C320, expressed
 * in the same unit (one bit instruction = one clock = 0.1 us, as in "paper"). The only
 * measurement the paper gives is Table 1, a part of a pickling-line program:
 *     80C320 - serial mode: 1050 bit and 280 byte instructions in 1.7 ms.
 * Charging the 1050 bit instructions 0.1 us each (105 us) leaves 1595 us for 280 byte
 * instructions: 5.70 us = 57 clocks per word instruction on average. Table 1 gives no
 * split by kind, so every word class gets that average (a table of measured per-class
 * costs would only change the numbers below). It does not give the byte side's binary
 * instructions either; we keep the paper's 10:1 word/binary ratio: 57 / 10 -> 6.
 * (The parallel-mode row, 850 + 140 in 1.1 ms, merges several byte instructions into
 * one dispatch, so it is not a per-instruction figure and is not used.)
 *
 * Both tables charge 1 clock for an illegal instruction (the firmware only flags it).
 *
 * The byte program's jumps JU_B / JC_B / JCN_B are binary instructions (one bit-side
 * instruction's worth of work: test F_B, load the PC), the same clocks whether taken
 * or not: the byte side has no pipeline to refill. END_B costs 0 in every table: it is
 * not work but the synchronisation point of parallel mode, where the byte part of a
 * scan ends and the byte processor waits for the next scan.
 */
#include <string.h>

#include "byteproc.h"

/* bb_cost_tables[] (the first is the default) and bb_class_names[]: generated from
 * bitbyte/lang/definition.toml, where the numbers above are written once. */
#include "cost_tables.h"

#define BB_NUM_COST_TABLES (sizeof bb_cost_tables / sizeof bb_cost_tables[0])

const bb_costs *bb_cost_table(const char *name) {
  if (name == NULL) return &bb_cost_tables[0];
  for (size_t i = 0; i < BB_NUM_COST_TABLES; ++i)
    if (strcmp(name, bb_cost_tables[i].name) == 0) return &bb_cost_tables[i];
  return NULL;
}

uint32_t bb_cost(const bb_state *s, int cls) {
  if (cls < 0 || cls >= BB_NUM_CLASSES) return 0;
  const bb_costs *t = (s != NULL && s->costs != NULL) ? s->costs : &bb_cost_tables[0];
  return t->clocks[cls];
}

const char *bb_class_name(int cls) {
  return (cls >= 0 && cls < BB_NUM_CLASSES) ? bb_class_names[cls] : "?";
}

int bb_set_costs(bb_state *s, const char *name) {
  const bb_costs *t = bb_cost_table(name);
  if (t == NULL) return -1;
  s->costs = t;
  return 0;
}
