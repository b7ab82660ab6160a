//! A pipelined device under test, and a runner that streams tests through it and checks every result.

use std::collections::VecDeque;
use std::fmt::Debug;

/// A block that takes one test per clock and returns each result `latency()` clocks later, tagged.
///
/// Cycle convention: [`PipelinedDut::step`] drives the inputs of cycle `c`, applies the rising edge that
/// ends it, and returns the outputs of cycle `c + 1`. A block of latency `L` returns the result of a test
/// driven in cycle `c` during cycle `c + L`, i.e. from the call `step` number `c + L - 1`.
pub trait PipelinedDut {
    type In: Clone + Debug;
    type Out: Clone + Debug + PartialEq;
    /// Clocks from input to output.
    fn latency(&self) -> usize;
    /// One clock: drive `input` (or a bubble), clock, read the outputs (`Some` when `valid_out`).
    fn step(&mut self, input: Option<(u16, &Self::In)>) -> Option<(u16, Self::Out)>;
}

/// The first disagreement found by [`run_checked`].
#[derive(Clone, Debug)]
pub struct Mismatch<I: Debug, O: Debug> {
    /// Index of the test in the stream.
    pub index: usize,
    pub input: Option<I>,
    pub expected: Option<O>,
    pub got: Option<O>,
    pub why: String,
}

impl<I: Debug, O: Debug> std::fmt::Display for Mismatch<I, O> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "test #{}: {}\n  input:    {:?}\n  expected: {:?}\n  got:      {:?}",
            self.index, self.why, self.input, self.expected, self.got
        )
    }
}

/// Streams `tests` (`None` = a bubble cycle) through `dut`, compares each result with `model`, and checks
/// that every result leaves exactly `latency()` clocks after its test entered, in order, with its tag.
/// Returns the number of tests checked.
pub fn run_checked<D, It, M>(
    dut: &mut D,
    tests: It,
    model: M,
) -> Result<usize, Mismatch<D::In, D::Out>>
where
    D: PipelinedDut,
    It: IntoIterator<Item = Option<D::In>>,
    M: Fn(&D::In) -> D::Out,
{
    let lat = dut.latency();
    // (tag, cycle issued, index, input)
    let mut pending: VecDeque<(u16, usize, usize, D::In)> = VecDeque::new();
    let mut cycle = 0usize;
    let mut index = 0usize;
    let mut checked = 0usize;
    let mut check = |pending: &mut VecDeque<(u16, usize, usize, D::In)>,
                     out: Option<(u16, D::Out)>,
                     cycle: usize|
     -> Result<(), Mismatch<D::In, D::Out>> {
        // Outputs returned by step `cycle` belong to cycle `cycle + 1`.
        let due = pending
            .front()
            .map(|p| p.1 + lat == cycle + 1)
            .unwrap_or(false);
        match (out, due) {
            (None, false) => Ok(()),
            (Some((tag, got)), true) => {
                let (etag, _, idx, input) = pending.pop_front().unwrap();
                let exp = model(&input);
                if tag != etag || got != exp {
                    return Err(Mismatch {
                        index: idx,
                        why: if tag != etag {
                            format!("tag {tag} where {etag} was due")
                        } else {
                            "result differs from the model".into()
                        },
                        input: Some(input),
                        expected: Some(exp),
                        got: Some(got),
                    });
                }
                checked += 1;
                Ok(())
            }
            (Some((tag, got)), false) => Err(Mismatch {
                index: pending.front().map(|p| p.2).unwrap_or(usize::MAX),
                why: format!(
                    "valid_out with tag {tag} in cycle {} when no result was due (latency {lat})",
                    cycle + 1
                ),
                input: None,
                expected: None,
                got: Some(got),
            }),
            (None, true) => {
                let (etag, issued, idx, input) = pending.pop_front().unwrap();
                Err(Mismatch {
                    index: idx,
                    why: format!("no valid_out in cycle {} for tag {etag} issued in cycle {issued} (latency {lat})", cycle + 1),
                    expected: Some(model(&input)),
                    input: Some(input),
                    got: None,
                })
            }
        }
    };
    for t in tests {
        let out = match &t {
            Some(input) => {
                let tag = (index & 0xffff) as u16;
                pending.push_back((tag, cycle, index, input.clone()));
                index += 1;
                dut.step(Some((tag, input)))
            }
            None => dut.step(None),
        };
        check(&mut pending, out, cycle)?;
        cycle += 1;
    }
    // Flush: bubbles until every result is out, plus one cycle to catch a spurious valid.
    for _ in 0..=lat {
        let out = dut.step(None);
        check(&mut pending, out, cycle)?;
        cycle += 1;
    }
    Ok(checked)
}
