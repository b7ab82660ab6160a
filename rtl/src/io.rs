//! `TesterIo`: the testbench-side interface of every pipelined tester (one test a clock: the slab
//! testers, the cull-plane testers and the bundle pairs, on both datapaths), so one driver, one stream
//! runner and one cross-simulation loop serve them all.

use rust_hdl::prelude::*;

/// A pipelined tester seen from a testbench: typed inputs and outputs mirroring its golden model.
pub trait TesterIo: Block {
    /// The quantised ray type (`FixRay`, `FloatRay`).
    type Ray: Clone + Copy + std::fmt::Debug + PartialEq + Send + 'static;
    /// The quantised box type.
    type Box: Clone + Copy + std::fmt::Debug + PartialEq + Send + 'static;
    /// The result type.
    type Out: Clone + Copy + std::fmt::Debug + PartialEq;
    /// Clocks from a test in to its result out.
    const LATENCY: usize;
    /// Sets the clock input.
    fn set_clock(&mut self, high: bool);
    /// Sets the synchronous reset input `rst`: high at a clock edge, every valid bit of the pipeline
    /// is cleared, so no test in flight leaves; data registers keep their values.
    fn set_reset(&mut self, on: bool);
    /// Drives one test: `None` drives a bubble (`valid_in` low).
    fn drive(&mut self, test: Option<(u16, &Self::Ray, &Self::Box)>);
    /// Reads the outputs: `Some((tag, result))` when `valid_out` is high.
    fn result(&self) -> Option<(u16, Self::Out)>;
    /// The raw value of an output port, by its Verilog name (for cross-simulation).
    fn output_word(&self, port: &str) -> Option<u64>;
}
