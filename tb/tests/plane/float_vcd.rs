//! Waveforms of the chained float node tester (binary16, two planes): the rust-hdl simulation writes a
//! VCD; read back with the `vcd` crate, `valid_out` rises exactly PLANE_FLOAT_LATENCY clock edges after
//! `valid_in`, for an isolated test and for a back-to-back burst.

use golden::plane::float::node_float;
use rtl::plane::float::PlaneFloatIo;
use tb::dut::run_checked;
use tb::plane::float::{node_stream, with_big_stack, CullFloatCtx, NodeVec};
use tb::rtl_sim::TesterSim;
use tb::vcd_read::read_trace;

#[test]
fn plane_float_valid_leaves_latency_clocks_after_it_enters() {
    with_big_stack(run);
}

fn run() {
    type P = rtl::PlaneFloatE5M10K2;
    let ctx = CullFloatCtx::new(P::cull_format(), P::planes());
    let path = tb::out_dir()
        .join("vcd")
        .join("plane_float_e5m10_k2_latency.vcd");
    let tests: Vec<NodeVec> = node_stream(ctx, 5, 0, 0).take(4).collect();
    // One isolated test, a gap longer than the latency, then three back to back.
    let mut stream = vec![tests[0]];
    stream.extend(std::iter::repeat_n(None, rtl::PLANE_FLOAT_LATENCY + 3));
    stream.extend(tests[1..].iter().cloned());
    {
        let mut dut = TesterSim::wrap(P::make()).vcd_to(&path).unwrap();
        let n = run_checked(&mut dut, stream, |v| node_float(&ctx.cf, ctx.k, &v.0, &v.1))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(n, 4);
    }
    let trace = read_trace(&path, &["valid_in", "valid_out"]).unwrap();
    trace
        .check_valid_latency(2, rtl::PLANE_FLOAT_LATENCY)
        .unwrap_or_else(|e| panic!("{e}"));
}
