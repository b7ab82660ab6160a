//! `Cut`: a named cut point of a pipeline, a register or a wire as the block's configuration chooses.
//!
//! A tester whose pipeline depth is a parameter (as FPnew's `NumPipeRegs` and the stage split of
//! Berkeley HardFloat make theirs) places a `Cut` wherever a register may go, and builds it with
//! [`Cut::new`]`(on)` from its configuration. With `on` the output `q` is `d` one clock later; without,
//! `q` is `d` in the same clock and the register's output is unused (synthesis removes it). The choice
//! is a constant of the instance (a Verilog `localparam`), so the exported module is the pipeline the
//! configuration names, and the rust-hdl simulation runs the same structure.
//!
//! # Inputs
//! `clock`, `d`.
//! # Outputs
//! `q`: `d` of one clock ago (a register), or `d` (a wire).

use rust_hdl::prelude::*;

/// A register or a wire; see the module documentation.
#[derive(LogicBlock)]
pub struct Cut<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    r: DFF<T>,
    registered: Constant<Bit>,
}

impl<T: Synth> Cut<T> {
    /// A register (`on`) or a wire.
    pub fn new(on: bool) -> Self {
        Cut {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            r: Default::default(),
            registered: Constant::new(on),
        }
    }

    /// An array of `N` cuts, all registers (`on`) or all wires.
    pub fn array<const N: usize>(on: bool) -> [Self; N] {
        std::array::from_fn(|_| Self::new(on))
    }

    /// `N` cuts for a chain: the first `regs` registers, the rest wires (a delay of `regs` clocks).
    pub fn chain<const N: usize>(regs: usize) -> [Self; N] {
        assert!(
            regs <= N,
            "a chain of {N} cuts holds at most {N} registers, not {regs}"
        );
        std::array::from_fn(|i| Self::new(i < regs))
    }
}

impl<T: Synth> Logic for Cut<T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.r.clock.next = self.clock.val();
        self.r.d.next = self.d.val();
        if self.registered.val() {
            self.q.next = self.r.q.val();
        } else {
            self.q.next = self.d.val();
        }
    }
}

/// The most clocks a [`Wait`] delays.
pub const MAX_WAIT: usize = 10;

/// `Wait`: side data held for as many clocks as the unit it travels beside takes, a chain of
/// [`MAX_WAIT`] cuts of which the first `regs` are registers ([`Cut::chain`]).
///
/// # Inputs
/// `clock`, `d`.
/// # Outputs
/// `q`: `d` of `regs` clocks ago.
#[derive(LogicBlock)]
pub struct Wait<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    step: [Cut<T>; MAX_WAIT],
}

impl<T: Synth> Wait<T> {
    /// A delay of `regs` clocks (at most [`MAX_WAIT`]).
    pub fn new(regs: usize) -> Self {
        Wait {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            step: Cut::chain(regs),
        }
    }
}

impl<T: Synth> Logic for Wait<T> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..10 {
            self.step[i].clock.next = self.clock.val();
        }
        self.step[0].d.next = self.d.val();
        self.step[1].d.next = self.step[0].q.val();
        self.step[2].d.next = self.step[1].q.val();
        self.step[3].d.next = self.step[2].q.val();
        self.step[4].d.next = self.step[3].q.val();
        self.step[5].d.next = self.step[4].q.val();
        self.step[6].d.next = self.step[5].q.val();
        self.step[7].d.next = self.step[6].q.val();
        self.step[8].d.next = self.step[7].q.val();
        self.step[9].d.next = self.step[8].q.val();
        self.q.next = self.step[9].q.val();
    }
}

/// The most clocks a [`Line`] delays: two [`Wait`]s in series.
pub const MAX_LINE: usize = 2 * MAX_WAIT;

