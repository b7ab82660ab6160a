// Device ceiling: a comparison behind a max, max(a, b) <= c on 14 bits (two comparisons in series,
// as a tree's last max feeding a hit decision), flip-flop to flip-flop.
module ceiling_max_le_14 (
    input wire clock,
    input wire [13:0] a,
    input wire [13:0] b,
    input wire [13:0] c,
    output reg le
);
  wire [13:0] mx = a > b ? a : b;
  always @(posedge clock) le <= mx <= c;
endmodule
