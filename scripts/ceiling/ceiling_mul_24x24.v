// Device ceiling: the 24 x 24-bit unsigned significand product of an fp32 multiplier (four DSPs and
// their adders), between flip-flops.
module ceiling_mul_24x24 (
    input wire clock,
    input wire [23:0] a,
    input wire [23:0] b,
    output reg [47:0] p
);
  always @(posedge clock) p <= a * b;
endmodule
