//! The float adder's and multiplier's exported Verilog: lint-clean, accepted by Icarus, and bit-exact in
//! Verilator with the golden model on every special pair and 200,000 random pairs per format and mode.

use golden::format::float::{FloatFormat, Rounding};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::export::{fp_add_verilog, fp_mul_verilog};
use rtl::names::fp_unit_module;

fn lint_and_icarus(v: &str, module: &str) {
    let path = tb::verilog_tools::write(v, module);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
}

fn cross<const E: usize, const M: usize, const N: usize>(n: usize) {
    let f = FloatFormat::new(E as u32, M as u32).unwrap();
    for unit in ["add", "mul"] {
        for (k, mode) in Rounding::ALL.into_iter().enumerate() {
            cross_unit::<E, M, N>(&f, unit, mode, k as u64, n);
        }
    }
}

fn cross_unit<const E: usize, const M: usize, const N: usize>(
    f: &FloatFormat,
    unit: &str,
    mode: Rounding,
    k: u64,
    n: usize,
) {
    {
        let module = fp_unit_module(unit, f, mode);
        let v = if unit == "add" {
            fp_add_verilog::<E, M, N>(mode)
        } else {
            fp_mul_verilog::<E, M, N>(mode)
        };
        let model = |a: u32, b: u32| {
            if unit == "add" {
                f.add(a, b, mode)
            } else {
                f.mul(a, b, mode)
            }
        };
        lint_and_icarus(&v, &module);
        let h = tb::verilator::build(&v, &module, &tb::out_dir().join("verilator"))
            .unwrap_or_else(|e| panic!("{e}"));
        let (ia, ib, iv, it) = (
            h.input_index("a").unwrap(),
            h.input_index("b").unwrap(),
            h.input_index("valid_in").unwrap(),
            h.input_index("tag_in").unwrap(),
        );
        let (ov, oy) = (
            h.output_index("valid_out").unwrap(),
            h.output_index("y").unwrap(),
        );
        let s = f.specials();
        let mut rng = Pcg64::seed_from_u64(k + 100);
        let mut pairs: Vec<(u32, u32)> = s
            .iter()
            .flat_map(|&a| s.iter().map(move |&b| (a, b)))
            .collect();
        for _ in 0..n {
            let a = rng.gen::<u32>() & f.mask();
            let b = if rng.gen() {
                (a ^ f.sign_bit() ^ rng.gen_range(0..64)) & f.mask()
            } else {
                rng.gen::<u32>() & f.mask()
            };
            pairs.push((a, b));
        }
        let ni = h.inputs.len();
        let feed = pairs.clone();
        let records = feed
            .into_iter()
            .enumerate()
            .map(move |(i, (a, b))| {
                let mut r = vec![0u64; ni];
                (r[ia], r[ib], r[iv], r[it]) = (a as u64, b as u64, 1, (i & 0xffff) as u64);
                r
            })
            .chain(std::iter::repeat_n(
                vec![0u64; ni],
                rtl::fp::add::FP_ADD_LATENCY + 1,
            ));
        let mut next = 0usize;
        h.stream(records, |_, out| {
            if out[ov] != 0 {
                let (a, b) = pairs[next];
                let want = model(a, b);
                if out[oy] as u32 != want {
                    return Err(format!(
                        "{module}: {a:#x} + {b:#x} = {:#x} in Verilator, {want:#x} in the model",
                        out[oy]
                    ));
                }
                next += 1;
            }
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(next, pairs.len(), "{module}: results missing");
    }
}

#[test]
fn e8m23() {
    cross::<8, 23, 32>(200_000);
}
#[test]
fn e5m10() {
    cross::<5, 10, 16>(200_000);
}
#[test]
fn e8m7() {
    cross::<8, 7, 16>(200_000);
}
