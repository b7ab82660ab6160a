//! The rust-hdl float comparator against `golden::format::float::FloatFormat::{lt, le}`: exhaustively over E4M3
//! pairs, and over every special pair plus 100,000 random pairs in binary32 and binary16.

use golden::format::float::FloatFormat;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::fp::cmp::FpCmp;
use rust_hdl::prelude::*;

fn check<const N: usize>(f: FloatFormat, pairs: impl Iterator<Item = (u32, u32)>) -> usize {
    let mut c = FpCmp::<N>::new(f.inf(false) as u64);
    c.connect_all();
    let mut n = 0;
    for (a, b) in pairs {
        c.a.next = bits::<N>(a as u64);
        c.b.next = bits::<N>(b as u64);
        assert!(simulate(&mut c, 100));
        assert_eq!(
            (c.lt.val(), c.le.val()),
            (f.lt(a, b), f.le(a, b)),
            "{} {a:#x} vs {b:#x}",
            f.name()
        );
        n += 1;
    }
    n
}

fn random(f: FloatFormat, seed: u64) -> impl Iterator<Item = (u32, u32)> {
    let s = f.specials();
    let mut rng = Pcg64::seed_from_u64(seed);
    let specials: Vec<_> = s
        .iter()
        .flat_map(|&a| s.iter().map(move |&b| (a, b)))
        .collect();
    let rand: Vec<_> = (0..100_000)
        .map(|_| {
            let a = rng.gen::<u32>() & f.mask();
            (
                a,
                if rng.gen() {
                    (a ^ rng.gen_range(0..4)) & f.mask()
                } else {
                    rng.gen::<u32>() & f.mask()
                },
            )
        })
        .collect();
    specials.into_iter().chain(rand)
}

#[test]
fn e4m3_exhaustive() {
    let f = FloatFormat::E4M3;
    assert_eq!(
        check::<8>(
            f,
            (0..=f.mask()).flat_map(|a| (0..=f.mask()).map(move |b| (a, b)))
        ),
        65536
    );
}

#[test]
fn fp32_and_fp16() {
    assert!(check::<32>(FloatFormat::FP32, random(FloatFormat::FP32, 1)) > 100_000);
    assert!(check::<16>(FloatFormat::FP16, random(FloatFormat::FP16, 2)) > 100_000);
}
