//! The port interface of every pipelined tester (one test a clock: the slab testers, the cull-plane
//! testers and the bundle pairs, on both datapaths), described once per block and once per family:
//!
//! - **The block's ports** are its struct fields (name, and width from the field's type), as the
//!   exported Verilog, the Verilator harness and the VCD name them. [`tester_ports!`] lists a block's
//!   data ports once; from the list come its [`TesterIo`] methods that set an input and read an output
//!   by its Verilog name. The control ports every tester shares (`clock`, `rst`, `valid_in`,
//!   `tag_in`, `valid_out`, `tag_out`) are part of the macro.
//! - **The family's [`PortCodec`]** says once what each data port carries: the value of an input for a
//!   test, the values of the outputs for a result, and a result read back from its output words. The
//!   rust-hdl driver ([`TesterIo::drive`], [`TesterIo::result`]), the Verilator harness's words, the
//!   cross-simulation loop, the port-word files (`rtu encode`, `rtu decode`) and the reset check all
//!   encode and decode through it, so a port's encoding is written in one place.
//!
//! What each port means, in words, is in the family's datasheet (`tb::ip::family_docs`), whose tests
//! check that it describes every port of the exported Verilog and only those.

use rust_hdl::prelude::*;

/// One port's word: its bits (the low `width` bits) and its width.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Word {
    pub bits: u64,
    pub width: usize,
}

impl Word {
    /// The word of `value` on a `width`-bit port: its low `width` bits (two's complement for a
    /// negative value).
    pub fn of(value: i64, width: usize) -> Word {
        let mask = if width >= 64 {
            u64::MAX
        } else {
            (1u64 << width) - 1
        };
        Word {
            bits: value as u64 & mask,
            width,
        }
    }

    /// The word read as a two's complement number.
    pub fn signed(&self) -> i64 {
        golden::format::fixed::sext(self.bits, self.width)
    }

    /// The word of a one-bit port as a flag.
    pub fn flag(&self) -> bool {
        self.bits != 0
    }
}

/// What the data ports of a family of testers carry: written once per family, used by every driver,
/// harness and file of its blocks. Values are integers that the port's width truncates (two's
/// complement for signed fields), so one codec serves every width of a family.
pub trait PortCodec: Copy + Send + Sync + std::fmt::Debug + 'static {
    /// The test's ray part (`FixRay`, `NodeFloatRay`, `PairInput`, ...).
    type Ray: Clone + Copy + std::fmt::Debug + PartialEq + Send + 'static;
    /// The test's box part.
    type Box: Clone + Copy + std::fmt::Debug + PartialEq + Send + 'static;
    /// The result.
    type Out: Clone + Copy + std::fmt::Debug + PartialEq;
    /// The value on data input `base[idx]` (`idx` 0 for a scalar port) for the test `(r, b)`; `None`
    /// when the family has no such input.
    fn input(&self, base: &str, idx: usize, r: &Self::Ray, b: &Self::Box) -> Option<i64>;
    /// The value of each data output (every output but `valid_out` and `tag_out`) for the result `o`.
    fn outputs(&self, o: &Self::Out) -> Vec<(&'static str, i64)>;
    /// The result of the data output words that `word` gives by port name; an error names a port
    /// `word` does not have.
    fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<Self::Out, String>;
}

/// The word of output `name` from `word`, or an error naming the port.
pub fn need(word: &dyn Fn(&str) -> Option<Word>, name: &str) -> Result<Word, String> {
    word(name).ok_or_else(|| format!("no output port {name}"))
}

/// A signal, or an array of signals, seen as port words: the storage behind [`tester_ports!`].
pub trait PortBits {
    /// Number of ports (1 for a scalar, `N` for an array).
    fn count(&self) -> usize;
    /// Drives port `idx` with the low bits of `value`.
    fn set(&mut self, idx: usize, value: i64);
    /// The word of port `idx`.
    fn word(&self, idx: usize) -> Word;
}

/// [`PortBits`] of the signals of direction `$d` (rust-hdl reads a signal's value per direction).
macro_rules! port_bits {
    ($d:ty) => {
        impl PortBits for Signal<$d, bool> {
            fn count(&self) -> usize {
                1
            }
            fn set(&mut self, _: usize, value: i64) {
                self.next = value & 1 != 0;
            }
            fn word(&self, _: usize) -> Word {
                Word {
                    bits: self.val() as u64,
                    width: 1,
                }
            }
        }

        impl<const N: usize> PortBits for Signal<$d, Bits<N>> {
            fn count(&self) -> usize {
                1
            }
            fn set(&mut self, _: usize, value: i64) {
                self.next = bits::<N>(Word::of(value, N).bits);
            }
            fn word(&self, _: usize) -> Word {
                Word {
                    bits: self.val().to_u64(),
                    width: N,
                }
            }
        }
    };
}

port_bits!(In);
port_bits!(Out);

impl<P: PortBits, const K: usize> PortBits for [P; K] {
    fn count(&self) -> usize {
        K
    }
    fn set(&mut self, idx: usize, value: i64) {
        self[idx].set(0, value);
    }
    fn word(&self, idx: usize) -> Word {
        self[idx].word(0)
    }
}

