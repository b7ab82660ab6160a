//! The port codecs of the slab testers: what each data port of `SlabFix` and `SlabFloat` carries
//! (the fields of the golden ray, box and result types), written once for every driver, harness and
//! word file ([`crate::io`]). The cull-plane testers reuse them for their slab ports.

use crate::io::{need, PortCodec, Word};
use golden::format::fixed::{FixBox, FixRay};
use golden::slab::fix::SlabFixOut;
use golden::slab::float::{FloatBox, FloatRay, SlabFloatOut};

/// The values of the interval outputs `hit`, `t_entry`, `t_exit` (every slab and cull-plane tester).
pub fn interval_outputs(hit: bool, t_entry: i64, t_exit: i64) -> Vec<(&'static str, i64)> {
    vec![
        ("hit", hit as i64),
        ("t_entry", t_entry),
        ("t_exit", t_exit),
    ]
}

/// The interval outputs read back: `hit`, and the words of `t_entry` and `t_exit`.
pub fn interval_words(word: &dyn Fn(&str) -> Option<Word>) -> Result<(bool, Word, Word), String> {
    Ok((
        need(word, "hit")?.flag(),
        need(word, "t_entry")?,
        need(word, "t_exit")?,
    ))
}

/// The fixed slab tester's ports: `ray_o_lo/hi` (grid codes), `ray_m_lo/hi` (inverse-direction
/// magnitudes), `ray_neg`, `ray_t_min/max` (t codes), `box_lo/hi` (grid codes); out `hit`,
/// `t_entry`, `t_exit` (t codes, signed).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SlabFixPorts;

impl PortCodec for SlabFixPorts {
    type Ray = FixRay;
    type Box = FixBox;
    type Out = SlabFixOut;

    fn input(&self, base: &str, idx: usize, r: &FixRay, b: &FixBox) -> Option<i64> {
        let at = |v: &[i64; 3]| v.get(idx).copied();
        match base {
            "ray_o_lo" => at(&r.o_lo),
            "ray_o_hi" => at(&r.o_hi),
            "ray_m_lo" => r.m_lo.get(idx).map(|&m| m as i64),
            "ray_m_hi" => r.m_hi.get(idx).map(|&m| m as i64),
            "ray_neg" => r.neg.get(idx).map(|&n| n as i64),
            "ray_t_min" => Some(r.t_min),
            "ray_t_max" => Some(r.t_max),
            "box_lo" => at(&b.lo),
            "box_hi" => at(&b.hi),
            _ => None,
        }
    }

    fn outputs(&self, o: &SlabFixOut) -> Vec<(&'static str, i64)> {
        interval_outputs(o.hit, o.t_entry, o.t_exit)
    }

    fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<SlabFixOut, String> {
        let (hit, en, ex) = interval_words(word)?;
        Ok(SlabFixOut {
            hit,
            t_entry: en.signed(),
            t_exit: ex.signed(),
        })
    }
}

/// The float slab tester's ports: the same names as [`SlabFixPorts`], each a code of the format
/// (`ray_neg` and `hit` one bit).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SlabFloatPorts;

impl PortCodec for SlabFloatPorts {
    type Ray = FloatRay;
    type Box = FloatBox;
    type Out = SlabFloatOut;

    fn input(&self, base: &str, idx: usize, r: &FloatRay, b: &FloatBox) -> Option<i64> {
        let at = |v: &[u32; 3]| v.get(idx).map(|&c| c as i64);
        match base {
            "ray_o_lo" => at(&r.o_lo),
            "ray_o_hi" => at(&r.o_hi),
            "ray_m_lo" => at(&r.m_lo),
            "ray_m_hi" => at(&r.m_hi),
            "ray_neg" => r.neg.get(idx).map(|&n| n as i64),
            "ray_t_min" => Some(r.t_min as i64),
            "ray_t_max" => Some(r.t_max as i64),
            "box_lo" => at(&b.lo),
            "box_hi" => at(&b.hi),
            _ => None,
        }
    }

    fn outputs(&self, o: &SlabFloatOut) -> Vec<(&'static str, i64)> {
        interval_outputs(o.hit, o.t_entry as i64, o.t_exit as i64)
    }

    fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<SlabFloatOut, String> {
        let (hit, en, ex) = interval_words(word)?;
        Ok(SlabFloatOut {
            hit,
            t_entry: en.bits as u32,
            t_exit: ex.bits as u32,
        })
    }
}
