//! `PlaneSums`: the three dot products of one cull plane, `S_lo`, `den_lo`, `den_hi`
//! (`golden::plane::fix::plane_sums`), combinational.
//!
//! The operands arrive already chosen by the sign of each normal component (the parent's muxes): `p_a` is
//! `o_lo` or `o_hi`, `dl_a`/`dh_a` the direction bound that makes each product a lower or upper bound.
//! rust-hdl 0.46 has no signed multiply, so like [`crate::slab::mul_round::MulRound`] this leaf has a native
//! simulation model and hand-written Verilog with explicitly sign-extended operands; cross-simulation of
//! the exported Verilog checks that they agree.
//!
//! ```text
//! s      = sum_a n_a * (2 p_a - lo_a - hi_a) - w        SB = G + N + 5 bits
//! den_lo = sum_a n_a * dl_a                             EB = N + FD + 4 bits
//! den_hi = sum_a n_a * dh_a
//! ```

use crate::slab::fix::{code, sext};
use rust_hdl::prelude::*;

/// One plane's sums; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneSums<
    const G: usize,
    const N: usize,
    const DB: usize,
    const WB: usize,
    const SB: usize,
    const EB: usize,
> {
    pub n0: Signal<In, Bits<N>>,
    pub n1: Signal<In, Bits<N>>,
    pub n2: Signal<In, Bits<N>>,
    pub p0: Signal<In, Bits<G>>,
    pub p1: Signal<In, Bits<G>>,
    pub p2: Signal<In, Bits<G>>,
    pub lo0: Signal<In, Bits<G>>,
    pub lo1: Signal<In, Bits<G>>,
    pub lo2: Signal<In, Bits<G>>,
    pub hi0: Signal<In, Bits<G>>,
    pub hi1: Signal<In, Bits<G>>,
    pub hi2: Signal<In, Bits<G>>,
    pub dl0: Signal<In, Bits<DB>>,
    pub dl1: Signal<In, Bits<DB>>,
    pub dl2: Signal<In, Bits<DB>>,
    pub dh0: Signal<In, Bits<DB>>,
    pub dh1: Signal<In, Bits<DB>>,
    pub dh2: Signal<In, Bits<DB>>,
    pub w: Signal<In, Bits<WB>>,
    pub s: Signal<Out, Bits<SB>>,
    pub den_lo: Signal<Out, Bits<EB>>,
    pub den_hi: Signal<Out, Bits<EB>>,
}

impl<
        const G: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
    > Default for PlaneSums<G, N, DB, WB, SB, EB>
{
    fn default() -> Self {
        assert!(
            SB == G + N + 5 && WB == G + N + 4 && EB == N + DB + 1 && SB <= 63 && EB <= 63,
            "PlaneSums<{G},{N},{DB},{WB},{SB},{EB}>: need WB = G+N+4, SB = G+N+5, EB = N+DB+1"
        );
        Self {
            n0: Default::default(),
            n1: Default::default(),
            n2: Default::default(),
            p0: Default::default(),
            p1: Default::default(),
            p2: Default::default(),
            lo0: Default::default(),
            lo1: Default::default(),
            lo2: Default::default(),
            hi0: Default::default(),
            hi1: Default::default(),
            hi2: Default::default(),
            dl0: Default::default(),
            dl1: Default::default(),
            dl2: Default::default(),
            dh0: Default::default(),
            dh1: Default::default(),
            dh2: Default::default(),
            w: Default::default(),
            s: Default::default(),
            den_lo: Default::default(),
            den_hi: Default::default(),
        }
    }
}

impl<
        const G: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
    > Logic for PlaneSums<G, N, DB, WB, SB, EB>
{
    fn update(&mut self) {
        let v = |x: u64, n: usize| sext(x, n);
        let n = [self.n0.val(), self.n1.val(), self.n2.val()].map(|x| v(x.to_u64(), N));
        let p = [self.p0.val(), self.p1.val(), self.p2.val()].map(|x| v(x.to_u64(), G));
        let lo = [self.lo0.val(), self.lo1.val(), self.lo2.val()].map(|x| v(x.to_u64(), G));
        let hi = [self.hi0.val(), self.hi1.val(), self.hi2.val()].map(|x| v(x.to_u64(), G));
        let dl = [self.dl0.val(), self.dl1.val(), self.dl2.val()].map(|x| v(x.to_u64(), DB));
        let dh = [self.dh0.val(), self.dh1.val(), self.dh2.val()].map(|x| v(x.to_u64(), DB));
        let mut s = -v(self.w.val().to_u64(), WB);
        let (mut el, mut eh) = (0i64, 0i64);
        for a in 0..3 {
            s += n[a] * (2 * p[a] - lo[a] - hi[a]);
            el += n[a] * dl[a];
            eh += n[a] * dh[a];
        }
        self.s.next = bits::<SB>(code(s, SB));
        self.den_lo.next = bits::<EB>(code(el, EB));
        self.den_hi.next = bits::<EB>(code(eh, EB));
    }

    fn connect(&mut self) {
        self.s.connect();
        self.den_lo.connect();
        self.den_hi.connect();
    }

    fn hdl(&self) -> Verilog {
        // `dst` = `src` sign-extended from `w` to `to` bits.
        let ext = |dst: &str, src: &str, w: usize, to: usize| {
            format!(
                "wire signed [{}:0] {dst} = {{{{{}{{{src}[{}]}}}}, {src}}};\n",
                to - 1,
                to - w,
                w - 1
            )
        };
        let mut v = String::from(
            "// Operands sign-extended to the result width, then multiplied and added.\n",
        );
        for a in 0..3 {
            v += &ext(&format!("ns{a}"), &format!("n{a}"), N, SB);
            v += &ext(&format!("ps{a}"), &format!("p{a}"), G, SB);
            v += &ext(&format!("los{a}"), &format!("lo{a}"), G, SB);
            v += &ext(&format!("his{a}"), &format!("hi{a}"), G, SB);
            v += &ext(&format!("nd{a}"), &format!("n{a}"), N, EB);
            v += &ext(&format!("dls{a}"), &format!("dl{a}"), DB, EB);
            v += &ext(&format!("dhs{a}"), &format!("dh{a}"), DB, EB);
        }
        v += &ext("ws", "w", WB, SB);
        v += "always @(*) begin\n";
        v += "   s = ns0 * ((ps0 <<< 1) - los0 - his0) + ns1 * ((ps1 <<< 1) - los1 - his1)\n";
        v += "     + ns2 * ((ps2 <<< 1) - los2 - his2) - ws;\n";
        v += "   den_lo = nd0 * dls0 + nd1 * dls1 + nd2 * dls2;\n";
        v += "   den_hi = nd0 * dhs0 + nd1 * dhs1 + nd2 * dhs2;\n";
        v += "end\n";
        Verilog::Custom(v)
    }
}
