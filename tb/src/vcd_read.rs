//! Reads a VCD back (with the `vcd` crate) to measure a block's latency from its waveform.

use std::collections::HashMap;
use std::io::BufReader;
use std::path::Path;

/// The scalar value changes of a few named signals, and the times of the clock's rising edges.
#[derive(Debug, Default)]
pub struct Trace {
    /// Rising-edge times of `clock`.
    pub clock_edges: Vec<u64>,
    /// Per requested signal: (time, value) of each change.
    pub changes: HashMap<String, Vec<(u64, bool)>>,
}

/// Reads the VCD at `path`, following the scalar signals named `names` (and `clock`) in the top scope's
/// first child scope (rust-hdl writes the block as scope `uut`).
pub fn read_trace(path: &Path, names: &[&str]) -> Result<Trace, String> {
    let f = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut parser = vcd::Parser::new(BufReader::new(f));
    let header = parser
        .parse_header()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut ids: HashMap<vcd::IdCode, String> = HashMap::new();
    let mut want: Vec<&str> = names.to_vec();
    want.push("clock");
    for n in &want {
        let var = header
            .find_var(&["uut", n])
            .ok_or_else(|| format!("{}: no signal uut.{n}", path.display()))?;
        ids.insert(var.code, n.to_string());
    }
    let mut trace = Trace::default();
    let mut now = 0u64;
    let mut clock = false;
    for cmd in parser {
        match cmd.map_err(|e| format!("{}: {e}", path.display()))? {
            vcd::Command::Timestamp(t) => now = t,
            vcd::Command::ChangeScalar(id, v) => {
                if let Some(n) = ids.get(&id) {
                    let b = v == vcd::Value::V1;
                    if n == "clock" {
                        if b && !clock {
                            trace.clock_edges.push(now);
                        }
                        clock = b;
                    } else {
                        trace.changes.entry(n.clone()).or_default().push((now, b));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(trace)
}

impl Trace {
    /// Times at which `name` rose.
    pub fn rises(&self, name: &str) -> Vec<u64> {
        let mut last = false;
        let mut out = vec![];
        for &(t, v) in self.changes.get(name).map(|v| v.as_slice()).unwrap_or(&[]) {
            if v && !last {
                out.push(t);
            }
            last = v;
        }
        out
    }

    /// Clock rising edges in `(from, to]`.
    pub fn edges_between(&self, from: u64, to: u64) -> usize {
        self.clock_edges
            .iter()
            .filter(|&&t| t > from && t <= to)
            .count()
    }

    /// Checks that `valid_out` rises exactly `latency` clock edges after each rise of `valid_in`, and
    /// that both rise `rises` times (an isolated test rises once; a back-to-back burst once in all).
    pub fn check_valid_latency(&self, rises: usize, latency: usize) -> Result<(), String> {
        let (ins, outs) = (self.rises("valid_in"), self.rises("valid_out"));
        if ins.len() != rises || outs.len() != rises {
            return Err(format!(
                "expected {rises} rises each: valid_in rises at {ins:?}, valid_out at {outs:?}"
            ));
        }
        for (i, o) in ins.iter().zip(&outs) {
            let n = self.edges_between(*i, *o);
            if n != latency {
                return Err(format!(
                    "valid_in at {i}, valid_out at {o}: {n} clock edges, expected {latency}"
                ));
            }
        }
        Ok(())
    }
}

/// Whether the VCD at `path` declares the signal `name` in the block's scope `uut`.
pub fn has_signal(path: &Path, name: &str) -> Result<bool, String> {
    let f = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let header = vcd::Parser::new(BufReader::new(f))
        .parse_header()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(header.find_var(&["uut", name]).is_some())
}
