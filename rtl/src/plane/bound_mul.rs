//! `BoundMul`: the product `A * r` of a plane's bound ([`super::bound::PlaneBound`]): the signed
//! numerator (`SB` bits) times the unsigned table entry (`R + 2` bits), exact in `SB + R + 2` bits.
//! Combinational; a native model and hand-written Verilog (rust-hdl 0.46's `hdl_gen` multiplies only
//! 16 by 16 bits), checked against each other by cross-simulation of the testers.
//!
//! # Inputs
//! `a` (`SB` bits, two's complement), `rv` (`R + 2` bits unsigned, zero-extended to 14 bits).
//! # Outputs
//! `prod`: the product in two's complement over its low [`BoundMul::product_bits`] bits, zero above
//! (synthesis removes the constant bits of the register after it).

use super::bound_table::RV_BITS;
use crate::slab::fix::sext;
use rust_hdl::prelude::*;

/// The product; see the module documentation.
#[derive(LogicBlock)]
pub struct BoundMul<const SB: usize> {
    pub a: Signal<In, Bits<SB>>,
    pub rv: Signal<In, Bits<RV_BITS>>,
    pub prod: Signal<Out, Bits<64>>,
    /// Table index bits `R`.
    r_bits: Constant<Bits<8>>,
}

impl<const SB: usize> BoundMul<SB> {
    /// A multiplier for entries of a `2^r_bits`-entry table.
    pub fn new(r_bits: u32) -> Self {
        assert!(r_bits as usize + 2 <= RV_BITS && Self::bits_for(r_bits) <= 64);
        Self {
            a: Default::default(),
            rv: Default::default(),
            prod: Default::default(),
            r_bits: Constant::new(bits::<8>(r_bits as u64)),
        }
    }

    /// Bits of the product for `r_bits` table bits: `SB + R + 2` (`|A| <= 2^(SB-1)`, `r < 2^(R+2)`).
    pub const fn bits_for(r_bits: u32) -> usize {
        SB + r_bits as usize + 2
    }

    /// Bits of this unit's product.
    pub fn product_bits(&self) -> usize {
        Self::bits_for(self.r_bits.val().to_u64() as u32)
    }
}

impl<const SB: usize> Logic for BoundMul<SB> {
    fn update(&mut self) {
        let pw = self.product_bits();
        let q = sext(self.a.val().to_u64(), SB) as i128 * self.rv.val().to_u64() as i128;
        let mask = if pw == 64 { u64::MAX } else { (1u64 << pw) - 1 };
        self.prod.next = bits::<64>(q as u64 & mask);
    }

    fn connect(&mut self) {
        self.prod.connect();
    }

    fn hdl(&self) -> Verilog {
        let r = self.r_bits.val().to_u64() as usize;
        let pw = self.product_bits();
        let unused = if r + 2 < RV_BITS {
            format!(
                "// Entry bits above R + 2 are zero by construction.\nwire unused_rv = ^rv[{}:{}];\n",
                RV_BITS - 1,
                r + 2
            )
        } else {
            String::new()
        };
        let widen = if pw < 64 {
            format!("{{{}'d0, p}}", 64 - pw)
        } else {
            "p".to_string()
        };
        Verilog::Custom(format!(
            "\
{unused}wire signed [{pw1}:0] p = $signed(a) * $signed({{1'b0, rv[r_bits + 8'd1:0]}});
always @(*) prod = {widen};
",
            pw1 = pw - 1,
        ))
    }
}
