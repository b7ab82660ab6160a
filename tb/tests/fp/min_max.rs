//! The float minimum/maximum unit against `golden::format::float::FloatFormat::{min, max}`: in rust-hdl
//! exhaustively over E4M3 pairs and over every special pair plus 100,000 random pairs in binary32 and
//! binary16; its Verilog lint-clean, accepted by Icarus and bit-exact in Verilator on the same pairs.

use golden::format::float::FloatFormat;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::fp::min_max::FpMinMax;
use rust_hdl::prelude::*;

fn pairs(f: FloatFormat, seed: u64) -> Vec<(u32, u32)> {
    let s = f.specials();
    let mut v: Vec<(u32, u32)> = s
        .iter()
        .flat_map(|&a| s.iter().map(move |&b| (a, b)))
        .collect();
    let mut rng = Pcg64::seed_from_u64(seed);
    for _ in 0..100_000 {
        let a = rng.gen::<u32>() & f.mask();
        v.push((
            a,
            if rng.gen() {
                (a ^ f.sign_bit() ^ rng.gen_range(0..2)) & f.mask()
            } else {
                rng.gen::<u32>() & f.mask()
            },
        ));
    }
    v
}

fn rtl_check<const N: usize>(f: FloatFormat, pairs: &[(u32, u32)]) {
    let mut u = FpMinMax::<N>::new(&f);
    u.connect_all();
    for &(a, b) in pairs {
        u.valid_in.next = true;
        u.a.next = bits::<N>(a as u64);
        u.b.next = bits::<N>(b as u64);
        for high in [false, true] {
            u.clock.next = Clock { clk: high };
            assert!(simulate(&mut u, 100));
        }
        let (mn, mx) = (u.min.val().to_u64() as u32, u.max.val().to_u64() as u32);
        assert!(u.valid_out.val());
        assert_eq!(
            (mn, mx),
            (f.min(a, b), f.max(a, b)),
            "{} min/max of {a:#x}, {b:#x}",
            f.name()
        );
    }
}

fn verilog_check<const N: usize>(f: FloatFormat, pairs: Vec<(u32, u32)>) {
    let module = format!("fp_min_max_{}", f.name());
    let mut u = FpMinMax::<N>::new(&f);
    let v = rtl::verilog::verilog_named(&mut u, &module);
    let path = tb::verilog_tools::write(&v, &module);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    let h = tb::verilator::build(&v, &module, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let (ia, ib, iv) = (
        h.input_index("a").unwrap(),
        h.input_index("b").unwrap(),
        h.input_index("valid_in").unwrap(),
    );
    let (omin, omax) = (
        h.output_index("min").unwrap(),
        h.output_index("max").unwrap(),
    );
    let ni = h.inputs.len();
    let feed = pairs.clone();
    let records = feed.into_iter().map(move |(a, b)| {
        let mut r = vec![0u64; ni];
        (r[ia], r[ib], r[iv]) = (a as u64, b as u64, 1);
        r
    });
    let mut k = 0;
    h.stream(records, |_, out| {
        let (a, b) = pairs[k];
        k += 1;
        if (out[omin] as u32, out[omax] as u32) != (f.min(a, b), f.max(a, b)) {
            return Err(format!(
                "{module}: ({a:#x}, {b:#x}) gives ({:#x}, {:#x}) in Verilator",
                out[omin], out[omax]
            ));
        }
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(k, pairs.len());
}

#[test]
fn e4m3_exhaustive() {
    let f = FloatFormat::E4M3;
    let all: Vec<_> = (0..=f.mask())
        .flat_map(|a| (0..=f.mask()).map(move |b| (a, b)))
        .collect();
    rtl_check::<8>(f, &all);
    verilog_check::<8>(f, all);
}

#[test]
fn fp32_and_fp16() {
    rtl_check::<32>(FloatFormat::FP32, &pairs(FloatFormat::FP32, 1));
    rtl_check::<16>(FloatFormat::FP16, &pairs(FloatFormat::FP16, 2));
    verilog_check::<32>(FloatFormat::FP32, pairs(FloatFormat::FP32, 3));
    verilog_check::<16>(FloatFormat::FP16, pairs(FloatFormat::FP16, 4));
}
