//! Drives rust-hdl blocks cycle by cycle with the direct loop (about 5x the throughput of rust-hdl's
//! threaded `Simulation`, per RUST_HDL_NOTES.md), optionally writing a VCD.

use crate::dut::PipelinedDut;
use golden::format::fixed::FixFormat;
use rtl::slab::fix::SlabFixIo;
use rtl::slab::float::SlabFloatIo;
use rtl::TesterIo;
use rust_hdl::core::vcd_probe::{write_vcd_change, write_vcd_dump, write_vcd_header, VCDProbe};
use rust_hdl::prelude::*;
use std::path::Path;

/// Half a clock period in VCD time units (ps): the clock period is 10 ps.
pub const HALF_PERIOD: u64 = 5;

/// A pipelined tester ([`TesterIo`]: slab, cull-plane or bundle pair, either datapath) in simulation.
pub struct TesterSim<S: TesterIo> {
    /// The block (read its outputs for cross-simulation).
    pub uut: S,
    vcd: Option<VCDProbe<crate::vcd_plain::VcdFile>>,
    cycle: u64,
}

/// The fixed slab tester's driver.
pub type SlabFixRtl<S> = TesterSim<S>;
/// The float slab tester's driver.
pub type SlabFloatRtl<S> = TesterSim<S>;

impl<S: SlabFixIo> TesterSim<S> {
    /// A fixed slab tester for `fmt`.
    pub fn new(fmt: &FixFormat) -> Self {
        Self::wrap(S::for_format(fmt))
    }

    /// The same, writing every signal of the block to a VCD file at `path`.
    pub fn with_vcd(fmt: &FixFormat, path: &Path) -> std::io::Result<Self> {
        Self::wrap(S::for_format(fmt)).vcd_to(path)
    }
}

impl<S: SlabFloatIo> TesterSim<S> {
    /// A float slab tester.
    pub fn float() -> Self {
        Self::wrap(S::make())
    }

    /// The same, writing every signal of the block to a VCD file at `path`.
    pub fn float_with_vcd(path: &Path) -> std::io::Result<Self> {
        Self::wrap(S::make()).vcd_to(path)
    }
}

impl<S: TesterIo> TesterSim<S> {
    /// Wraps a block (connected here).
    pub fn wrap(mut uut: S) -> Self {
        uut.connect_all();
        TesterSim {
            uut,
            vcd: None,
            cycle: 0,
        }
    }

    /// Starts writing every signal of the block to a VCD file at `path`.
    pub fn vcd_to(mut self, path: &Path) -> std::io::Result<Self> {
        let w = crate::vcd_plain::create(path)?;
        let mut v = write_vcd_header(w, &self.uut);
        v = write_vcd_dump(v, &self.uut);
        self.vcd = Some(v);
        Ok(self)
    }

    fn settle(&mut self, t: u64) {
        if !simulate(&mut self.uut, 1000) {
            panic!("the slab tester failed to converge in cycle {}", self.cycle);
        }
        if let Some(mut v) = self.vcd.take() {
            v.timestamp(t).expect("VCD write");
            self.vcd = Some(write_vcd_change(v, &self.uut));
        }
    }
}

impl<S: TesterIo> PipelinedDut for TesterSim<S> {
    type In = (S::Ray, S::Box);
    type Out = S::Out;

    fn latency(&self) -> usize {
        S::LATENCY
    }

    fn step(&mut self, input: Option<(u16, &(S::Ray, S::Box))>) -> Option<(u16, S::Out)> {
        self.uut.drive(input.map(|(tag, (r, b))| (tag, r, b)));
        self.uut.set_clock(false);
        let t = self.cycle * 2 * HALF_PERIOD;
        self.settle(t);
        self.uut.set_clock(true);
        self.settle(t + HALF_PERIOD);
        self.cycle += 1;
        self.uut.result()
    }
}

