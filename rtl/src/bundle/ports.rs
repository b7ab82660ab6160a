//! The port codecs of the bundle pairs ([`crate::io`]): the bundle (in two-ray mode ray A) on `o_lo`,
//! `o_hi`, `d_lo`, `d_hi`, `t_lo`, `t_hi`; `two_rays`; ray B on `r_o_lo` .. `r_d_hi` and `r_t` (its
//! `t_hi`); the inner box on `in_lo/hi`, the outer on `out_lo/hi`; out `all_hit`, `all_miss`. The
//! fixed pair carries grid, direction and t codes, the float pair codes of its format: one codec
//! each, the same port names.

use crate::bundle::pair_fix::PairInput;
use crate::bundle::pair_float::FloatPairInput;
use crate::io::{need, PortCodec, Word};
use golden::bundle::edge::BoxPair;
use golden::format::fixed::FixBox;
use golden::slab::float::FloatBox;

/// A pair codec: `$input` is the pair's input type (with `sides()`), `$box` the box type.
macro_rules! pair_codec {
    ($(#[$doc:meta])* $name:ident, $input:ty, $box:ty) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub struct $name;

        impl PortCodec for $name {
            type Ray = $input;
            type Box = BoxPair<$box>;
            /// `(all_hit, all_miss)`.
            type Out = (bool, bool);

            fn input(&self, base: &str, idx: usize, input: &$input, p: &BoxPair<$box>) -> Option<i64> {
                let (a, r) = input.sides();
                let at = |v: &[_; 3]| v.get(idx).map(|&c| i64::from(c));
                match base {
                    "o_lo" => at(&a.o_lo),
                    "o_hi" => at(&a.o_hi),
                    "d_lo" => at(&a.d_lo),
                    "d_hi" => at(&a.d_hi),
                    "t_lo" => Some(i64::from(a.t_lo)),
                    "t_hi" => Some(i64::from(a.t_hi)),
                    "two_rays" => Some(input.is_two_rays() as i64),
                    "r_o_lo" => at(&r.o_lo),
                    "r_o_hi" => at(&r.o_hi),
                    "r_d_lo" => at(&r.d_lo),
                    "r_d_hi" => at(&r.d_hi),
                    "r_t" => Some(i64::from(r.t_hi)),
                    "in_lo" => at(&p.inner.lo),
                    "in_hi" => at(&p.inner.hi),
                    "out_lo" => at(&p.outer.lo),
                    "out_hi" => at(&p.outer.hi),
                    _ => None,
                }
            }

            fn outputs(&self, o: &(bool, bool)) -> Vec<(&'static str, i64)> {
                vec![("all_hit", o.0 as i64), ("all_miss", o.1 as i64)]
            }

            fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<(bool, bool), String> {
                Ok((need(word, "all_hit")?.flag(), need(word, "all_miss")?.flag()))
            }
        }
    };
}

pair_codec!(
    /// The fixed pair's ports (`BundleFix`): grid codes, direction codes, t codes.
    PairFixPorts,
    PairInput,
    FixBox
);

pair_codec!(
    /// The float pair's ports (`BundleFloat`): codes of the format.
    PairFloatPorts,
    FloatPairInput,
    FloatBox
);
