`default_nettype none
`include "param_check.vh"
// Hardware semaphore for the multi-core PLC (seed 000: the STM32 HSEM guarding the
// shared memory). One lock, `Cores` requesters. A request is a one-step read-lock:
// in the clock a core asks, it learns whether it got the lock (grant_o), and owns
// it from the next clock until it releases it. While the lock is held, other
// requests are refused (the requester spins and asks again); when the owner releases
// it, the next clock grants it to a waiting core, chosen round-robin after the last
// owner so that no core waits more than Cores - 1 grants.
module hsem #(
  parameter integer Cores = 2  // requesters (cores), at least 2
) (
  input  wire                     clk_i,
  input  wire                     rst_ni,
  input  wire [Cores-1:0]         lock_req_i,  // try to take the lock this clock
  input  wire [Cores-1:0]         release_i,   // the owner gives it back
  output wire [Cores-1:0]         grant_o,     // this clock's request succeeds
  output reg                      locked_o,
  output reg  [$clog2(Cores)-1:0] owner_o      // meaningful while locked_o
);
  localparam integer IdW = $clog2(Cores);
  localparam [31:0]  LastCore = Cores - 1;

  `PARAM_CHECK(g_bad_cores, Cores < 2,
               "hsem: Cores must be at least 2 (an owner id needs a bit)")

  reg [IdW-1:0] last_q;  // the last core granted: round-robin starts after it

  // The first requesting core after last_q, cyclically.
  reg           any_req;
  reg [IdW-1:0] pick;
  reg [31:0]    cand;
  integer       i;
  always @(*) begin
    any_req = 1'b0;
    pick    = {IdW{1'b0}};
    cand    = 32'd0;
    for (i = Cores; i >= 1; i = i - 1) begin
      // visit last_q+Cores .. last_q+1 (mod Cores); the lowest distance wins
      cand = ({{(32-IdW){1'b0}}, last_q} + i) % Cores;
      if (lock_req_i[cand[IdW-1:0]]) begin
        any_req = 1'b1;
        pick    = cand[IdW-1:0];
      end
    end
  end

  // verilator lint_off UNUSEDSIGNAL
  wire unused_cand = ^cand;            // only its low bits index the requests
  // verilator lint_on UNUSEDSIGNAL

  wire grant_any = !locked_o && any_req;
  assign grant_o = grant_any ? ({{(Cores-1){1'b0}}, 1'b1} << pick) : {Cores{1'b0}};

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      locked_o <= 1'b0;
      owner_o  <= {IdW{1'b0}};
      last_q   <= LastCore[IdW-1:0];   // core 0 first
    end else if (grant_any) begin
      locked_o <= 1'b1;
      owner_o  <= pick;
      last_q   <= pick;
    end else if (locked_o && release_i[owner_o]) begin
      locked_o <= 1'b0;               // only the owner's release counts
    end
  end

`ifdef FORMAL
  // formal/hsem.sby, by k-induction. The properties are stated against a shadow of the
  // lock built from the ports alone (grants seen, releases by the core that holds it),
  // not against locked_o or the grant logic above.
