"""Simulator drivers: the Verilator harness runner and the cocotb test modules and runner."""
