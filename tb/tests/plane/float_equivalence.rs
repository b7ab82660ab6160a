//! Randomized equivalence: the rust-hdl `PlaneFloat` (slab + K cull planes) against
//! `golden::plane::float::node_float`, bit for bit, with latency and tag order checked by
//! `tb::dut::run_checked`: raw bit patterns (NaN and infinities included) and valid quantised world nodes
//! with fitted planes, with bubbles; and the reciprocal unit `FpRecip` against `recip_float` exhaustively
//! (16-bit formats) in both directions.

use golden::format::float::FloatFormat;
use golden::plane::float::{node_float, recip_float, CullFloatFormat};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::plane::float::PlaneFloatIo;
use rtl::plane::recip::FpRecip;
use rust_hdl::prelude::*;
use tb::dut::run_checked;
use tb::plane::float::{node_stream, raw_node, with_big_stack, CullFloatCtx, NodeVec};
use tb::rtl_sim::TesterSim;

/// Runs `n` cycles of a stream through the block, checked against the model.
fn equivalence<P: PlaneFloatIo>(name: &'static str, seed: u64, cycles: usize, raw_every: u64) {
    with_big_stack(move || equivalence_run::<P>(name, seed, cycles, raw_every));
}

fn equivalence_run<P: PlaneFloatIo>(name: &str, seed: u64, cycles: usize, raw_every: u64) {
    let ctx = CullFloatCtx::new(P::cull_format(), P::planes());
    let stream: Vec<NodeVec> = node_stream(ctx, seed, raw_every, 7).take(cycles).collect();
    let tests = stream.iter().filter(|v| v.is_some()).count();
    let mut dut = TesterSim::wrap(P::make());
    let t0 = std::time::Instant::now();
    let n = run_checked(&mut dut, stream.clone(), |v| {
        node_float(&ctx.cf, ctx.k, &v.0, &v.1)
    })
    .unwrap_or_else(|e| {
        let path = tb::out_dir().join("vcd").join(format!("{name}_fail.vcd"));
        let mut d = TesterSim::wrap(P::make()).vcd_to(&path).expect("VCD");
        let _ = run_checked(&mut d, stream.clone(), |v| {
            node_float(&ctx.cf, ctx.k, &v.0, &v.1)
        });
        panic!("{name}: {e}\nwaveform: {}", path.display())
    });
    assert_eq!(n, tests);
    eprintln!("{name}: {n} tests in {:.1} s", t0.elapsed().as_secs_f64());
}

/// The hit rate of world vectors is not degenerate (so the equivalence above exercises both outcomes).
fn world_hits<P: PlaneFloatIo>() {
    let ctx = CullFloatCtx::new(P::cull_format(), P::planes());
    let v: Vec<_> = node_stream(ctx, 99, 0, 0).take(2000).flatten().collect();
    let hits = v
        .iter()
        .filter(|(r, b)| node_float(&ctx.cf, ctx.k, r, b).hit)
        .count();
    assert!(hits > 100 && hits < 1900, "{hits} hits of 2000");
}

#[test]
fn plane_float_e5m10_k1_matches_model() {
    world_hits::<rtl::PlaneFloatE5M10K1>();
    equivalence::<rtl::PlaneFloatE5M10K1>("plane_float_e5m10_k1", 1, 30_000, 2);
}
#[test]
fn plane_float_e5m10_k2_matches_model() {
    equivalence::<rtl::PlaneFloatE5M10K2>("plane_float_e5m10_k2", 2, 30_000, 2);
}
#[test]
fn plane_float_e5m10_k4_matches_model() {
    equivalence::<rtl::PlaneFloatE5M10K4>("plane_float_e5m10_k4", 3, 15_000, 2);
}
#[test]
fn plane_float_e5m10_k8_matches_model() {
    equivalence::<rtl::PlaneFloatE5M10K8>("plane_float_e5m10_k8", 8, 5_000, 2);
}
#[test]
fn plane_float_e8m7_k2_matches_model() {
    world_hits::<rtl::PlaneFloatE8M7K2>();
    equivalence::<rtl::PlaneFloatE8M7K2>("plane_float_e8m7_k2", 4, 20_000, 2);
}
#[test]
fn plane_float_e8m7_k1_matches_model() {
    equivalence::<rtl::PlaneFloatE8M7K1>("plane_float_e8m7_k1", 5, 20_000, 3);
}
#[test]
fn plane_float_e8m23_k2_matches_model() {
    equivalence::<rtl::PlaneFloatE8M23K2>("plane_float_e8m23_k2", 6, 8_000, 2);
}

/// `FpRecip` against `recip_float` on the patterns `xs`, both directions; returns how many were checked.
fn recip_check<const E: usize, const M: usize, const N: usize>(
    xs: impl Iterator<Item = u32>,
) -> usize {
    let f = FloatFormat::new(E as u32, M as u32).unwrap();
    let cf = CullFloatFormat::over(f);
    let mut uut = FpRecip::<E, M, N>::new(cf.r);
    uut.connect_all();
    let mut checked = 0;
    for x in xs {
        for upper in [false, true] {
            uut.valid_in.next = true;
            uut.tag_in.next = bits::<16>(0);
            uut.mag.next = bits::<N>(x as u64);
            uut.upper.next = upper;
            for high in [false, true] {
                uut.clock.next = Clock { clk: high };
                assert!(simulate(&mut uut, 1000));
            }
            // Latency 1: the edge just applied registered this input's result.
            let want = recip_float(&cf, x, upper);
            let got = uut.r.val().to_u64() as u32;
            assert_eq!(got, want, "{} recip({x:#x}, upper {upper})", f.name());
            checked += 1;
        }
    }
    checked
}

/// binary16 and bfloat16: every pattern.
#[test]
fn fp_recip_matches_model_on_every_fp16_and_bf16_pattern() {
    assert_eq!(recip_check::<5, 10, 16>(0..=0xffff), 2 << 16);
    assert_eq!(recip_check::<8, 7, 16>(0..=0xffff), 2 << 16);
}

/// binary32: the model's result depends on the sign, the exponent and the table index (the top
/// `R = 8` fraction bits); every such combination is checked, with the 15 fraction bits the table does
/// not read all zeros, all ones, and one random pattern (an implementation that read them would differ
/// on some). Not all 2^32 patterns.
#[test]
fn fp_recip_matches_model_on_every_fp32_exponent_and_table_index() {
    let mut rng = Pcg64::seed_from_u64(31);
    let mut xs = vec![];
    for sign_exp_idx in 0u32..1 << 17 {
        let high = sign_exp_idx << 15;
        xs.extend([high, high | 0x7fff, high | rng.gen_range(1..0x7fff)]);
    }
    assert_eq!(recip_check::<8, 23, 32>(xs.into_iter()), 6 << 17);
}

/// Raw patterns only, back to back (no world vectors, no bubbles): the special-value paths.
#[test]
fn plane_float_e5m10_k2_raw_back_to_back() {
    with_big_stack(raw_back_to_back);
}

fn raw_back_to_back() {
    type P = rtl::PlaneFloatE5M10K2;
    let ctx = CullFloatCtx::new(P::cull_format(), 2);
    let mut rng = Pcg64::seed_from_u64(77);
    let stream: Vec<NodeVec> = (0..10_000)
        .map(|_| Some(raw_node(&ctx.cf, 2, &mut rng)))
        .collect();
    let mut dut = TesterSim::wrap(P::make());
    let n = run_checked(&mut dut, stream, |v| node_float(&ctx.cf, 2, &v.0, &v.1))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(n, 10_000);
}
