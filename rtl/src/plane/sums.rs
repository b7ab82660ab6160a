//! `PlaneSums`: the three dot products of one cull plane, `S_lo`, `den_lo`, `den_hi`
//! (`golden::plane::fix::plane_sums`), in one clock or up to three.
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
//!
//! Three steps, with a cut point (a register or a wire, as the tester's configuration chooses) after
//! each of the first two:
//! 1. the terms `2 p_a - lo_a - hi_a` (`SB` bits); cut [`super::fix::cut::TERMS`]: the terms, the
//!    normal components, the direction bounds and `w` are registered (`*_qo`);
//! 2. the nine products `n_a * term_a`, `n_a * dl_a`, `n_a * dh_a`; cut
//!    [`super::fix::cut::PRODUCTS`]: the products and `w` are registered (`*_qp`);
//! 3. the three sums of three (and `- w`).
//!
//! The registers are this leaf's own (rust-hdl locals, assigned on the clock edge in the simulation and
//! in the Verilog alike), each holding its value's two's complement code at its own width.
//!
//! # Inputs
//! `clock` (used only with a cut), `n0..2`, `p0..2`, `lo0..2`, `hi0..2`, `dl0..2`, `dh0..2`, `w`.
//! # Outputs
//! `s`, `den_lo`, `den_hi` of the inputs [`PlaneSums::latency`] clocks ago.

use super::fix::cut;
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
    pub clock: Signal<In, Clock>,
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
    /// 1: the terms and the other operands are registered (`*_qo`).
    terms_cut: Constant<Bit>,
    /// 1: the products are registered (`*_qp`).
    products_cut: Constant<Bit>,
    // the terms' cut
    t_qo0: Signal<Local, Bits<SB>>,
    t_qo1: Signal<Local, Bits<SB>>,
    t_qo2: Signal<Local, Bits<SB>>,
    n_qo0: Signal<Local, Bits<N>>,
    n_qo1: Signal<Local, Bits<N>>,
    n_qo2: Signal<Local, Bits<N>>,
    dl_qo0: Signal<Local, Bits<DB>>,
    dl_qo1: Signal<Local, Bits<DB>>,
    dl_qo2: Signal<Local, Bits<DB>>,
    dh_qo0: Signal<Local, Bits<DB>>,
    dh_qo1: Signal<Local, Bits<DB>>,
    dh_qo2: Signal<Local, Bits<DB>>,
    w_qo: Signal<Local, Bits<WB>>,
    // the products' cut
    ms_qp0: Signal<Local, Bits<SB>>,
    ms_qp1: Signal<Local, Bits<SB>>,
    ms_qp2: Signal<Local, Bits<SB>>,
    ml_qp0: Signal<Local, Bits<EB>>,
    ml_qp1: Signal<Local, Bits<EB>>,
    ml_qp2: Signal<Local, Bits<EB>>,
    mh_qp0: Signal<Local, Bits<EB>>,
    mh_qp1: Signal<Local, Bits<EB>>,
    mh_qp2: Signal<Local, Bits<EB>>,
    w_qp: Signal<Local, Bits<WB>>,
}

