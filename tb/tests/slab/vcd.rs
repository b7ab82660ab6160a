//! Waveforms: the rust-hdl simulation writes a VCD on request; reading it back with the `vcd` crate,
//! for the fixed and the float tester,
//! `valid_out` rises exactly the block's latency (4 clocks, 6 for the deep fixed tester) clock edges after `valid_in`, for single tests separated
//! by bubbles and for a back-to-back burst.

use golden::format::fixed::FixFormat;
use golden::slab::fix::slab_fix;
use golden::slab::gen::GenKind;
use tb::campaign::slab_vectors;
use tb::dut::run_checked;
use tb::rtl_sim::SlabFixRtl;
use tb::vcd_read::read_trace;

#[test]
fn valid_leaves_latency_clocks_after_it_enters() {
    valid_latency::<rtl::SlabFixB12>("slab_fix_b12_latency.vcd", 4);
}

/// The 6-clock tester: `valid_out` rises 6 edges after `valid_in`, as `slab_fix_latency` says.
#[test]
fn valid_leaves_6_clocks_after_it_enters_the_deep_tester() {
    assert_eq!(
        rtl::slab::fix::slab_fix_latency(rtl::slab::fix::SLAB_FIX_CUTS_DEEP),
        6
    );
    valid_latency::<rtl::SlabFixB12P6>("slab_fix_b12_p6_latency.vcd", 6);
}

fn valid_latency<S: rtl::slab::fix::SlabFixIo>(name: &str, latency: usize) {
    assert_eq!(S::LATENCY, latency);
    let fmt = FixFormat::b12();
    let path = tb::out_dir().join("vcd").join(name);
    let tests: Vec<_> = slab_vectors(fmt, GenKind::Mixed, 11, 6, false).collect();
    // Three isolated tests (each followed by 6 bubbles), then three back to back.
    let mut stream = vec![];
    for t in &tests[..3] {
        stream.push(*t);
        stream.extend(std::iter::repeat_n(None, 6));
    }
    stream.extend(tests[3..].iter().cloned());
    {
        let mut dut = SlabFixRtl::<S>::with_vcd(&fmt, &path).unwrap();
        let n = run_checked(&mut dut, stream, |v| slab_fix(&fmt, &v.0, &v.1))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(n, 6);
    }
    // The ports carry the exported Verilog's plain names, never rust-hdl's `ray_o_lo$0`.
    assert!(tb::vcd_read::has_signal(&path, "ray_o_lo_0").unwrap());
    assert!(!tb::vcd_read::has_signal(&path, "ray_o_lo$0").unwrap());
    let trace = read_trace(&path, &["valid_in", "valid_out"]).unwrap();
    // Isolated tests: one rise each; the burst: one more rise.
    trace
        .check_valid_latency(4, latency)
        .unwrap_or_else(|e| panic!("{e}"));
}

/// The same for the float tester (binary16): `valid_out` rises `S::LATENCY` edges after `valid_in`.
fn float_valid_latency<S: rtl::slab::float::SlabFloatIo>(file: &str, latency: usize) {
    use golden::format::float::FloatFormat;
    use golden::slab::float::{quantize_box, quantize_ray, slab_float};
    let f = S::format();
    assert_eq!(f, FloatFormat::FP16);
    let path = tb::out_dir().join("vcd").join(file);
    let (lo, hi) = tb::campaign::campaign_bounds();
    let tests: Vec<_> = golden::slab::gen::SlabGen::new(GenKind::Mixed, lo, hi, 1.0 / 64.0, 12)
        .take(4)
        .map(|(r, b)| Some((quantize_ray(&f, &r).unwrap(), quantize_box(&f, &b).unwrap())))
        .collect();
    let mut stream = vec![tests[0]];
    stream.extend(std::iter::repeat_n(None, 16));
    stream.extend(tests[1..].iter().cloned());
    {
        let mut dut = tb::rtl_sim::SlabFloatRtl::<S>::float_with_vcd(&path).unwrap();
        let n = run_checked(&mut dut, stream, |v| slab_float(&f, &v.0, &v.1))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(n, 4);
    }
    let trace = read_trace(&path, &["valid_in", "valid_out"]).unwrap();
    trace
        .check_valid_latency(2, latency)
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn float_valid_leaves_latency_clocks_after_it_enters() {
    float_valid_latency::<rtl::SlabFloatE5M10>("slab_float_e5m10_latency.vcd", 9);
}

#[test]
fn float_13_clocks_valid_leaves_13_clocks_after_it_enters() {
    float_valid_latency::<rtl::SlabFloatE5M10P13>("slab_float_e5m10_p13_latency.vcd", 13);
}