/// A pipelined tester seen from a testbench: typed inputs and outputs mirroring its golden model,
/// through its family's [`PortCodec`]. A block implements the port methods with [`tester_ports!`];
/// the typed driver and reader are provided.
pub trait TesterIo: Block {
    /// The quantised ray type (`FixRay`, `FloatRay`, ...).
    type Ray: Clone + Copy + std::fmt::Debug + PartialEq + Send + 'static;
    /// The quantised box type.
    type Box: Clone + Copy + std::fmt::Debug + PartialEq + Send + 'static;
    /// The result type.
    type Out: Clone + Copy + std::fmt::Debug + PartialEq;
    /// The family's port codec.
    type Ports: PortCodec<Ray = Self::Ray, Box = Self::Box, Out = Self::Out>;
    /// Clocks from a test in to its result out.
    const LATENCY: usize;
    /// The codec of this block's ports (its configuration, from the block's parameters).
    fn ports() -> Self::Ports;
    /// Sets the clock input.
    fn set_clock(&mut self, high: bool);
    /// Sets the synchronous reset input `rst`: high at a clock edge, every valid bit of the pipeline
    /// is cleared, so no test in flight leaves; data registers keep their values.
    fn set_reset(&mut self, on: bool);
    /// Sets `valid_in` and, when valid, `tag_in`.
    fn set_valid(&mut self, valid: bool, tag: u16);
    /// Drives every data input with `value(base, idx)`.
    fn set_inputs(&mut self, value: &dyn Fn(&str, usize) -> i64);
    /// The word of an output port, by its Verilog name (`valid_out`, `tag_out`, `hit`, ...; an element of an array port as `<name>_<index>`).
    fn output(&self, port: &str) -> Option<Word>;

    /// Drives one test: `None` drives a bubble (`valid_in` low; the data inputs keep their values).
    fn drive(&mut self, test: Option<(u16, &Self::Ray, &Self::Box)>) {
        match test {
            Some((tag, r, b)) => {
                let p = Self::ports();
                self.set_valid(true, tag);
                self.set_inputs(&|base, idx| {
                    p.input(base, idx, r, b)
                        .unwrap_or_else(|| panic!("the port codec {p:?} has no input {base}"))
                });
            }
            None => self.set_valid(false, 0),
        }
    }

    /// Reads the outputs: `Some((tag, result))` when `valid_out` is high.
    fn result(&self) -> Option<(u16, Self::Out)> {
        if !self.output("valid_out")?.flag() {
            return None;
        }
        let tag = self.output("tag_out")?.bits as u16;
        let out = Self::ports()
            .result(&|p| self.output(p))
            .unwrap_or_else(|e| panic!("the port codec does not fit the block: {e}"));
        Some((tag, out))
    }

    /// The raw value of an output port, by its Verilog name (for cross-simulation).
    fn output_word(&self, port: &str) -> Option<u64> {
        self.output(port).map(|w| w.bits)
    }
}

/// The port methods of a [`TesterIo`] implementation, from the block's data input and output fields
/// (scalars or arrays of signals, named as the Verilog ports are: an array `box_lo` is `box_lo_0`,
/// `box_lo_1`, ...). Invoke inside the `impl TesterIo` block:
///
/// ```ignore
/// rtl::tester_ports!(inputs: ray_o_lo, box_lo; outputs: hit, t_entry, t_exit);
/// ```
#[macro_export]
macro_rules! tester_ports {
    (inputs: $($i:ident),+ ; outputs: $($o:ident),+ $(;)?) => {
        fn set_clock(&mut self, high: bool) {
            self.clock.next = rust_hdl::prelude::Clock { clk: high };
        }

        fn set_reset(&mut self, on: bool) {
            self.rst.next = on;
        }

        fn set_valid(&mut self, valid: bool, tag: u16) {
            self.valid_in.next = valid;
            if valid {
                $crate::io::PortBits::set(&mut self.tag_in, 0, tag as i64);
            }
        }

        fn set_inputs(&mut self, value: &dyn Fn(&str, usize) -> i64) {
            $(
                for idx in 0..$crate::io::PortBits::count(&self.$i) {
                    $crate::io::PortBits::set(&mut self.$i, idx, value(stringify!($i), idx));
                }
            )+
        }

        fn output(&self, port: &str) -> Option<$crate::io::Word> {
            let (base, idx) = $crate::verilog::split_port(port);
            let pick = |p: &dyn $crate::io::PortBits, idx: Option<usize>| match (p.count(), idx) {
                (1, None) => Some(p.word(0)),
                (n, Some(i)) if n > 1 && i < n => Some(p.word(i)),
                _ => None,
            };
            // A scalar whose name ends in `_<digits>` is found by its whole name.
            match port {
                "valid_out" => return pick(&self.valid_out, None),
                "tag_out" => return pick(&self.tag_out, None),
                $(stringify!($o) => return pick(&self.$o, None),)+
                _ => {}
            }
            match base {
                $(stringify!($o) => pick(&self.$o, idx),)+
                _ => None,
            }
        }
    };
}
