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
  // formal/hsem.sby: mutual exclusion and granting after release, by k-induction.
`include "formal_past.vh"

  // mutual exclusion: at most one grant, and never while the lock is held
  always @(*) begin
    assert ($onehot0(grant_o));
    if (locked_o) assert (grant_o == {Cores{1'b0}});
    assert (owner_o < Cores);
  end
  always @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    // the owner keeps the lock until it releases it; nobody else can take or free it
    if ($past(locked_o) && !$past(release_i[owner_o]))
      assert (locked_o && owner_o == $past(owner_o));
    // a grant makes the granted core the owner
    if ($past(grant_o) != {Cores{1'b0}})
      assert (locked_o && grant_o == {Cores{1'b0}} &&
              $past(grant_o) == ({{(Cores-1){1'b0}}, 1'b1} << owner_o));
    // a released lock goes to a waiting core in the very next clock
    if ($past(locked_o) && $past(release_i[owner_o]) && lock_req_i != {Cores{1'b0}})
      assert (grant_o != {Cores{1'b0}});
  end

  // Bounded waiting, for any one core f_core that keeps asking whenever the lock is
  // free (a spinning core): from its first request on, at most Cores - 1 grants go to
  // other cores before it gets the lock. Each such grant goes to a core ahead of it in
  // the round-robin order after last_q, so the distance from last_q to f_core shrinks
  // with every grant: f_others + distance <= Cores is the inductive invariant.
  (* anyconst *) reg [IdW-1:0] f_core;
  reg         f_waiting;                  // f_core asked (not owning it) and waits
  reg [IdW:0] f_others;                   // grants to other cores while it waits
  wire [31:0] f_dist = ({{(32-IdW){1'b0}}, f_core} + Cores - {{(32-IdW){1'b0}}, last_q} - 1)
                       % Cores + 1;       // 1 .. Cores: how far f_core is after last_q
  always @(*) begin
    assume (f_core < Cores);
    if (rst_ni && f_waiting && !locked_o) assume (lock_req_i[f_core]);
  end
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      f_waiting <= 1'b0;
      f_others  <= {(IdW+1){1'b0}};
    end else if (grant_o[f_core]) begin
      f_waiting <= 1'b0;
      f_others  <= {(IdW+1){1'b0}};
    end else if (f_waiting || (lock_req_i[f_core] && !(locked_o && owner_o == f_core))) begin
      f_waiting <= 1'b1;
      if (grant_o != {Cores{1'b0}}) f_others <= f_others + 1'b1;
    end
  always @(*) if (rst_ni) begin
    assert (last_q < Cores);
    if (locked_o) assert (last_q == owner_o);        // the last grant went to the owner
    if (f_waiting && locked_o) assert (owner_o != f_core);
  end
  always @(*) if (rst_ni && !f_waiting) assert (f_others == 0);
  always @(*) if (rst_ni && f_waiting) begin
    assert ({{(31-IdW){1'b0}}, f_others} + f_dist <= Cores);
    assert (f_others <= Cores - 1);
  end
  // no grant is ever withheld from a request while the lock is free
  always @(*) if (rst_ni && !locked_o && lock_req_i != {Cores{1'b0}})
    assert (grant_o != {Cores{1'b0}});
  always @(posedge clk_i) if (rst_ni) cover (f_past_valid && $past(grant_o[1]) && grant_o == 0 &&
                                             lock_req_i[0]);
`endif
endmodule
`default_nettype wire