impl<
        const G: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
    > PlaneSums<G, N, DB, WB, SB, EB>
{
    /// A unit with the registers `cuts` names (bits [`cut::TERMS`], [`cut::PRODUCTS`]; others are
    /// ignored).
    pub fn new(cuts: usize) -> Self {
        assert!(
            SB == G + N + 5 && WB == G + N + 4 && EB == N + DB + 1 && SB <= 63 && EB <= 63,
            "PlaneSums<{G},{N},{DB},{WB},{SB},{EB}>: need WB = G+N+4, SB = G+N+5, EB = N+DB+1"
        );
        Self {
            clock: Default::default(),
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
            terms_cut: Constant::new(cuts & cut::TERMS != 0),
            products_cut: Constant::new(cuts & cut::PRODUCTS != 0),
            t_qo0: Default::default(),
            t_qo1: Default::default(),
            t_qo2: Default::default(),
            n_qo0: Default::default(),
            n_qo1: Default::default(),
            n_qo2: Default::default(),
            dl_qo0: Default::default(),
            dl_qo1: Default::default(),
            dl_qo2: Default::default(),
            dh_qo0: Default::default(),
            dh_qo1: Default::default(),
            dh_qo2: Default::default(),
            w_qo: Default::default(),
            ms_qp0: Default::default(),
            ms_qp1: Default::default(),
            ms_qp2: Default::default(),
            ml_qp0: Default::default(),
            ml_qp1: Default::default(),
            ml_qp2: Default::default(),
            mh_qp0: Default::default(),
            mh_qp1: Default::default(),
            mh_qp2: Default::default(),
            w_qp: Default::default(),
        }
    }

    /// Clocks from the operands in to the sums out for the cut points `cuts`.
    pub const fn latency(cuts: usize) -> usize {
        (cuts & cut::SUM_STEPS).count_ones() as usize
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
        let edge = self.clock.pos_edge();

        // Step 1: the terms; the cut holds them with the operands that go on beside them. The registers
        // are read before they are assigned: at the clock edge, the next step takes their old values.
        let p = [self.p0.val(), self.p1.val(), self.p2.val()].map(|x| v(x.to_u64(), G));
        let lo = [self.lo0.val(), self.lo1.val(), self.lo2.val()].map(|x| v(x.to_u64(), G));
        let hi = [self.hi0.val(), self.hi1.val(), self.hi2.val()].map(|x| v(x.to_u64(), G));
        let t = [0, 1, 2].map(|a| bits::<SB>(code(2 * p[a] - lo[a] - hi[a], SB)));
        let n = [self.n0.val(), self.n1.val(), self.n2.val()];
        let dl = [self.dl0.val(), self.dl1.val(), self.dl2.val()];
        let dh = [self.dh0.val(), self.dh1.val(), self.dh2.val()];
        let w = self.w.val();
        let (t_in, n_in, dl_in, dh_in, w_in) = (t, n, dl, dh, w);
        let (t, n, dl, dh, w) = if self.terms_cut.val() {
            (
                [self.t_qo0.val(), self.t_qo1.val(), self.t_qo2.val()],
                [self.n_qo0.val(), self.n_qo1.val(), self.n_qo2.val()],
                [self.dl_qo0.val(), self.dl_qo1.val(), self.dl_qo2.val()],
                [self.dh_qo0.val(), self.dh_qo1.val(), self.dh_qo2.val()],
                self.w_qo.val(),
            )
        } else {
            (t, n, dl, dh, w)
        };

        // Step 2: the products, at the width of their sums (which they fit).
        let n = n.map(|x| v(x.to_u64(), N));
        let ms = [0, 1, 2].map(|a| bits::<SB>(code(n[a] * v(t[a].to_u64(), SB), SB)));
        let ml = [0, 1, 2].map(|a| bits::<EB>(code(n[a] * v(dl[a].to_u64(), DB), EB)));
        let mh = [0, 1, 2].map(|a| bits::<EB>(code(n[a] * v(dh[a].to_u64(), DB), EB)));
        if edge {
            self.ms_qp0.next = ms[0];
            self.ms_qp1.next = ms[1];
            self.ms_qp2.next = ms[2];
            self.ml_qp0.next = ml[0];
            self.ml_qp1.next = ml[1];
            self.ml_qp2.next = ml[2];
            self.mh_qp0.next = mh[0];
            self.mh_qp1.next = mh[1];
            self.mh_qp2.next = mh[2];
            self.w_qp.next = w;
        }
        // The terms' registers take their new values after the products' took theirs from the old
        // (a rust-hdl local reads back what was last assigned to it).
        if edge {
            self.t_qo0.next = t_in[0];
            self.t_qo1.next = t_in[1];
            self.t_qo2.next = t_in[2];
            self.n_qo0.next = n_in[0];
            self.n_qo1.next = n_in[1];
            self.n_qo2.next = n_in[2];
            self.dl_qo0.next = dl_in[0];
            self.dl_qo1.next = dl_in[1];
            self.dl_qo2.next = dl_in[2];
            self.dh_qo0.next = dh_in[0];
            self.dh_qo1.next = dh_in[1];
            self.dh_qo2.next = dh_in[2];
            self.w_qo.next = w_in;
        }
        let (ms, ml, mh, w) = if self.products_cut.val() {
            (
                [self.ms_qp0.val(), self.ms_qp1.val(), self.ms_qp2.val()],
                [self.ml_qp0.val(), self.ml_qp1.val(), self.ml_qp2.val()],
                [self.mh_qp0.val(), self.mh_qp1.val(), self.mh_qp2.val()],
                self.w_qp.val(),
            )
        } else {
            (ms, ml, mh, w)
        };

        // Step 3: the sums.
        let sum = |x: [Bits<SB>; 3]| x.iter().map(|y| v(y.to_u64(), SB)).sum::<i64>();
        let sum_e = |x: [Bits<EB>; 3]| x.iter().map(|y| v(y.to_u64(), EB)).sum::<i64>();
        self.s.next = bits::<SB>(code(sum(ms) - v(w.to_u64(), WB), SB));
        self.den_lo.next = bits::<EB>(code(sum_e(ml), EB));
        self.den_hi.next = bits::<EB>(code(sum_e(mh), EB));
    }

    fn connect(&mut self) {
        self.s.connect();
        self.den_lo.connect();
        self.den_hi.connect();
        for x in [
            &mut self.t_qo0,
            &mut self.t_qo1,
            &mut self.t_qo2,
            &mut self.ms_qp0,
            &mut self.ms_qp1,
            &mut self.ms_qp2,
        ] {
            x.connect();
        }
        for x in [&mut self.n_qo0, &mut self.n_qo1, &mut self.n_qo2] {
            x.connect();
        }
        for x in [
            &mut self.dl_qo0,
            &mut self.dl_qo1,
            &mut self.dl_qo2,
            &mut self.dh_qo0,
            &mut self.dh_qo1,
            &mut self.dh_qo2,
        ] {
            x.connect();
        }
        for x in [
            &mut self.ml_qp0,
            &mut self.ml_qp1,
            &mut self.ml_qp2,
            &mut self.mh_qp0,
            &mut self.mh_qp1,
            &mut self.mh_qp2,
        ] {
            x.connect();
        }
        self.w_qo.connect();
        self.w_qp.connect();
    }

    fn hdl(&self) -> Verilog {
        // `terms_cut` and `products_cut` are this block's constants, emitted by rust-hdl as
        // localparams; the `*_qo` and `*_qp` registers are declared by rust-hdl as its local signals.
        // `dst` = `src` sign-extended from `w` to `to` bits.
        let ext = |dst: &str, src: &str, w: usize, to: usize| {
            if w == to {
                format!("wire signed [{}:0] {dst} = {src};\n", to - 1)
            } else {
                format!(
                    "wire signed [{}:0] {dst} = {{{{{}{{{src}[{}]}}}}, {src}}};\n",
                    to - 1,
                    to - w,
                    w - 1
                )
            }
        };
        // `dst` = `reg` when `on`, else `comb`, at `w` bits.
        let pick = |dst: &str, on: &str, reg: &str, comb: &str, w: usize| {
            format!("wire [{}:0] {dst} = {on} ? {reg} : {comb};\n", w - 1)
        };
        let mut v = String::from("// Step 1: the terms 2 p - lo - hi; cut `terms_cut` (*_qo).\n");
        let mut regs = String::new();
        for a in 0..3 {
            v += &ext(&format!("ps{a}"), &format!("p{a}"), G, SB);
            v += &ext(&format!("los{a}"), &format!("lo{a}"), G, SB);
            v += &ext(&format!("his{a}"), &format!("hi{a}"), G, SB);
            v += &format!(
                "wire signed [{}:0] tc{a} = (ps{a} <<< 1) - los{a} - his{a};\n",
                SB - 1
            );
            regs += &format!("   t_qo{a} <= tc{a};\n   n_qo{a} <= n{a};\n");
            regs += &format!("   dl_qo{a} <= dl{a};\n   dh_qo{a} <= dh{a};\n");
        }
        v += "initial begin\n";
        for a in 0..3 {
            v += &format!("   t_qo{a} = {SB}'d0; n_qo{a} = {N}'d0;\n");
            v += &format!("   dl_qo{a} = {DB}'d0; dh_qo{a} = {DB}'d0;\n");
            v += &format!("   ms_qp{a} = {SB}'d0; ml_qp{a} = {EB}'d0; mh_qp{a} = {EB}'d0;\n");
        }
        v += &format!("   w_qo = {WB}'d0; w_qp = {WB}'d0;\nend\n");
        v += &format!("always @(posedge clock) begin\n{regs}   w_qo <= w;\nend\n");
        for a in 0..3 {
            v += &pick(
                &format!("to{a}"),
                "terms_cut",
                &format!("t_qo{a}"),
                &format!("tc{a}"),
                SB,
            );
            v += &pick(
                &format!("no{a}"),
                "terms_cut",
                &format!("n_qo{a}"),
                &format!("n{a}"),
                N,
            );
            v += &pick(
                &format!("dlo{a}"),
                "terms_cut",
                &format!("dl_qo{a}"),
                &format!("dl{a}"),
                DB,
            );
            v += &pick(
                &format!("dho{a}"),
                "terms_cut",
                &format!("dh_qo{a}"),
                &format!("dh{a}"),
                DB,
            );
        }
        v += &pick("wo", "terms_cut", "w_qo", "w", WB);

        v +=
            "// Step 2: the nine products at the width of their sums; cut `products_cut` (*_qp).\n";
        let mut regs = String::new();
        for a in 0..3 {
            v += &ext(&format!("ns{a}"), &format!("no{a}"), N, SB);
            v += &ext(&format!("nd{a}"), &format!("no{a}"), N, EB);
            v += &ext(&format!("dls{a}"), &format!("dlo{a}"), DB, EB);
            v += &ext(&format!("dhs{a}"), &format!("dho{a}"), DB, EB);
            v += &format!(
                "wire signed [{}:0] msc{a} = ns{a} * $signed(to{a});\n",
                SB - 1
            );
            v += &format!("wire signed [{}:0] mlc{a} = nd{a} * dls{a};\n", EB - 1);
            v += &format!("wire signed [{}:0] mhc{a} = nd{a} * dhs{a};\n", EB - 1);
            regs += &format!(
                "   ms_qp{a} <= msc{a};\n   ml_qp{a} <= mlc{a};\n   mh_qp{a} <= mhc{a};\n"
            );
        }
        v += &format!("always @(posedge clock) begin\n{regs}   w_qp <= wo;\nend\n");
        for a in 0..3 {
            let (ms, ml, mh) = (format!("ms{a}"), format!("ml{a}"), format!("mh{a}"));
            v += &pick(
                &ms,
                "products_cut",
                &format!("ms_qp{a}"),
                &format!("msc{a}"),
                SB,
            );
            v += &pick(
                &ml,
                "products_cut",
                &format!("ml_qp{a}"),
                &format!("mlc{a}"),
                EB,
            );
            v += &pick(
                &mh,
                "products_cut",
                &format!("mh_qp{a}"),
                &format!("mhc{a}"),
                EB,
            );
        }
        v += &pick("wp", "products_cut", "w_qp", "wo", WB);
        v += &ext("ws", "wp", WB, SB);

        v += "// Step 3: the sums.\n";
        v += "always @(*) begin\n";
        v += "   s = $signed(ms0) + $signed(ms1) + $signed(ms2) - ws;\n";
        v += "   den_lo = ml0 + ml1 + ml2;\n";
        v += "   den_hi = mh0 + mh1 + mh2;\n";
        v += "end\n";
        Verilog::Custom(v)
    }
}
