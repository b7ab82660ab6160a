//! The rust-hdl float adder and multiplier against `golden::format::float::FloatFormat::{add, mul}`, bit for bit,
//! in every rounding mode: every special pair, random pairs (with close pairs for cancellation), back to
//! back and with bubbles; exhaustive on E4M3.

use golden::format::float::{FloatFormat, Rounding};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use tb::dut::run_checked;
use tb::rtl_sim::{FpAddRtl, FpMulRtl};

fn pairs(f: &FloatFormat, n: usize, seed: u64) -> Vec<Option<(u32, u32)>> {
    let s = f.specials();
    let mut v: Vec<Option<(u32, u32)>> = s
        .iter()
        .flat_map(|&a| s.iter().map(move |&b| Some((a, b))))
        .collect();
    let mut rng = Pcg64::seed_from_u64(seed);
    for _ in 0..n {
        let a = rng.gen::<u32>() & f.mask();
        let b = match rng.gen_range(0..3) {
            0 => (a ^ rng.gen_range(0..64)) & f.mask(),
            1 => (a ^ f.sign_bit() ^ rng.gen_range(0..64)) & f.mask(),
            _ => rng.gen::<u32>() & f.mask(),
        };
        v.push(Some((a, b)));
        if rng.gen_ratio(1, 8) {
            v.push(None);
        }
    }
    v
}

fn check<const E: usize, const M: usize, const N: usize>(n: usize) {
    let f = FloatFormat::new(E as u32, M as u32).unwrap();
    for (k, mode) in Rounding::ALL.into_iter().enumerate() {
        let mut dut = FpAddRtl::<E, M, N>::new(mode);
        let got = run_checked(&mut dut, pairs(&f, n, k as u64), |&(a, b)| {
            f.add(a, b, mode)
        });
        got.unwrap_or_else(|e| panic!("{} add {mode:?}: {e}", f.name()));
        let mut dut = FpMulRtl::<E, M, N>::new(mode);
        let got = run_checked(&mut dut, pairs(&f, n, 10 + k as u64), |&(a, b)| {
            f.mul(a, b, mode)
        });
        got.unwrap_or_else(|e| panic!("{} mul {mode:?}: {e}", f.name()));
    }
}

#[test]
fn e8m23() {
    check::<8, 23, 32>(60_000);
}
#[test]
fn e8m15() {
    check::<8, 15, 24>(60_000);
}
#[test]
fn e8m7() {
    check::<8, 7, 16>(60_000);
}
#[test]
fn e5m10() {
    check::<5, 10, 16>(60_000);
}
#[test]
fn e4m3_exhaustive() {
    let f = FloatFormat::E4M3;
    for mode in Rounding::ALL {
        let all: Vec<_> = (0..=f.mask())
            .flat_map(|a| (0..=f.mask()).map(move |b| Some((a, b))))
            .collect();
        let mut dut = FpAddRtl::<4, 3, 8>::new(mode);
        run_checked(&mut dut, all.clone(), |&(a, b)| f.add(a, b, mode))
            .unwrap_or_else(|e| panic!("e4m3 add {mode:?}: {e}"));
        let mut dut = FpMulRtl::<4, 3, 8>::new(mode);
        run_checked(&mut dut, all, |&(a, b)| f.mul(a, b, mode))
            .unwrap_or_else(|e| panic!("e4m3 mul {mode:?}: {e}"));
    }
}

/// Every configuration of the optional cut points (`rtl::fp::add::cut`, `rtl::fp::mul::cut`), in every
/// rounding mode, on binary16 and binary32: the same results, each at its own latency (checked by
/// `run_checked`).
#[test]
fn every_cut_configuration_matches_the_model() {
    fn one<const E: usize, const M: usize, const N: usize>(n: usize) {
        let f = FloatFormat::new(E as u32, M as u32).unwrap();
        for (k, mode) in Rounding::ALL.into_iter().enumerate() {
            for cuts in 1..=rtl::fp::add::cut::ALL {
                let mut dut = FpAddRtl::<E, M, N>::with_cuts(mode, cuts);
                let seed = 20 + (k * 4 + cuts) as u64;
                run_checked(&mut dut, pairs(&f, n, seed), |&(a, b)| f.add(a, b, mode))
                    .unwrap_or_else(|e| panic!("{} add {mode:?} cuts {cuts:#x}: {e}", f.name()));
            }
            for cuts in 1..=rtl::fp::mul::cut::ALL {
                let mut dut = FpMulRtl::<E, M, N>::with_cuts(mode, cuts);
                let seed = 40 + (k * 4 + cuts) as u64;
                run_checked(&mut dut, pairs(&f, n, seed), |&(a, b)| f.mul(a, b, mode))
                    .unwrap_or_else(|e| panic!("{} mul {mode:?} cuts {cuts:#x}: {e}", f.name()));
            }
        }
    }
    one::<5, 10, 16>(20_000);
    one::<8, 23, 32>(20_000);
}

/// The latency check can fail: a unit with a cut point run as if it had none is caught.
#[test]
fn a_wrong_latency_is_caught() {
    let f = FloatFormat::FP16;
    let mode = Rounding::NearestEven;
    let mut add = FpAddRtl::<5, 10, 16>::with_cuts(mode, rtl::fp::add::cut::NORM);
    let r = tb::dut::run_checked(
        &mut Claimed(&mut add, rtl::fp::add::FP_ADD_LATENCY),
        pairs(&f, 200, 3),
        |&(a, b)| f.add(a, b, mode),
    );
    assert!(r.is_err(), "a 4-clock adder passed as a 3-clock one");
}

/// A unit that claims another latency than its own.
struct Claimed<'a, D>(&'a mut D, usize);

impl<D: tb::dut::PipelinedDut> tb::dut::PipelinedDut for Claimed<'_, D> {
    type In = D::In;
    type Out = D::Out;
    fn latency(&self) -> usize {
        self.1
    }
    fn step(&mut self, input: Option<(u16, &D::In)>) -> Option<(u16, D::Out)> {
        self.0.step(input)
    }
}

/// The check can fail: a unit rounding toward -inf disagrees with the round-to-nearest model.
#[test]
fn a_wrong_mode_is_caught() {
    let f = FloatFormat::FP16;
    let mut add = FpAddRtl::<5, 10, 16>::new(Rounding::Down);
    let r = run_checked(&mut add, pairs(&f, 2_000, 9), |&(a, b)| {
        f.add(a, b, Rounding::NearestEven)
    });
    assert!(
        r.is_err(),
        "round-down adder matched the round-to-nearest model"
    );
    let mut mul = FpMulRtl::<5, 10, 16>::new(Rounding::Up);
    let r = run_checked(&mut mul, pairs(&f, 2_000, 9), |&(a, b)| {
        f.mul(a, b, Rounding::NearestEven)
    });
    assert!(
        r.is_err(),
        "round-up multiplier matched the round-to-nearest model"
    );
}
