"""Parallel mode's partitioning compiler (spec §2, §3 "Exchange instructions"; paper
§4.2-4.3, Fig. 10-15): one mixed program -> a bit part for the bit processor and a
byte part for the byte processor, with the transfer and synchronisation instructions
inserted, so that every scan's outputs, markers, words, timers and counters equal
serial mode's whatever the relative speed of the two processors.

The model
---------
In parallel mode each processor runs its own part from its own memory.  They meet only
in the exchange channels (`= FBY k` -> `READ FBY k`: a condition to the byte side;
`WRITE FBI k` -> `LD/A/O.. FBI k`: to the bit side; a read of an empty channel and a
write of a full one stall) and at END / END_B (the PIO/PII update waits for both).
Serial mode has one RLO; parallel mode has two condition flip-flops, F_b (bit side) and
F_B (byte side).  The compiler walks the program in order and keeps `loc`, the set of
sides whose flip-flop holds the serial RLO at this point: {bit, byte} at scan start
(both are 0 then: the bit RLO is reset, the firmware's bb_run_scan clears F_B).

The walk produces *rows*: one per instruction of either side, in program order; a
transfer is one row holding both halves (the write on one side, the read on the
other), a label one row valid on both sides.  The bit part is the rows' bit column,
the byte part the byte column.  Both sides execute the projections of the same path
(see "Jumps"), so each side meets the transfers in the same order; with a one-place
handshake channel per index (or one queue per direction) the i-th write of a channel
pairs with its i-th read, and since every transfer's two halves sit in one row, no
side can wait for something the other side only does later: no deadlock
(tests/test_partition.py checks both claims on random programs with random
interleavings).

Rules (source instruction -> rows):

* Bit instructions that read the RLO -- A AN O ON X XN, NOT, = S R, FP FN, JC JCN, the
  opening parentheses (they push it) and `)` (combines with it) -- need it on the bit
  side: if bit is not in loc, a transfer byte -> bit (byte `WRITE FBI k`, bit
  `LD FBI k`) goes before.  LD LDN SET CLR and the combining ones leave loc = {bit};
  = S R and the openers leave loc as it is (with bit added by the transfer).
* Byte instructions that read the RLO -- SD SS SP SF, R T n, CU CD, S C n, R C n --
  need it on the byte side: else a transfer bit -> byte (bit `= FBY k`, byte
  `READ FBY k`) goes before; they do not change it.  A plain compare sets it on the
  byte side (loc = {byte}).  `A cmp` / `O cmp`: with byte in loc they run as written
  (loc = {byte}); otherwise as in the paper's Fig. 13: the byte side runs the plain
  compare and `WRITE FBI k`, the bit side `A FBI k` / `O FBI k` (loc = {bit}) -- this
  spends no transfer of the RLO itself.  L, T and the arithmetic leave loc alone.
* Parentheses: the stack lives on the bit side; byte instructions inside are fine
  (an `A cmp` inside combines on the bit side as above; a `)` after a compare first
  fetches the RLO back).
* Jumps (bit JU/JC/JCN): the byte side must take the same path when the code the jump
  skips (forward: the rows between the jump and its label; backward: the rows of the
  loop body, label to jump) holds any byte-side row -- transfers the compiler put
  there included.  Then the jump is *mirrored*: JU gets a byte `JU_B`; JC/JCN get
  `JC_B`/`JCN_B` on F_B, after a bit -> byte transfer of the condition when byte is not
  in loc (when F_B already holds the RLO, e.g. right after a compare whose result was
  fetched for the jump, no transfer is needed: an improvement over "always transfer").
  Whether a jump needs mirroring depends on transfers inserted further on, so the walk
  is repeated with the set of mirrored jumps growing until nothing new is found (it
  only grows: a mirror adds byte rows, never removes the need for another).  A jump
  whose skipped code has no byte row is not mirrored: the byte side's sequence is the
  same whether it is taken or not.
* Join points: before a label that a jump targets (on the fall-through path, unless
  that path is dead after JU or END) and before every jump, the RLO is brought to the
  bit side; after such a label loc = {bit} (the paths may leave F_B differently).
  Labels are positions in both parts (`bit_labels`, `byte_labels`).
* Timer / counter status (spec §2: a bit-side read of `T n` / `C n` waits for every
  earlier instruction on that timer or counter).  "Earlier" is taken from the control
  flow graph: an update U may precede a read R in a scan when R is reachable from U
  (forward jumps may make this conservative, loops are covered -- plain program order
  would miss the read at the top of a loop that follows the update at its bottom in
  the previous iteration).  A byte -> bit transfer row between U and R already orders
  them (the bit side cannot pass its `.. FBI k` before the byte side has executed
  every row before `WRITE FBI k`, U included), so the walk keeps the set of timers /
  counters updated since the last byte -> bit row on some path (`unsynced_updates`:
  joined over the jumps to a label; at a loop head every updated one), and a read
  needs ordering only when its timer / counter is in that set *and* an update may
  precede it; symmetrically `unsynced_reads` (bit reads since the last bit -> byte
  row) for updates after reads.
  - A bit read of T n / C n that needs ordering gets a synchronising round trip
    right before it: the RLO is made valid on the byte side (bit -> byte transfer if
    needed), then byte `WRITE FBI k` + bit `LD FBI k`, which both carries the RLO
    back and holds the read until the byte side has passed every earlier update.
    When the read is LD/LDN (it overwrites the RLO anyway) the plain `WRITE FBI k` +
    `LD FBI k` suffices, whatever F_B holds.  (hardware_wait: a read with a sole
    update in the same straight stretch waits in hardware instead, bit 16.)
  - A byte update of T n / C n that a bit read of it may precede, with no bit -> byte
    row in between, must not overtake the read: a bit -> byte transfer goes right
    before the update even when the byte side already holds the RLO (when only the
    byte side holds it, it first goes to the bit side): the byte side cannot pass
    `READ FBY k` before the bit side has executed everything before `= FBY k`, the
    read included.
  `status_sync=False` drops both (the paper's Fig. 2 timers: the bit side never
  waits); that gives the paper's Fig. 13 exactly but is not serial-equivalent.
* REFRESH: one that becomes the bit part's first instruction executes in the PII
  latch clock; there it is a second latch that finds no edge since the scan start's
  (IR/IF := 0, input_unit.v), as serially after the byte work before it (with pins
  that do not move in between), so it needs no NOP in front.
* END anywhere: bit END and byte END_B in one row; the parts end with END / END_B.
* Channels: transfers are numbered round-robin per direction over `channels`
  (FBY 0, 1, 2, ... ; FBI 0, 1, ...), so a writer can run up to `channels` conditions
  ahead.  The queue exchange (one queue per direction) runs the same code: there the
  index is irrelevant, the order is what counts.
* The bit side's schedule (`schedule`, on by default with the status sync; off in
  the paper's / free-running mode): the rows fix the byte part and the order of the
  transfers, but the bit part's rungs may run in another order inside a basic block
  (cut at labels, jumps, END).  A rung starts at an RLO load (LD LDN SET CLR) at
  parenthesis depth 0 and runs to the next one: nothing before it is read by it,
  its RLO is dead at its end.  Two rungs keep their order when one writes a bit the
  other reads or writes; when both hold `= FBY` writes or both FBI reads (the i-th
  write pairs with the i-th read); when the first holds `= FBY` and the second
  waits for the byte side (an FBI read, a bit-16 status read) -- only writes to the
  byte side move up past reads from it; when either reads T n / C n and the other
  holds a transfer (the status ordering above counts on those positions); and
  around barriers (jumps, END, REFRESH, REFRESH Q, NOP, PI / PQ, QR / QF, a block's
  first rung when it continues an RLO, a block's last rung: the code after a label may
  continue its RLO).  So every rung computes what it computes serially, and
  serial-equivalence is kept.  Among the orders allowed, a list schedule driven by
  a timing model of the straight-line path (bit: 1 clock per instruction, byte: the
  cost table; `_Timing`) takes the rungs a pending `= FBY` depends on when the byte
  side would otherwise wait for it, else the first rung in program order that
  runs without waiting, else the one that finishes first: a rung that needs a
  compare result steps back and independent bit work runs meanwhile.  Each block's
  new order is played against the byte part with one place per direction (a queue
  of depth 1: every handshake channel count and queue depth waits on a subset of
  that) and kept only when it cannot deadlock; the whole order only when the model
  gives fewer clocks than program order.  Transfers are complete inside a block on
  both sides and the sides take the same path through the blocks, so the per-block
  check covers every path.  report_text() says how many rungs moved.
* Exchange instructions (READ, WRITE, operands FBI/FBY) in a mixed program are an
  error: the compiler inserts them.  A hand-partitioned program (`BIT:` / `BYTE:`
  sections, see bitbyte/lang/parser.py) is taken verbatim: its BYTE section's JU/JC/JCN
  become JU_B/JC_B/JCN_B, its END END_B, and each part gets a final END / END_B when
  missing.

API: partition(program, channels=4, *, config, status_sync, hardware_wait, schedule,
costs) -> Partition (bitbyte.lang.parts).  The stages, one module each: walk (the rows
and transfers), status (status syncs), schedule (the bit side's rung order), hand
(BIT:/BYTE: sections); then estimate (clocks per scan) and report (report_text,
side_by_side, part_listing).  bitbyte.asm.assemble_parallel writes the
`bitbyte asm --mode parallel` files.
"""
from __future__ import annotations

