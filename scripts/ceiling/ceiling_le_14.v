// Device ceiling: one 14-bit unsigned comparison (a t-code comparison of the 8-bit-grid slab tester),
// flip-flop to flip-flop.
module ceiling_le_14 (
    input wire clock,
    input wire [13:0] a,
    input wire [13:0] b,
    output reg le
);
  always @(posedge clock) le <= a <= b;
endmodule