/// Drivers for the two-operand float units (`FpAdd`, `FpMul`): operand pairs in, result patterns out.
macro_rules! fp_unit_driver {
    ($name:ident, $block:ident, $latency:path, $what:literal) => {
        #[doc = concat!("A float ", $what, " in simulation.")]
        pub struct $name<const E: usize, const M: usize, const N: usize> {
            /// The block.
            pub uut: rtl::$block<E, M, N>,
            latency: usize,
        }

        impl<const E: usize, const M: usize, const N: usize> $name<E, M, N> {
            /// The unit without optional cut points.
            pub fn new(mode: golden::format::float::Rounding) -> Self {
                Self::with_cuts(mode, 0)
            }

            /// The unit with the optional cut points `cuts` (its `with_cuts`).
            pub fn with_cuts(mode: golden::format::float::Rounding, cuts: usize) -> Self {
                let mut uut = rtl::$block::with_cuts(mode, cuts);
                uut.connect_all();
                $name {
                    uut,
                    latency: $latency(cuts),
                }
            }
        }

        impl<const E: usize, const M: usize, const N: usize> PipelinedDut for $name<E, M, N> {
            type In = (u32, u32);
            type Out = u32;

            fn latency(&self) -> usize {
                self.latency
            }

            fn step(&mut self, input: Option<(u16, &(u32, u32))>) -> Option<(u16, u32)> {
                match input {
                    Some((tag, (a, b))) => {
                        self.uut.valid_in.next = true;
                        self.uut.tag_in.next = bits::<{ rtl::TAG_BITS }>(tag as u64);
                        self.uut.a.next = bits::<N>(*a as u64);
                        self.uut.b.next = bits::<N>(*b as u64);
                    }
                    None => self.uut.valid_in.next = false,
                }
                for high in [false, true] {
                    self.uut.clock.next = Clock { clk: high };
                    assert!(
                        simulate(&mut self.uut, 1000),
                        concat!("float ", $what, " failed to converge")
                    );
                }
                if self.uut.valid_out.val() {
                    Some((
                        self.uut.tag_out.val().to_u64() as u16,
                        self.uut.y.val().to_u64() as u32,
                    ))
                } else {
                    None
                }
            }
        }
    };
}

fp_unit_driver!(FpAddRtl, FpAdd, rtl::fp::add::fp_add_latency, "adder");
fp_unit_driver!(FpMulRtl, FpMul, rtl::fp::mul::fp_mul_latency, "multiplier");

/// Any clocked block in simulation, one clock at a time (the direct loop), with an optional VCD: the
/// driver of the blocks whose inputs are not one test a clock (the results processors).
pub struct Clocked<B: Block> {
    /// The block (drive its inputs, read its outputs).
    pub uut: B,
    vcd: Option<VCDProbe<crate::vcd_plain::VcdFile>>,
    cycle: u64,
}

impl<B: Block> Clocked<B> {
    /// Wraps a block (connected here).
    pub fn new(mut uut: B) -> Self {
        uut.connect_all();
        Clocked {
            uut,
            vcd: None,
            cycle: 0,
        }
    }

    /// Starts writing every signal of the block to a VCD file at `path`.
    pub fn vcd_to(mut self, path: &Path) -> std::io::Result<Self> {
        let w = crate::vcd_plain::create(path)?;
        let v = write_vcd_header(w, &self.uut);
        self.vcd = Some(write_vcd_dump(v, &self.uut));
        Ok(self)
    }

    fn settle(&mut self, t: u64) {
        if !simulate(&mut self.uut, 1000) {
            panic!("the block failed to converge in cycle {}", self.cycle);
        }
        if let Some(mut v) = self.vcd.take() {
            v.timestamp(t).expect("VCD write");
            self.vcd = Some(write_vcd_change(v, &self.uut));
        }
    }

    /// One clock with the inputs already driven: `set_clock(uut, level)` sets the clock input low, the
    /// block settles, then high (the edge), and it settles again.
    pub fn clock(&mut self, set_clock: impl Fn(&mut B, bool)) {
        set_clock(&mut self.uut, false);
        let t = self.cycle * 2 * HALF_PERIOD;
        self.settle(t);
        set_clock(&mut self.uut, true);
        self.settle(t + HALF_PERIOD);
        self.cycle += 1;
    }
}