from bitbyte.compiler.hand import _hand_partitioned
from bitbyte.compiler.schedule import _schedule_bit_part
from bitbyte.compiler.walk import _Builder
from bitbyte.encoding import encoder
from bitbyte.lang.config import Config, DEFAULT
from bitbyte.lang.errors import SourceError
from bitbyte.lang.parts import BYTE_PROG_WORDS, Partition
from bitbyte.lang.program import Program


# --------------------------------------------------------------------------------------
# Entry point
# --------------------------------------------------------------------------------------

def partition(program: Program, channels: int = 4, *, config: Config = DEFAULT,
              status_sync: bool = True, hardware_wait: bool = True,
              schedule: bool | None = None, costs="paper",
              tc_path: str = "channel") -> Partition:
    """Split `program` into its bit and byte parts (module docstring) and encode them.

    channels: exchange channels per direction used round-robin (1..config.channels).
    status_sync=False: the paper's Fig. 2 timers (no waiting for T n / C n; not
    serial-equivalent).  hardware_wait: a status read that exactly one update
    precedes in the same straight-line stretch waits in hardware (instruction bit 16,
    docs/isa.md) instead of through a channel round trip.  schedule: reorder the bit
    part's rungs inside basic blocks to wait less (default: on with status_sync);
    costs: the byte cost table the schedule's timing model assumes (the order is valid
    for any).  Raises SourceError for what cannot be partitioned (an exchange
    instruction in a mixed program, a part too large) and ValueError for a bad channel
    count.  tc_path: "channel" (a timer's enable / a counter's input crosses as a
    condition, `= FBY k` / `READ FBY k`) or "status" (through the status buffer, Fig. 2,
    docs/exchange.md; with status_sync, i.e. in parallel mode, the byte side waits for
    this scan's write: the word's status-wait bit)."""
    if not 1 <= channels <= config.channels:
        raise ValueError(f"channels must be 1..{config.channels} (the build's exchange "
                         f"channels per direction), not {channels}")
    if any(ins.section for ins in program.instrs):
        part = _hand_partitioned(program, channels)
    else:
        mirrored: set[int] = set()
        while True:
            builder = _Builder(program, channels, status_sync, mirrored, hardware_wait,
                               tc_status=tc_path == "status")
            builder.build()
            more = builder.unmirrored_jumps_over_byte_rows()
            if not more:
                break
            mirrored |= more
        part = builder.result()
        if status_sync if schedule is None else schedule:
            _schedule_bit_part(part, costs)
    _encode(part, config)
    return part


# --------------------------------------------------------------------------------------
# Encoding
# --------------------------------------------------------------------------------------

def _encode(part: Partition, config: Config) -> None:
    for name, instrs, limit in (("bit", part.bit, config.prog_words),
                                ("byte", part.byte, BYTE_PROG_WORDS)):
        if len(instrs) > limit:
            culprit = instrs[limit]
            raise SourceError(part.program.path, culprit.line, culprit.col,
                              f"program too large: the {name} part has {len(instrs)} "
                              f"words, its program memory holds {limit}", culprit.source)
    part.bit_words = encoder.encode_bit_part(part.bit_program())
    byte_program = part.byte_program()
    part.pool = encoder.constant_pool(byte_program)
    part.byte_words = encoder.encode_byte_part(byte_program, part.pool)