`include "formal_past.vh"

  // ---- shadow of the lock: taken by a grant (owned from the next clock), given back
  // by its holder's release; anybody else's release does nothing
  reg           f_held;
  reg [IdW-1:0] f_holder;
  reg [IdW-1:0] f_granted;               // the index of this clock's grant, if any
  integer       f_i;
  always @(*) begin
    f_granted = {IdW{1'b0}};
    for (f_i = 0; f_i < Cores; f_i = f_i + 1)
      if (grant_o[f_i]) f_granted = f_i[IdW-1:0];
  end
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_held   <= 1'b0;
      f_holder <= {IdW{1'b0}};
    end else if (grant_o != {Cores{1'b0}}) begin
      f_held   <= 1'b1;
      f_holder <= f_granted;
    end else if (f_held && release_i[f_holder]) begin
      f_held   <= 1'b0;
    end

  always @(*) if (rst_ni) begin
    // mutual exclusion: one grant at most, only to a core that asks, never while a
    // core holds the lock
    assert ($onehot0(grant_o));
    assert ((grant_o & ~lock_req_i) == {Cores{1'b0}});
    if (f_held) assert (grant_o == {Cores{1'b0}});
    // no grant is withheld: a request while nobody holds the lock is granted at once
    // (so a released lock goes to a waiting core in the very next clock)
    if (!f_held && lock_req_i != {Cores{1'b0}}) assert (grant_o != {Cores{1'b0}});
    // the outputs tell who holds it (the owner keeps it until it releases it)
    assert (locked_o == f_held);
    if (f_held) assert (owner_o == f_holder);
    f_inv_holder: assert (f_holder < Cores);
  end

  // ---- bounded waiting, in grants: take any core f_core that keeps asking whenever the
  // lock is free (a spinning core). From its first request on, until it is granted, at
  // most Cores - 1 grants go to other cores (f_others), and no other core f_rival (any)
  // is granted twice (f_rival_grants).
  (* anyconst *) reg [IdW-1:0] f_core;
  (* anyconst *) reg [IdW-1:0] f_rival;
  reg         f_waiting;                  // f_core asked (not holding it) and waits
  reg [IdW:0] f_others;                   // grants to other cores while it waits
  reg [1:0]   f_rival_grants;             // ... of them to f_rival
  always @(*) begin
    assume (f_core < Cores && f_rival < Cores && f_rival != f_core);
    if (rst_ni && f_waiting && !f_held) assume (lock_req_i[f_core]);
  end
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_waiting      <= 1'b0;
      f_others       <= {(IdW+1){1'b0}};
      f_rival_grants <= 2'd0;
    end else if (grant_o[f_core]) begin
      f_waiting      <= 1'b0;
      f_others       <= {(IdW+1){1'b0}};
      f_rival_grants <= 2'd0;
    end else if (f_waiting || (lock_req_i[f_core] && !(f_held && f_holder == f_core))) begin
      f_waiting <= 1'b1;
      if (grant_o != {Cores{1'b0}} && f_others != {(IdW+1){1'b1}}) f_others <= f_others + 1'b1;
      if (grant_o[f_rival] && f_rival_grants != 2'd3) f_rival_grants <= f_rival_grants + 2'd1;
    end
  always @(*) if (rst_ni) begin
    assert (f_others <= Cores - 1);
    assert (f_rival_grants <= 2'd1);
    if (!f_waiting) assert (f_others == 0 && f_rival_grants == 2'd0);
  end

  // Invariants the induction needs (labelled f_inv_*: of the round-robin state, not
  // claims; the bmc task drops them, so a mutant must break a claim): every grant to
  // another core while f_core waits goes to a core ahead of it after last_q, so its
  // distance from last_q shrinks with each: f_others + distance <= Cores; f_rival, once
  // granted, is last_q or behind f_core.
  wire [31:0] f_dist = ({{(32-IdW){1'b0}}, f_core} + Cores - {{(32-IdW){1'b0}}, last_q} - 1)
                       % Cores + 1;       // 1 .. Cores: how far f_core is after last_q
  wire [31:0] f_rdist = ({{(32-IdW){1'b0}}, f_rival} + Cores - {{(32-IdW){1'b0}}, last_q} - 1)
                        % Cores + 1;      // ... f_rival
  always @(*) if (rst_ni) begin
    f_inv_last: assert (last_q < Cores);
    if (f_held) f_inv_last_held: assert (last_q == f_holder);
    if (f_waiting && f_held) f_inv_not_own: assert (f_holder != f_core);
    if (f_waiting) f_inv_dist: assert ({{(31-IdW){1'b0}}, f_others} + f_dist <= Cores);
    if (f_waiting && f_rival_grants != 2'd0)
      f_inv_rival: assert (f_rdist > f_dist || f_rdist == Cores);
    if (f_rival_grants != 2'd0) f_inv_rival_other: assert (f_others != 0);
  end
  // ---- bounded waiting, in clocks: if every holder gives the lock back within f_hmax
  // clocks of owning it (an assumption here; core_seq.v proves n + 3 for a copy of n
  // plan entries), a spinning core is granted at the latest after waiting
  // (Cores - 1) * (f_hmax + 1) + f_hmax clocks: the lock held when it began to wait is
  // free after f_hmax clocks at most, each other core's turn takes f_hmax + 1, and
  // Cores - 1 turns at most come first (the bound in grants above). Only in
  // formal/hsem_wait.sby (F_HOLD_BOUND): the assumption must not narrow the claims above.
`ifdef F_HOLD_BOUND
  (* anyconst *) reg [3:0] f_hmax;        // 1..15 owned clocks at most
  reg [3:0] f_hcnt;                       // clocks the holder has owned it before this one
  reg [7:0] f_wclk;                       // clocks f_core has waited before this one
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_hcnt <= 4'd0;
      f_wclk <= 8'd0;
    end else begin
      if (grant_o != {Cores{1'b0}}) f_hcnt <= 4'd0;
      else if (f_held && f_hcnt != 4'hF) f_hcnt <= f_hcnt + 4'd1;
      if (grant_o[f_core]) f_wclk <= 8'd0;
      else if ((f_waiting || (lock_req_i[f_core] && !(f_held && f_holder == f_core))) &&
               f_wclk != 8'hFF) f_wclk <= f_wclk + 8'd1;
    end
  always @(*) begin
    assume (f_hmax != 4'd0);
    // the holder releases in its owned clock f_hmax at the latest
    if (rst_ni && f_held && {28'd0, f_hcnt} + 32'd1 >= {28'd0, f_hmax}) assume (release_i[f_holder]);
  end
  wire [31:0] f_turn = {28'd0, f_hmax} + 32'd1;    // a grant, then up to f_hmax owned clocks
  always @(*) if (rst_ni) begin
    if (grant_o[f_core]) assert ({24'd0, f_wclk} <= (Cores - 1) * f_turn + {28'd0, f_hmax});
    if (f_held) f_inv_hcnt: assert (f_hcnt < f_hmax);
    if (!f_waiting) f_inv_wclk0: assert (f_wclk == 8'd0);
    // while it waits: the current holder's turn, after f_others whole turns
    if (f_waiting && f_held)
      f_inv_wclk_held: assert ({24'd0, f_wclk} <= {{(31-IdW){1'b0}}, f_others} * f_turn + {28'd0, f_hcnt});
    if (f_waiting && !f_held)
      f_inv_wclk_free: assert ({24'd0, f_wclk} <= {{(31-IdW){1'b0}}, f_others} * f_turn + {28'd0, f_hmax});
  end
  // the bound in clocks is met but for its last term: the lock free when the core asks,
  // Cores - 1 whole turns of others (a core that asks while the lock is held waits
  // behind fewer turns, so the bound above is not reached; it is the simple one)
  always @(posedge clk_i) if (rst_ni)
    cover (grant_o[f_core] && {24'd0, f_wclk} == (Cores - 1) * f_turn && f_hmax == 4'd1);
`endif
  always @(posedge clk_i) if (rst_ni) cover (f_past_valid && $past(grant_o[1]) && grant_o == 0 &&
                                             lock_req_i[0]);
  // a core waits through Cores - 1 other grants and is granted
  always @(posedge clk_i) if (rst_ni) cover (f_waiting && f_others == Cores - 1 && grant_o[f_core]);
`endif
endmodule
`default_nettype wire
