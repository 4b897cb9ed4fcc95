"""Instruction encoding: field layout and opcodes (from the definition) and the encoder of programs into words and listings."""
