//! `Delay3`: a value delayed by three clocks (three registers in series), for side data that must meet a
//! 3-clock unit's result.
//!
//! # Inputs
//! `clock`, `d`.
//! # Outputs
//! `q`: `d` of three clocks ago.

use rust_hdl::prelude::*;

/// Three-clock delay line; see the module documentation.
#[derive(LogicBlock, Default)]
pub struct Delay3<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    r1: DFF<T>,
    r2: DFF<T>,
    r3: DFF<T>,
}

impl<T: Synth> Logic for Delay3<T> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r1, r2, r3);
        self.r1.d.next = self.d.val();
        self.r2.d.next = self.r1.q.val();
        self.r3.d.next = self.r2.q.val();
        self.q.next = self.r3.q.val();
    }
}
