// Device ceiling: a read of a 16-entry LUT RAM (TRELLIS_DPR16X4, as the bundle processors' ray store)
// at a registered address into a register; the write port is clocked.
module ceiling_lutram_16x4 (
    input wire clock,
    input wire we,
    input wire [3:0] wa,
    input wire [3:0] wd,
    input wire [3:0] ra,
    output reg [3:0] rd
);
  reg [3:0] mem[0:15];
  always @(posedge clock) begin
    if (we) mem[wa] <= wd;
    rd <= mem[ra];
  end
endmodule
