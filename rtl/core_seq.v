`default_nettype none
`include "bit_isa.vh"
// Core sequencer of a plant core (docs/multicore.md): when a scan starts, the
// precycle, the scan itself and the postcycle, each copy run by the copy engine
// (copy_engine.v) that moves the shared variables (seed 000 Fig. 4: read at scan
// start, write at scan end); and the lock handling around those copies (Fig. 8).
//
// Scan k starts at nominal_k = k * period (a common time base, time_i); a core that
// is still busy then starts right after and counts an overrun. A scan is:
//   precycle   take the lock (semaphore), copy shared -> local (M bits, MW words)
//   scan       pulse the CPU's RUN input once; the CPU latches, executes, ends
//   postcycle  take the lock (semaphore), copy local -> shared, publish (ping-pong)
// Protection (protect_i, `PROTECTION_*): semaphore — every copy holds the hardware lock; a
// precycle that would wait past the point where the scan can still end within its
// period is skipped (the core runs on its old local copies, sticky copy_fail); a
// postcycle always waits. Ping-pong — a writer writes the buffer readers do not
// read and flips it at the end of its postcycle; a reader reads, for each writer,
// the buffer published when its precycle began; if that writer starts overwriting
// the buffer before the reader has read all it reads from it (a very fast writer), the
// read could be torn: copy_fail is set. None — no lock (shows tearing).
//
// A copy list of n entries takes n + 3 clocks: n + 2 in the engine (fill, drain) and
// the clock that releases the lock or publishes the ping-pong buffer, with no access.
// The copy plan's format: copy_engine.v.
module core_seq #(
  parameter integer Cores       = 2,     // cores of the plant (writer ids)
  parameter integer PlanWords   = 1024,  // copy-plan entries (power of two)
  parameter integer SharedWords = 4096,  // shared 32-bit words SH0.. (power of two)
  parameter integer MarkerBits  = 2048,  // the core's M bits
  parameter integer MwWords     = 256    // the core's MW words
) (
  input  wire                          clk_i,
  input  wire                          rst_ni,
  // copy plan load (while stopped)
  input  wire                          plan_we_i,
  input  wire [$clog2(PlanWords)-1:0]  plan_waddr_i,
  input  wire [31:0]                   plan_wdata_i,
  // configuration, constant while running
  input  wire [63:0]                   period_i,     // between scan starts, in 1/1000 clock
                                                      // (period_us x clock kHz); 0: back to back
  input  wire [$clog2(PlanWords):0]    pre_len_i,    // precycle entries (from plan address 0)
  input  wire [$clog2(PlanWords)-1:0]  post_base_i,  // first postcycle entry
  input  wire [$clog2(PlanWords):0]    post_len_i,   // postcycle entries
  input  wire [1:0]                    protect_i,    // `PROTECTION_* (bit_isa.vh)
  // time base and plant RUN
  input  wire                          run_i,        // the plant runs (all cores ready)
  input  wire [63:0]                   time_i,       // clocks since the plant started
  // the core's CPU
  output wire                          cpu_run_o,    // start one scan (the CPU is idle)
  input  wire                          cpu_ready_i,  // idle between scans
  input  wire                          cpu_scan_done_i,
  input  wire [31:0]                   cpu_scan_cycles_i,  // the last scan's clocks
  // hardware semaphore (hsem.v)
  output wire                          lock_req_o,
  output wire                          release_o,
  input  wire                          grant_i,
  // shared memory (shared_mem.v): read port, write port, ping-pong selects
  output wire                          sh_re_o,
  output wire [$clog2(SharedWords):0]  sh_raddr_o,   // {buffer, word}
  output wire [$clog2(Cores)-1:0]      sh_rbank_o,   // the word's writer: its bank
  input  wire [31:0]                   sh_rdata_i,   // the word read the clock before
  output wire                          sh_we_o,
  output wire [$clog2(SharedWords):0]  sh_waddr_o,
  output wire [31:0]                   sh_wdata_o,
  input  wire [Cores-1:0]              sh_sel_i,     // per writer: the buffer to read
  input  wire [Cores-1:0]              sh_posting_i, // per core: writes shared memory now
  output wire                          sh_flip_o,    // ping-pong: publish this core's buffer
  // local memories: M bits (bit_proc's copy port), MW words (plc_core's word RAM)
  output wire                          copy_en_o,    // the sequencer owns both ports
  output wire                          m_we_o,
  output wire [$clog2(MarkerBits)-1:0] m_addr_o,
  output wire                          m_wdata_o,
  input  wire                          m_rdata_i,
  output wire                          w_we_o,
  output wire [$clog2(MwWords)-1:0]    w_addr_o,
  output wire [15:0]                   w_wdata_o,
  input  wire [15:0]                   w_rdata_i,
  // status of the last completed scan (valid with cycle_done_o and after)
  output reg                           cycle_done_o,  // a postcycle ended at this edge
  output reg  [31:0]                   pre_clocks_o,  // precycle incl. waits
  output reg  [31:0]                   post_clocks_o, // postcycle incl. waits
  output reg  [31:0]                   sem_wait_o,    // clocks spent waiting for the lock
  output reg                           overrun_o,     // this scan started late
  output reg                           copy_fail_o,   // sticky: a precycle was skipped,
                                                      // or overtaken (ping-pong)
  output reg  [31:0]                   overruns_o,    // scans that started late
  output reg  [31:0]                   skips_o        // precycles skipped
);
  localparam integer PaW = $clog2(PlanWords);
  // (the sizes are the copy engine's; copy_engine.v checks their ranges)

  localparam [1:0] ProtSem  = `PROTECTION_SEMAPHORE;
  localparam [1:0] ProtPing = `PROTECTION_PINGPONG;

  localparam [2:0] StWait     = 3'd0;  // until the nominal start
  localparam [2:0] StPreLock  = 3'd1;
  localparam [2:0] StPreCopy  = 3'd2;
  localparam [2:0] StRunStart = 3'd3;  // RUN pulse; the CPU latches in the next clock
  localparam [2:0] StScan     = 3'd4;
  localparam [2:0] StPostLock = 3'd5;
  localparam [2:0] StPostCopy = 3'd6;

  reg [2:0]  state_q;
  reg [63:0] nominal_q;                // nominal start of the next / current scan, in
                                       // 1/1000 clock: scan k at k * period exactly
  reg        started_q;                // scan 0 has been scheduled

  // ---------------------------------------------------------------- timing
  // Fig. 8: waiting is worth it only while the copies and the scan still fit.
  wire [63:0] need = {{(63-PaW){1'b0}}, pre_len_i} + {{(63-PaW){1'b0}}, post_len_i} +
                     {32'd0, cpu_scan_cycles_i} + 64'd6;
  // Times in 1/1000 clock: a period need not be a whole number of clocks (it is
  // period_us x clock kHz), so scan k starts in the first clock at or after k * period
  // without drifting.
  wire [63:0] now_m = time_i * 64'd1000;
  wire give_up = (period_i != 64'd0) &&
                 ((time_i + need) * 64'd1000 > nominal_q + period_i);
  // late: not in the first clock at or after the nominal start (period 0 has none)
  wire       late = started_q && (period_i != 64'd0) && (now_m >= nominal_q + 64'd1000);

  // ---------------------------------------------------------------- the copies
  wire copying = (state_q == StPreCopy) || (state_q == StPostCopy);
  wire copy_done, list_empty, post, overtaken;
  // a scan begins (the precycle's list) / the scan ended (the postcycle's)
  wire begin_pre  = (state_q == StWait) && run_i && (now_m >= nominal_q || !started_q);
  wire begin_post = (state_q == StScan) && cpu_scan_done_i;
`ifdef FORMAL
  wire f_started, f_local_rd;
  wire [PaW+2:0] f_runs;
  wire [PaW:0]   f_len;
`endif

  copy_engine #(
    .Cores      (Cores),
    .PlanWords  (PlanWords),
    .SharedWords(SharedWords),
    .MarkerBits (MarkerBits),
    .MwWords    (MwWords)
  ) u_copy (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .plan_we_i   (plan_we_i),
    .plan_waddr_i(plan_waddr_i),
    .plan_wdata_i(plan_wdata_i),
    .pre_len_i   (pre_len_i),
    .post_base_i (post_base_i),
    .post_len_i  (post_len_i),
    .ping_i      (protect_i == ProtPing),
    .load_pre_i  (begin_pre),
    .load_post_i (begin_post),
    .run_i       (copying),
    .done_o      (copy_done),
    .empty_o     (list_empty),
    .post_o      (post),
    .overtaken_o (overtaken),
    .sh_re_o     (sh_re_o),
    .sh_raddr_o  (sh_raddr_o),
    .sh_rbank_o  (sh_rbank_o),
    .sh_rdata_i  (sh_rdata_i),
    .sh_we_o     (sh_we_o),
    .sh_waddr_o  (sh_waddr_o),
    .sh_wdata_o  (sh_wdata_o),
    .sh_sel_i    (sh_sel_i),
    .sh_posting_i(sh_posting_i),
    .m_we_o      (m_we_o),
    .m_addr_o    (m_addr_o),
    .m_wdata_o   (m_wdata_o),
    .m_rdata_i   (m_rdata_i),
    .w_we_o      (w_we_o),
    .w_addr_o    (w_addr_o),
    .w_wdata_o   (w_wdata_o),
    .w_rdata_i   (w_rdata_i)
`ifdef FORMAL
    ,
    .f_started_o (f_started),
    .f_local_rd_o(f_local_rd),
    .f_runs_o    (f_runs),
    .f_len_o     (f_len)
`endif
  );

  // The engine owns the local ports only in the copy states (nothing executes then).
  assign copy_en_o = copying;

  // ---------------------------------------------------------------- control
  wire lock_wanted = (protect_i == ProtSem);
  assign lock_req_o = (state_q == StPreLock) || (state_q == StPostLock);
  assign release_o  = lock_wanted && copy_done && !list_empty;  // an empty list took no lock
  assign sh_flip_o  = (protect_i == ProtPing) && copy_done && post;
  assign cpu_run_o  = (state_q == StRunStart);

  reg [31:0] pre_cnt_q, post_cnt_q, wait_cnt_q;
  wire       in_pre  = (state_q == StPreLock) || (state_q == StPreCopy) ||
                       (state_q == StRunStart);
  wire       in_post = (state_q == StPostLock) || (state_q == StPostCopy) ||
                       ((state_q == StScan) && cpu_scan_done_i);
  wire       waiting = lock_req_o && !grant_i;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q       <= StWait;
      nominal_q     <= 64'd0;
      started_q     <= 1'b0;
      pre_cnt_q     <= 32'd0;
      post_cnt_q    <= 32'd0;
      wait_cnt_q    <= 32'd0;
      cycle_done_o  <= 1'b0;
      pre_clocks_o  <= 32'd0;
      post_clocks_o <= 32'd0;
      sem_wait_o    <= 32'd0;
      overrun_o     <= 1'b0;
      copy_fail_o   <= 1'b0;
      overruns_o    <= 32'd0;
      skips_o       <= 32'd0;
    end else begin
      cycle_done_o <= 1'b0;
      if (in_pre)  pre_cnt_q  <= pre_cnt_q + 32'd1;
      if (in_post) post_cnt_q <= post_cnt_q + 32'd1;
      if (waiting) wait_cnt_q <= wait_cnt_q + 32'd1;
      if (overtaken) copy_fail_o <= 1'b1;

      case (state_q)
        StWait: if (begin_pre) begin
          // scan 0 starts at time 0; later ones at their nominal start or, late, now
          // late: after its nominal start (back to back, period 0, has none)
          overrun_o  <= late;
          if (late) overruns_o <= overruns_o + 32'd1;
          if (!started_q || period_i == 64'd0) nominal_q <= now_m;
          started_q  <= 1'b1;
          pre_cnt_q  <= 32'd1;           // the precycle begins in this clock
          post_cnt_q <= 32'd0;
          wait_cnt_q <= 32'd0;
          state_q    <= (lock_wanted && pre_len_i != 0) ? StPreLock : StPreCopy;
        end
        StPreLock:
          if (grant_i) state_q <= StPreCopy;
          else if (give_up) begin
            copy_fail_o <= 1'b1;
            skips_o     <= skips_o + 32'd1;
            state_q     <= StRunStart;
          end
        StPreCopy: if (copy_done) state_q <= StRunStart;
        StRunStart: if (cpu_ready_i) state_q <= StScan;
        StScan: if (begin_post)
          state_q <= (lock_wanted && post_len_i != 0) ? StPostLock : StPostCopy;
        StPostLock: if (grant_i) state_q <= StPostCopy;
        StPostCopy: if (copy_done) begin
          state_q       <= StWait;
          nominal_q     <= nominal_q + period_i;
          cycle_done_o  <= 1'b1;
          pre_clocks_o  <= pre_cnt_q;
          post_clocks_o <= post_cnt_q + 32'd1;
          sem_wait_o    <= wait_cnt_q;
        end
        default: state_q <= StWait;
      endcase
    end
  end

`ifdef FORMAL
  // formal/core_seq.sby: the sequencer's protocol with the semaphore, the CPU and the
  // local memories, by k-induction (small parameters; the plan RAM and every input
  // of the CPU, the shared memory and the time base are free, within the assumptions).
  // The copy engine's own guarantees are in copy_engine.v, proved together with these.
  reg f_past_valid = 1'b0;
  always @(posedge clk_i) f_past_valid <= 1'b1;
  always @(*) if (!f_past_valid) assume (!rst_ni);

  // ---- the environment
  // the configuration is constant while running (it may change only under reset)
  always @(posedge clk_i) if (f_past_valid && rst_ni) begin
    assume ($stable(protect_i));
    assume ($stable(period_i));
    assume ($stable(pre_len_i));
    assume ($stable(post_base_i));
    assume ($stable(post_len_i));
  end
  // the common time base counts up by one clock at most
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni)
    assume (time_i == $past(time_i) || time_i == $past(time_i) + 64'd1);
  // hsem grants only a request, in the clock it is made
  always @(*) if (!lock_req_o) assume (!grant_i);

  // ---- lock ownership, as hsem sees it: granted at an edge, owned from the next
  // clock until (and including) the clock of the release
  reg f_owned;
  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)        f_owned <= 1'b0;
    else if (grant_i)   f_owned <= 1'b1;
    else if (release_o) f_owned <= 1'b0;
  end

  wire f_sem     = (protect_i == ProtSem);
  wire f_lockst  = (state_q == StPreLock) || (state_q == StPostLock);
  wire f_prest   = (state_q == StPreLock) || (state_q == StPreCopy) ||
                   (state_q == StRunStart) || (state_q == StScan);
  wire f_postst  = (state_q == StPostLock) || (state_q == StPostCopy);

  always @(*) if (rst_ni) begin
    // ---- (a) semaphore: shared memory is read and written only under the lock
    if (f_sem && sh_re_o) assert (f_owned && !release_o);
    if (f_sem && sh_we_o) assert (f_owned && !release_o);
    if (f_sem && sh_flip_o) assert (1'b0);        // no flips without ping-pong
    // the lock is held only while copying and asked for only while not held; a
    // sequencer without the semaphore never asks
    if (f_owned)    assert (f_sem && copying);
    if (lock_req_o) assert (f_sem && !f_owned);
    // Only the owner releases (an empty list goes to its copy state without the lock
    // and does not release either).
    if (release_o) assert (f_owned);

    // ---- (b) the CPU is never started while a copy runs (the engine's pipeline is
    // empty whenever it does not run: copy_engine.v); the sequencer owns the local
    // ports only in the copy states, and uses them only then
    if (cpu_run_o) assert (!copy_en_o && !copying);
    assert (copy_en_o == ((state_q == StPreCopy) || (state_q == StPostCopy)));
    if (m_we_o || w_we_o || f_local_rd) assert (copy_en_o);
    if ((state_q == StRunStart) || (state_q == StScan)) assert (!copy_en_o);

    // ---- (c) local writes only in a precycle, shared writes only in a postcycle
    if (m_we_o || w_we_o) assert (state_q == StPreCopy && !post);
    if (sh_re_o)          assert (state_q == StPreCopy && !post);
    if (sh_we_o)          assert (state_q == StPostCopy && post);
    if (f_local_rd)       assert (state_q == StPostCopy);

    // ---- (d) no lock across a scan: the CPU starts and runs without the lock
    if (cpu_run_o || state_q == StScan || state_q == StWait) assert (!f_owned);

    // ---- inductive invariants of the state machine and the engine's list (labelled
    // f_inv_*: the bmc task drops them, so a mutant must break a claim)
    f_inv_state: assert (state_q <= StPostCopy);
    if (f_prest)  f_inv_pre: assert (!post);
    if (f_postst) f_inv_post: assert (post);
    if (f_lockst) f_inv_lock: assert (!f_started && !list_empty);
    if (f_sem && copying && !list_empty && !copy_done) f_inv_owned: assert (f_owned);
  end

  // ---- (g) Fig. 8's decision, both ways: a precycle waiting for the lock skips its
  // copy exactly when waiting longer could no longer let the scan end within its period
  // (docs/multicore.md: now + pre entries + post entries + the last scan's cycles + 6
  // > nominal start + period, with period 0 never). The property keeps its own nominal
  // start: scan 0's at its start, every later one a period after the one before
  // (scan k at k * period, however late it began).
  reg        f_sched;                    // scan 0 has begun
  reg [63:0] f_nom;                      // this scan's nominal start, 1/1000 clock
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_sched <= 1'b0;
      f_nom   <= 64'd0;
    end else if (begin_pre) begin
      f_sched <= 1'b1;
      f_nom   <= f_sched ? f_nom + period_i : time_i * 64'd1000;
    end
  wire [63:0] f_rest = {{(63-PaW){1'b0}}, pre_len_i} + {{(63-PaW){1'b0}}, post_len_i} +
                       {32'd0, cpu_scan_cycles_i} + 64'd6;   // clocks the scan still needs
  wire f_too_late = (period_i != 64'd0) && ((time_i + f_rest) * 64'd1000 > f_nom + period_i);
  wire f_pre_waits = (state_q == StPreLock) && !grant_i;   // asks, the lock is busy

  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // give-up => skip: the CPU starts on its old local copies, copy_fail and the skip
    // counted; no copy was made (nothing read from shared memory)
    if ($past(f_pre_waits && f_too_late))
      assert (cpu_run_o && !lock_req_o && copy_fail_o && skips_o == $past(skips_o) + 32'd1);
    // still in time => it keeps asking (no skip, no start)
    if ($past(f_pre_waits && !f_too_late))
      assert (lock_req_o && !cpu_run_o && skips_o == $past(skips_o));
    // skip => give-up: a precycle that asked and starts the CPU without its copy did so
    // only because the lock was busy and it was too late
    if ($past(state_q == StPreLock) && cpu_run_o) assert ($past(f_pre_waits && f_too_late));
    // skips are counted only there
    if (skips_o != $past(skips_o)) assert ($past(f_pre_waits && f_too_late));
  end
  // the shadow's nominal start is the sequencer's (with a period; without, nothing is
  // ever late)
  always @(*) if (rst_ni && period_i != 64'd0) begin
    if (!f_sched) f_inv_unsched: assert (state_q == StWait && !started_q);
    if (f_sched)  f_inv_sched: assert (started_q);
    if (f_sched && state_q != StWait) f_inv_nom: assert (nominal_q == f_nom);
    if (f_sched && state_q == StWait) f_inv_next: assert (nominal_q == f_nom + period_i);
  end

  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // ---- (e) copy_fail is sticky and set only by a skipped precycle (g) or, with
    // ping-pong, by a precycle read that its writer overtook
    if ($past(copy_fail_o)) assert (copy_fail_o);
    if (!$past(copy_fail_o) && copy_fail_o)
      assert (($past(f_pre_waits && f_too_late) && cpu_run_o) ||
              ($past(overtaken) && $past(state_q) == StPreCopy && protect_i == ProtPing));
    // ---- (f) a postcycle never gives up: it leaves StPostLock only with the grant
    if ($past(state_q) == StPostLock)
      assert (state_q == ($past(grant_i) ? StPostCopy : StPostLock));
    // a grant is followed by the copy that needs it
    if ($past(grant_i)) assert (f_owned && copying);
  end

  // ---- (h) SEM_WAIT counts what hsem saw: the clocks this core asked for the lock
  // and was not granted it, over the cycle a cycle_done_o reports (none are asked for
  // in StWait, so counting from the last report is counting from the precycle's start).
  // Counted here from the ports alone; the helper invariants tie it to the register.
  reg [31:0] f_wait;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) f_wait <= 32'd0;
    else         f_wait <= (cycle_done_o ? 32'd0 : f_wait) + {31'd0, lock_req_o && !grant_i};
  always @(*) if (rst_ni) begin
    if (cycle_done_o) assert (sem_wait_o == f_wait);
    if (state_q != StWait) f_inv_wait: assert (wait_cnt_q == f_wait);
    if (state_q == StWait && !cycle_done_o) f_inv_wait_none: assert (f_wait == 32'd0);
  end

  // ---- (i) the lock is held at most n + 3 clocks for a list of n entries (from the
  // clock after the grant to the release, both included): a waiting core's wait is
  // bounded by the other cores' lists (hsem grants round robin). Counted from the ports.
  reg [PaW+2:0] f_held;                  // clocks owned before this one
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni)              f_held <= 0;
    else if (grant_i)         f_held <= 0;
    else if (f_owned && !release_o) f_held <= f_held + 1'b1;
  wire [PaW+2:0] f_list = post ? {1'b0, post_len_i} : {1'b0, pre_len_i};
  always @(*) if (rst_ni && f_owned) begin
    assert (f_held <= f_list + 2);
    f_inv_held: assert (f_held == f_runs);
  end
  // the engine's list is this phase's (the configuration is constant while running)
  always @(*) if (rst_ni && state_q != StWait)
    f_inv_list: assert (f_len == (post ? post_len_i : pre_len_i));

  // ---- (j) SEM_WAIT bounded in clocks: when hsem grants a request that has waited
  // f_gmax clocks at the latest (an assumption, hsem.v proves it in clocks from the
  // other cores' hold bound (i)), a scan waits at most 2 * f_gmax clocks: once in its
  // precycle, once in its postcycle. Only in formal/core_seq_wait.sby
  // (F_GRANT_BOUND): the assumption must not narrow what (a)-(i) are proved for.
`ifdef F_GRANT_BOUND
  // (one bound, 1: any bound 0..15 takes the bmc task from seconds to minutes, and the
  // proof's shape does not depend on it)
  wire [3:0] f_gmax = 4'd1;
  reg [4:0] f_reqrun;                    // clocks this request has waited before this one
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) f_reqrun <= 5'd0;
    else         f_reqrun <= (lock_req_o && !grant_i) ? f_reqrun + 5'd1 : 5'd0;
  always @(*) if (rst_ni && lock_req_o && f_reqrun >= {1'b0, f_gmax}) assume (grant_i);
  wire [31:0] f_g = {28'd0, f_gmax};
  always @(*) if (rst_ni) begin
    if (cycle_done_o) assert (sem_wait_o <= 2 * f_g);
    f_inv_reqrun: assert (f_reqrun <= {1'b0, f_gmax});
    // (a precycle that gave up leaves its count for the RUN clock)
    if (!lock_req_o && state_q != StRunStart) f_inv_reqrun0: assert (f_reqrun == 5'd0);
    if (state_q == StPreLock) f_inv_prewait: assert (f_wait == {27'd0, f_reqrun});
    if (state_q == StPreCopy || state_q == StRunStart || state_q == StScan)
      f_inv_prewaited: assert (f_wait <= f_g);
    if (state_q == StPostLock) f_inv_postwait: assert (f_wait <= f_g + {27'd0, f_reqrun});
    if (state_q == StPostCopy) f_inv_postwaited: assert (f_wait <= 2 * f_g);
  end
  // the bound is reached: both waits as long as hsem may make them
  always @(posedge clk_i) if (rst_ni) cover (cycle_done_o && sem_wait_o == 2 * f_g);
`endif

  // the interesting runs exist (formal/core_seq.sby, task cover; copy_engine.v has
  // the gathered postcycle write)
  always @(posedge clk_i) if (rst_ni) begin
    cover (f_sem && cycle_done_o && $past(sh_we_o, 2) && pre_clocks_o > 32'd4);
    cover (f_sem && copy_fail_o && state_q == StScan);
    // the hold bound (i) is reached: a list of items released in its owned clock n + 3
    cover (f_owned && release_o && f_list != 0 && f_held == f_list + 2);
    // a precycle that waited for the lock, still in time, and is granted; one of a
    // later scan (a scan has completed: its nominal start is a period on) that gives up
    cover (f_past_valid && $past(f_pre_waits && !f_too_late) && grant_i);
    cover (f_past_valid && $past(f_pre_waits && f_too_late) && cpu_run_o &&
           pre_clocks_o != 32'd0);
  end
`endif
endmodule
`default_nettype wire