/// `Line`: side data held for up to [`MAX_LINE`] clocks, two [`Wait`]s in series, for a unit whose
/// latency is a parameter that may exceed [`MAX_WAIT`] (the 13-clock float bundle pair).
///
/// # Inputs
/// `clock`, `d`.
/// # Outputs
/// `q`: `d` of `regs` clocks ago.
#[derive(LogicBlock)]
pub struct Line<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    first: Wait<T>,
    second: Wait<T>,
}

impl<T: Synth> Line<T> {
    /// A delay of `regs` clocks (at most [`MAX_LINE`]).
    pub fn new(regs: usize) -> Self {
        assert!(
            regs <= MAX_LINE,
            "a Line delays at most {MAX_LINE} clocks, not {regs}"
        );
        let first = regs.min(MAX_WAIT);
        Line {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            first: Wait::new(first),
            second: Wait::new(regs - first),
        }
    }

    /// An array of `N` lines of `regs` clocks each.
    pub fn array<const N: usize>(regs: usize) -> [Self; N] {
        std::array::from_fn(|_| Self::new(regs))
    }
}

impl<T: Synth> Logic for Line<T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.first.clock.next = self.clock.val();
        self.second.clock.next = self.clock.val();
        self.first.d.next = self.d.val();
        self.second.d.next = self.first.q.val();
        self.q.next = self.second.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clocks a cut with `d` and returns `q` before and after the rising edge.
    fn edge(c: &mut Cut<Bits<8>>, d: u64) -> (u64, u64) {
        c.d.next = bits::<8>(d);
        c.clock.next = Clock { clk: false };
        assert!(simulate(c, 100));
        let before = c.q.val().to_u64();
        c.clock.next = Clock { clk: true };
        assert!(simulate(c, 100));
        (before, c.q.val().to_u64())
    }

    #[test]
    fn a_register_delays_by_one_clock_and_a_wire_not_at_all() {
        let mut reg = Cut::<Bits<8>>::new(true);
        reg.connect_all();
        assert_eq!(edge(&mut reg, 5), (0, 5));
        assert_eq!(edge(&mut reg, 9), (5, 9));
        let mut wire = Cut::<Bits<8>>::new(false);
        wire.connect_all();
        assert_eq!(edge(&mut wire, 5), (5, 5));
        assert_eq!(edge(&mut wire, 9), (9, 9));
    }

    #[test]
    fn a_wait_delays_by_its_register_count() {
        const _: () = assert!(MAX_WAIT == 10, "Wait::update is unrolled for 10 steps");
        for regs in [0, 1, 3, 10] {
            let mut w = Wait::<Bits<8>>::new(regs);
            w.connect_all();
            let mut seen = vec![];
            for d in 1..=14u64 {
                w.d.next = bits::<8>(d);
                w.clock.next = Clock { clk: false };
                assert!(simulate(&mut w, 100));
                w.clock.next = Clock { clk: true };
                assert!(simulate(&mut w, 100));
                seen.push(w.q.val().to_u64());
            }
            // After the edge of input d, q is the input of regs - 1 edges before (d itself for a wire).
            let want: Vec<u64> = (1..=14u64)
                .map(|d| {
                    if regs == 0 {
                        d
                    } else {
                        (d + 1).saturating_sub(regs as u64)
                    }
                })
                .collect();
            assert_eq!(seen, want, "{regs} registers");
        }
    }

    #[test]
    fn a_line_delays_by_its_register_count_beyond_one_wait() {
        for regs in [3, 9, 13, MAX_LINE] {
            let mut w = Line::<Bits<8>>::new(regs);
            w.connect_all();
            let mut seen = vec![];
            for d in 1..=30u64 {
                w.d.next = bits::<8>(d);
                w.clock.next = Clock { clk: false };
                assert!(simulate(&mut w, 100));
                w.clock.next = Clock { clk: true };
                assert!(simulate(&mut w, 100));
                seen.push(w.q.val().to_u64());
            }
            let want: Vec<u64> = (1..=30u64)
                .map(|d| (d + 1).saturating_sub(regs as u64))
                .collect();
            assert_eq!(seen, want, "{regs} registers");
        }
    }
}
