// Device ceiling: a 28-bit addition (a carry chain as long as an fp16 adder's working sum), flip-flop
// to flip-flop.
module ceiling_add_28 (
    input wire clock,
    input wire [27:0] a,
    input wire [27:0] b,
    output reg [27:0] s
);
  always @(posedge clock) s <= a + b;
endmodule
