// Parameter checks at elaboration (hand-written; not generated).
//
// A module whose parameters have a legal range states it where the range comes from,
// in a generate-if whose condition is the violation:
//
//     if (Channels < 1 || Channels > 8) begin : g_bad_channels
//       `PARAM_ERROR("bit_proc: Channels must be 1..8 (...)");
//     end
//
// so that a build out of range stops with a message naming the parameter instead of
// elaborating into a circuit that quietly misbehaves (a wrapped index, a [-1:0] range).
// Both Yosys and Verilator run $error there as an elaboration system task (Yosys:
// ERROR; Verilator's %Warning-USERERROR fails `--lint-only -Wall`). Icarus 11
// has no elaboration system tasks in a generate block, so for it the same check is an
// initial $fatal, which stops the simulation at time 0 with the message.
// The message is a plain string: Yosys does not format arguments there.
`ifndef PARAM_CHECK_VH
`define PARAM_CHECK_VH

`ifdef __ICARUS__
`define PARAM_ERROR(msg) initial $fatal(1, msg)
`else
`define PARAM_ERROR(msg) $error(msg)
`endif

// `PARAM_CHECK(label, bad, msg): the generate-if above in one line; `bad` is the
// violated condition, `label` names the generate block (g_bad_<parameter>).
`define PARAM_CHECK(label, bad, msg) if (bad) begin : label `PARAM_ERROR(msg); end

`endif
