//! proptest with shrinking, and a waveform of the shrunk failing case: [`shrinking_check`] for any block
//! and strategy (the results processor's job programs, [`crate::bundle::split::split_shrinking`]), and
//! [`shrinking_equivalence`] for any pipelined block whose inputs come from a random generator (the
//! cull-plane testers, the bundle pairs; the slab testers have their own field-by-field strategies in
//! [`crate::slab::strategies`]).
//!
//! The block's raw-input generator (`raw_node`, `raw_bundle`, ...: every code over its range, special
//! values weighted up) draws from a [`Tape`], a random source that replays a list of words proptest
//! chooses (then a fixed pseudo-random sequence). proptest shrinks the lists (fewer tests per burst,
//! shorter tapes, smaller words), and the generator turns a shrunk tape into a simpler input: a zero word
//! draws the low end of every range and the first branch of every choice. This is the "choice sequence" idea of
//! Hypothesis (MacIver, Hatfield-Dodds et al., "Hypothesis: A new approach to property-based testing",
//! JOSS 4(43), 2019), on proptest's own shrinking of vectors and integers.
//!
//! A failure is reported with the shrunk burst decoded into the block's inputs, the first mismatch, and
//! the path of a VCD of the shrunk burst replayed on a fresh block (`out/vcd/<name>_<hash>.vcd`).

use crate::dut::{run_checked, PipelinedDut};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestError, TestRunner};
use rand::RngCore;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// A random source replaying `words`, then a fixed pseudo-random sequence (SplitMix64 from the tape's
/// length), so that a generator which draws until a choice comes up (`raw_bundle` recurses while it draws
/// its two-ray branch) ends on every tape, the all-zero one included.
pub struct Tape<'a> {
    words: &'a [u64],
    pos: usize,
}

/// SplitMix64's output for state `x` (Steele, Lea and Flood, "Fast splittable pseudorandom number
/// generators", OOPSLA 2014).
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl<'a> Tape<'a> {
    pub fn new(words: &'a [u64]) -> Self {
        Tape { words, pos: 0 }
    }
}

impl RngCore for Tape<'_> {
    fn next_u64(&mut self) -> u64 {
        let w = match self.words.get(self.pos) {
            Some(&w) => w,
            None => splitmix64(((self.words.len() as u64) << 32) ^ self.pos as u64),
        };
        self.pos += 1;
        w
    }
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }
    fn fill_bytes(&mut self, dest: &mut [u8]) {
        for chunk in dest.chunks_mut(8) {
            let w = self.next_u64().to_le_bytes();
            chunk.copy_from_slice(&w[..chunk.len()]);
        }
    }
    fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), rand::Error> {
        self.fill_bytes(dest);
        Ok(())
    }
}

/// One burst: per clock a bubble (`None`) or a test drawn from its tape.
pub type Burst = Vec<Option<Vec<u64>>>;

/// Bursts of 1 to 8 clocks, a quarter of them bubbles, each test from a tape of up to `words` words.
pub fn bursts(words: usize) -> impl Strategy<Value = Burst> {
    let clock = prop_oneof![
        1 => Just(None),
        3 => prop::collection::vec(any::<u64>(), 0..words).prop_map(Some),
    ];
    prop::collection::vec(clock, 1..9)
}

/// Decodes a burst into the block's inputs.
pub fn decode<I>(burst: &Burst, gen: &impl Fn(&mut Tape) -> I) -> Vec<Option<I>> {
    burst
        .iter()
        .map(|t| t.as_ref().map(|w| gen(&mut Tape::new(w))))
        .collect()
}

/// The proptest driver every shrinking check here shares: `cases` values of `strategy`, each judged by
/// `check` (`Err` with the mismatch); a failing value is shrunk by proptest, replayed by `replay` with the
/// path of a VCD to write (`out/vcd/<name>_<hash of the value as printed>.vcd`), and reported in a panic naming the
/// shrunk value as `describe` writes it, the mismatch and the path (after `waveform: `).
pub fn shrinking_check<S>(
    name: &str,
    cases: u32,
    strategy: S,
    check: impl FnMut(&S::Value) -> Result<(), String>,
    replay: impl FnOnce(&S::Value, &Path),
    describe: impl FnOnce(&S::Value) -> String,
) where
    S: Strategy,
{
    let check = std::cell::RefCell::new(check);
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        // Each shrink step simulates the block; a thousand steps reach a one-test burst (or a one-job
        // program) with many words zero, and bound the time a failure takes to report.
        max_shrink_iters: 1024,
        ..Config::default()
    });
    match runner.run(&strategy, |v| {
        (check.borrow_mut())(&v).map_err(TestCaseError::fail)
    }) {
        Ok(()) => {}
        Err(TestError::Fail(why, v)) => {
            let path = vcd_path(name, &v);
            // A waveform of an earlier run with the same shrunk value must not stand in for this one.
            std::fs::remove_file(&path).ok();
            replay(&v, &path);
            panic!(
                "{name}: RTL differs from the model on the shrunk {}\n{why}\nwaveform: {}",
                describe(&v),
                path.display()
            );
        }
        Err(e) => panic!("{name}: {e}"),
    }
}

