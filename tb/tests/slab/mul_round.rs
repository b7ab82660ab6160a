//! The hand-written Verilog of `rtl::slab::mul_round::MulRound` (multiply, directed rounding and
//! saturation decided on the product) against its model, `MulRound::eval`, on every input of small
//! units, in Icarus: floor and ceil, shifts from 0 to beyond the t code's range, combinational and with
//! the product registered (the operands change after each clock edge, so `y` shows which: the last
//! edge's product, or this clock's), at widths where the saturation is reached from both sides and where it
//! cannot be reached (its comparisons become constants).

use rtl::slab::mul_round::MulRound;
use rtl::verilog::verilog_named;

/// Runs every `(a, m)` through the Verilog of `unit` (named `name`) in Icarus, a clock edge after
/// each, then the operands' complements, and returns `y` per input in the order a = 0.., m = 0..
/// (codes): of `(a, m)` for a unit with its product registered, of the complements for one without.
fn icarus_table<const D: usize, const I: usize, const T: usize>(
    mut unit: MulRound<D, I, T>,
    name: &str,
) -> Vec<u64> {
    let dir = tb::out_dir().join("mul_round");
    std::fs::create_dir_all(&dir).unwrap();
    let v = verilog_named(&mut unit, name);
    let bench = format!(
        "module bench;
reg clock = 0;
reg [{dm1}:0] a;
reg [{im1}:0] m;
wire [{tm1}:0] y;
{name} u(.clock(clock), .a(a), .m(m), .y(y));
integer i, j;
initial begin
   for (i = 0; i < {na}; i = i + 1)
      for (j = 0; j < {nm}; j = j + 1) begin
         a = i; m = j;
         #1 clock = 1; #1 clock = 0;
         // New operands after the edge: a registered product still shows (i, j), a combinational
         // unit the new operands.
         a = ~i; m = ~j;
         #1 $display(\"%0d\", y);
      end
   $finish;
end
endmodule
",
        dm1 = D - 1,
        im1 = I - 1,
        tm1 = T - 1,
        na = 1 << D,
        nm = 1 << I,
    );
    let src = dir.join(format!("{name}.v"));
    std::fs::write(&src, format!("{v}\n{bench}")).unwrap();
    tb::verilog_tools::icarus_run(&src)
        .unwrap_or_else(|e| panic!("{e}"))
        .lines()
        .filter_map(|l| l.trim().parse().ok())
        .collect()
}

fn every_input<const D: usize, const I: usize, const T: usize>(tag: &str, shifts: &[usize]) {
    let mut checked = 0;
    for &shift in shifts {
        for ceil in [false, true] {
            for pipelined in [false, true] {
                let name = format!("mr_{tag}_s{shift}_{}_{}", ceil as u8, pipelined as u8);
                let got = icarus_table(MulRound::<D, I, T>::new(ceil, shift, pipelined), &name);
                assert_eq!(
                    got.len(),
                    1 << (D + I),
                    "{name}: Icarus printed too few lines"
                );
                for (k, &y) in got.iter().enumerate() {
                    let (mut a, mut m) = ((k >> I) as u64, (k & ((1 << I) - 1)) as u64);
                    if !pipelined {
                        (a, m) = (!a & ((1 << D) - 1), !m & ((1 << I) - 1));
                    }
                    let want = MulRound::<D, I, T>::eval(ceil, shift, a, m);
                    assert_eq!(y, want, "{name}: a = {a:#x}, m = {m:#x}");
                }
                checked += got.len();
            }
        }
    }
    assert_eq!(checked, shifts.len() * 4 << (D + I));
}

/// t codes of 6 bits: the products reach beyond both ends at every shift up to 4.
#[test]
fn verilog_equals_model_on_every_input_where_it_saturates() {
    every_input::<5, 6, 6>("sat", &[0, 1, 4, 10]);
}

/// t codes of 12 bits: no product reaches either end, and the saturation compares are constants.
#[test]
fn verilog_equals_model_on_every_input_where_it_cannot_saturate() {
    every_input::<4, 5, 12>("nosat", &[0, 3]);
}
