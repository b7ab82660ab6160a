//! An exact characterisation of correct rounding, used to check the float model in every mode.
//!
//! A result `r` of rounding the exact value `x` is correct when: toward -inf, `r <= x < next_up(r)`;
//! toward +inf, `next_down(r) < x <= r`; to nearest, `r` is the nearer of those two (ties to the even
//! fraction), with the IEEE overflow thresholds. Exact zeros follow IEEE's sign rules. The exact value is
//! formed in rational arithmetic from the operands, independently of the model's integer datapath.

use crate::exact::rat;
use crate::format::float::{Class, FloatFormat, Rounding};
use num_rational::BigRational;

/// An operation of the float model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Add,
    Sub,
    Mul,
}

fn value(f: &FloatFormat, x: u32) -> BigRational {
    rat(f.to_f64(x))
}

/// Checks `f.op(a, b, mode)` against the exact result; the error describes the disagreement.
pub fn check_op(f: &FloatFormat, op: Op, a: u32, b: u32, mode: Rounding) -> Result<(), String> {
    let r = match op {
        Op::Add => f.add(a, b, mode),
        Op::Sub => f.sub(a, b, mode),
        Op::Mul => f.mul(a, b, mode),
    };
    let (fa, fb) = (f.to_f64(a), f.to_f64(b));
    let ctx = || {
        format!(
            "{} {op:?} {mode:?}: {a:#x} ({fa:e}), {b:#x} ({fb:e}) gave {r:#x} ({:e})",
            f.name(),
            f.to_f64(r)
        )
    };
    // Non-finite operands: the IEEE rules, through f64 (exact for these cases).
    let special = |x: f64| x.is_nan() || x.is_infinite();
    if special(fa) || special(fb) {
        let want = match op {
            Op::Add => fa + fb,
            Op::Sub => fa - fb,
            Op::Mul => fa * fb,
        };
        let got = f.to_f64(r);
        return if (want.is_nan() && got.is_nan())
            || (want == got && want.is_sign_negative() == got.is_sign_negative())
        {
            Ok(())
        } else {
            Err(format!("{}: expected {want}", ctx()))
        };
    }
    let (ra, rb) = (rat(fa), rat(fb));
    let x = match op {
        Op::Add => &ra + &rb,
        Op::Sub => &ra - &rb,
        Op::Mul => &ra * &rb,
    };
    let zero = BigRational::from_integer(0.into());
    let rneg = f.is_negative(r);
    if x == zero {
        // IEEE sign of an exact zero: products take the xor of signs; sums of equal-signed zeros keep it;
        // otherwise +0, except -0 when rounding down.
        let want_neg = match op {
            Op::Mul => fa.is_sign_negative() != fb.is_sign_negative(),
            _ => {
                let nb = if op == Op::Sub {
                    !fb.is_sign_negative()
                } else {
                    fb.is_sign_negative()
                };
                if fa == 0.0 && fb == 0.0 && fa.is_sign_negative() == nb {
                    nb
                } else {
                    mode == Rounding::Down
                }
            }
        };
        return if f.class(r) == Class::Zero && rneg == want_neg {
            Ok(())
        } else {
            Err(format!("{}: expected a zero, negative = {want_neg}", ctx()))
        };
    }
    // Nonzero exact value: a zero result must carry the exact value's sign.
    if f.class(r) == Class::Zero && rneg != (x < zero) {
        return Err(format!("{}: zero of the wrong sign", ctx()));
    }
    let down = |v: u32| f.next_down(v);
    let up = |v: u32| f.next_up(v);
    // Value of a result or its neighbour, with +-inf standing for the first value past the largest finite.
    let beyond = rat(f.to_f64(f.max_finite(false)))
        + (rat(f.to_f64(f.max_finite(false))) - value(f, f.max_finite(false) - 1));
    let ext = |v: u32| -> BigRational {
        match f.class(v) {
            Class::Inf if f.is_negative(v) => -beyond.clone(),
            Class::Inf => beyond.clone(),
            _ => value(f, v),
        }
    };
    let ok = match mode {
        Rounding::Down => match f.class(r) {
            Class::Inf if rneg => x < -ext(f.max_finite(false)),
            Class::Inf => false,
            _ => value(f, r) <= x && (f.class(up(r)) == Class::Inf || x < ext(up(r))),
        },
        Rounding::Up => match f.class(r) {
            Class::Inf if !rneg => x > ext(f.max_finite(false)),
            Class::Inf => false,
            _ => x <= value(f, r) && (f.class(down(r)) == Class::Inf || ext(down(r)) < x),
        },
        Rounding::NearestEven => {
            let d = f.add_like_round_down(&x);
            let u = f.next_up(d);
            let (dv, uv) = (ext(d), ext(u));
            let (ld, lu) = (&x - &dv, &uv - &x);
            let want = if ld < lu {
                d
            } else if lu < ld {
                u
            } else if f.class(u) == Class::Inf {
                // IEEE 754 7.4: a tie at max + half an ulp already overflows.
                u
            } else if (u & 1) == 1 {
                d
            } else {
                u
            };
            // Both zeros are "the same" choice here; the sign was checked above.
            r == want || (f.class(r) == Class::Zero && f.class(want) == Class::Zero)
        }
    };
    if ok {
        Ok(())
    } else {
        Err(ctx())
    }
}

impl FloatFormat {
    /// The largest value of the format at or below the rational `x` (for the checks only: a slow search).
    pub fn add_like_round_down(&self, x: &BigRational) -> u32 {
        use num_traits::ToPrimitive;
        // An f64 near x, rounded down into the format, then corrected by stepping.
        let mut r = self.from_f64(x.to_f64().unwrap_or(0.0), Rounding::Down);
        while self.class(r) != Class::Inf && &rat(self.to_f64(r)) > x {
            r = self.next_down(r);
        }
        loop {
            let n = self.next_up(r);
            if self.class(n) == Class::Inf || &rat(self.to_f64(n)) > x {
                return r;
            }
            r = n;
        }
    }
}