/// Checks `cases` bursts of `strategy` (each decoded into the block's inputs, a bubble as `None`)
/// through the block `make(None)` against `model`: results, tags and latency (`run_checked`). On a
/// failure, proptest's shrunk burst is replayed on `make(Some(path))`, which must write a VCD at `path`
/// ([`shrinking_check`]).
pub fn shrinking_pipelined<D, S, M>(
    name: &str,
    cases: u32,
    strategy: S,
    decode: impl Fn(&S::Value) -> Vec<Option<D::In>>,
    make: impl Fn(Option<&Path>) -> D,
    model: M,
) where
    D: PipelinedDut,
    S: Strategy,
    M: Fn(&D::In) -> D::Out,
{
    let mut dut = make(None);
    // Set while a burst runs: a burst that panicked (the model, or a simulation that does not settle)
    // left the block mid-burst, and the next case starts on a fresh one.
    let mut dirty = false;
    shrinking_check(
        name,
        cases,
        strategy,
        |burst| {
            if std::mem::replace(&mut dirty, true) {
                dut = make(None);
            }
            let r = run_checked(&mut dut, decode(burst), &model)
                .map(|_| ())
                .map_err(|m| {
                    // A failing run stops with results still in the pipeline: drain them, so the next
                    // case (proptest's shrinking) is judged on its own burst.
                    for _ in 0..=dut.latency() {
                        dut.step(None);
                    }
                    m.to_string()
                });
            dirty = false;
            r
        },
        |burst, path| {
            let mut d = make(Some(path));
            let _ = run_checked(&mut d, decode(burst), &model);
        },
        |burst| format!("burst {:?}", decode(burst)),
    );
}

/// [`shrinking_pipelined`] on bursts of tapes ([`bursts`]), each test drawn by `gen`. Tapes hold up to
/// `words` words (enough for every field the generator draws; more are never read).
pub fn shrinking_equivalence<D, G, M>(
    name: &str,
    cases: u32,
    words: usize,
    make: impl Fn(Option<&Path>) -> D,
    gen: G,
    model: M,
) where
    D: PipelinedDut,
    G: Fn(&mut Tape) -> D::In,
    M: Fn(&D::In) -> D::Out,
{
    shrinking_pipelined(name, cases, bursts(words), |b| decode(b, &gen), make, model)
}

/// Runs `f`, a [`shrinking_check`] expected to fail (a mutation test), and returns its panic message
/// after checking that it reports a shrunk value and that its waveform exists and holds `signal`.
pub fn expect_caught(signal: &str, f: impl FnOnce() + std::panic::UnwindSafe) -> String {
    let msg = match std::panic::catch_unwind(f) {
        Ok(()) => panic!("a wrong model passed"),
        Err(e) => e.downcast_ref::<String>().cloned().unwrap_or_default(),
    };
    let vcd = PathBuf::from(msg.rsplit("waveform: ").next().unwrap_or("").trim());
    assert!(vcd.exists(), "no VCD at {}: {msg}", vcd.display());
    assert!(std::fs::read_to_string(&vcd).unwrap().contains(signal));
    assert!(msg.contains("on the shrunk "), "{msg}");
    msg
}

fn vcd_path(name: &str, value: &impl std::fmt::Debug) -> PathBuf {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    format!("{value:?}").hash(&mut h);
    crate::out_dir()
        .join("vcd")
        .join(format!("{name}_{:08x}.vcd", h.finish() as u32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    #[test]
    fn a_tape_replays_its_words_then_a_fixed_sequence() {
        let w = [u64::MAX, 7];
        let mut t = Tape::new(&w);
        assert_eq!((t.next_u64(), t.next_u64()), (u64::MAX, 7));
        // Past the tape: the same pseudo-random words for the same tape length, not all zeros.
        let past: Vec<u64> = (0..4).map(|_| t.next_u64()).collect();
        let mut again = Tape::new(&[1, 2]);
        again.next_u64();
        again.next_u64();
        assert_eq!(past, (0..4).map(|_| again.next_u64()).collect::<Vec<_>>());
        assert!(past.iter().all(|&w| w != 0));
        // Zero words draw the low end of a range.
        let mut z = Tape::new(&[0, 0]);
        assert_eq!(z.gen_range(5..100), 5);
        assert_eq!(z.gen_range(-3i64..=3), -3);
    }
}
