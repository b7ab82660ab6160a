// Device ceiling: one fabric-registered product in one MULT18X18D, signed 9 x unsigned 12 bits (the
// product of the 8-bit-grid slab tester's multiply). The wrapper of scripts/timing drives `a` and `m`
// from flip-flops; the product is registered in `p`: flip-flop, DSP, flip-flop.
module ceiling_mul_9x12 (
    input wire clock,
    input wire signed [8:0] a,
    input wire [11:0] m,
    output reg signed [21:0] p
);
  always @(posedge clock) p <= a * $signed({1'b0, m});
endmodule
