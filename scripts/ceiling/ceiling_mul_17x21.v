// Device ceiling: a product wider than one MULT18X18D, signed 17 x unsigned 21 bits (the 16-bit-grid
// slab tester's multiply): two DSPs and the fabric adder that joins them, between flip-flops.
module ceiling_mul_17x21 (
    input wire clock,
    input wire signed [16:0] a,
    input wire [20:0] m,
    output reg signed [38:0] p
);
  always @(posedge clock) p <= a * $signed({1'b0, m});
endmodule
