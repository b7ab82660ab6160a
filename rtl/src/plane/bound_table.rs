//! `BoundTable`: the directed reciprocal table of the fixed cull-plane tester's bound
//! ([`super::bound::PlaneBound`]): `2^R` entries, each a lower and an upper bound of `2^(R+1) / m`
//! (`golden::plane::fix::recip_entry`), read by the index and the half [`super::bound_pick::BoundPick`]
//! chose. Combinational; a `case` in the Verilog, which synthesis maps to LUTs.
//!
//! # Inputs
//! `idx` (the `R`-bit index, zero-extended to 12 bits; the bits above `R` are ignored), `upper`.
//! # Outputs
//! `rv`: the entry, `R + 2` bits unsigned, zero-extended to 14 bits.

use super::bound_pick::IDX_BITS;
use golden::plane::fix::recip_entry;
use rust_hdl::prelude::*;

/// Width of the `rv` port: `R + 2` bits for the largest `R`.
pub const RV_BITS: usize = IDX_BITS + 2;

/// The reciprocal table; see the module documentation.
#[derive(LogicBlock)]
pub struct BoundTable {
    pub idx: Signal<In, Bits<IDX_BITS>>,
    pub upper: Signal<In, Bit>,
    pub rv: Signal<Out, Bits<RV_BITS>>,
    /// Table index bits `R`.
    r_bits: Constant<Bits<8>>,
}

impl BoundTable {
    /// A table of `2^r_bits` entries.
    pub fn new(r_bits: u32) -> Self {
        assert!((1..=IDX_BITS as u32).contains(&r_bits));
        Self {
            idx: Default::default(),
            upper: Default::default(),
            rv: Default::default(),
            r_bits: Constant::new(bits::<8>(r_bits as u64)),
        }
    }
}

impl Logic for BoundTable {
    fn update(&mut self) {
        let r = self.r_bits.val().to_u64() as u32;
        let (lo, hi) = recip_entry(r, self.idx.val().to_u64() & ((1 << r) - 1));
        self.rv.next = bits::<RV_BITS>(if self.upper.val() { hi } else { lo });
    }

    fn connect(&mut self) {
        self.rv.connect();
    }

    fn hdl(&self) -> Verilog {
        let r = self.r_bits.val().to_u64() as usize;
        let mut table = String::new();
        for i in 0..(1u64 << r) {
            let (lo, hi) = recip_entry(r as u32, i);
            table += &format!(
                "      {r}'d{i}: begin rl = {w}'d{lo}; rh = {w}'d{hi}; end\n",
                w = r + 2
            );
        }
        let unused = if r < IDX_BITS {
            format!(
                "// Index bits above R are zero by construction.\nwire unused_idx = ^idx[{}:{r}];\n",
                IDX_BITS - 1
            )
        } else {
            String::new()
        };
        Verilog::Custom(format!(
            "\
{unused}reg [{r21}:0] rl;
reg [{r21}:0] rh;
always @(*) begin
   case (idx[r_bits - 8'd1:0])
{table}      default: begin rl = {r2}'d0; rh = {r2}'d0; end
   endcase
   rv = {{{pad}'d0, upper ? rh : rl}};
end
",
            r2 = r + 2,
            r21 = r + 1,
            pad = RV_BITS - r - 2,
        ))
    }
}
