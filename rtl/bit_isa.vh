// Opcodes of the bit processor. The encoding is documented in docs/isa.md; keep both
// in step. Macros (not localparams) so that a module includes only the names it uses
// without tripping Verilator's unused-parameter warning.
`ifndef BIT_ISA_VH
`define BIT_ISA_VH

// Instruction word fields
`define ISA_OPCODE      31:24
`define ISA_AREA        15:12
`define ISA_INDEX       11:0
`define ISA_TARGET      15:0
`define ISA_WAIT_UPDATE 16      // T/C read: wait for this scan's byte-side update

// Opcodes without an operand
`define OP_NOP          8'h00
`define OP_END          8'h01
`define OP_NOT          8'h02
`define OP_SET          8'h03
`define OP_CLR          8'h04
`define OP_CLOSE        8'h05   // ")"
`define OP_REFRESH      8'h06
// 0x08 | f<<1 | n : LD LDN A AN O ON X XN  (f: 00 load, 01 and, 10 or, 11 xor)
`define OP_LOGIC_MASK   8'hF8
`define OP_LOGIC        8'h08
// 0x10 | f<<1 | n : A( AN( O( ON( X( XN(
`define OP_OPEN         8'h10
`define OP_ASSIGN       8'h18   // "="
`define OP_SETBIT       8'h19   // "S"
`define OP_RESETBIT     8'h1A   // "R"
`define OP_FP           8'h1B
`define OP_FN           8'h1C
`define OP_JU           8'h20
`define OP_JC           8'h21
`define OP_JCN          8'h22

// Logic functions (opcode bits 2:1)
`define FN_LOAD         2'b00
`define FN_AND          2'b01
`define FN_OR           2'b10
`define FN_XOR          2'b11

// Operand areas (instruction bits 15:12)
`define AREA_I          4'd0
`define AREA_PI         4'd1
`define AREA_IR         4'd2
`define AREA_IF         4'd3
`define AREA_Q          4'd4
`define AREA_PQ         4'd5
`define AREA_M          4'd6
`define AREA_T          4'd7
`define AREA_C          4'd8
`define AREA_FB         4'd9    // FBI k (read) / FBY k (write)


// Byte instructions (bit 7 set): dispatched to the byte processor in serial mode.
`define OP_BYTE_BIT     7
`define OP_B_SD         8'hB0
`define OP_B_RT         8'hB4   // R T n
`define OP_B_CU         8'hB8
`define OP_B_RC         8'hBB   // R C n
`define AREA_IW         4'd10
`define AREA_QW         4'd11
`define AREA_MW         4'd12

`endif
