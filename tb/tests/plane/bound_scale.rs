//! The hand-written Verilog of `rtl::plane::bound_scale::BoundScale` (the bound's shift by `C - L`,
//! floored for an entry and ceiled for an exit, saturated to a t code) against its model,
//! `golden::plane::fix::scale_product`, on every input of small units, in Icarus: every product, every
//! leading-one position from 0 to past the product's width (so that shifts keep all, some and none of
//! its bits), the four class combinations, scale exponents below, at and above zero, at t code widths
//! where the saturation is reached from both sides and where it cannot be.

use golden::format::fixed::{code, sext};
use golden::plane::fix::scale_product;
use rtl::plane::bound_scale::BoundScale;
use rtl::verilog::verilog_named;

/// Leading-one positions tried: 0 up to past every shift that keeps a bit of the product.
const LEADS: u64 = 24;

/// Runs every `(prod, lead, is_exit, is_entry)` of `pw`-bit products through the Verilog of `unit`
/// (named `name`) in Icarus and returns `y` per input, in the order prod, lead, class (codes).
fn icarus_table<const T: usize>(mut unit: BoundScale<T>, name: &str, pw: usize) -> Vec<u64> {
    let dir = tb::out_dir().join("bound_scale");
    std::fs::create_dir_all(&dir).unwrap();
    let v = verilog_named(&mut unit, name);
    let bench = format!(
        "module bench;
reg [63:0] prod;
reg [7:0] lead;
reg is_exit, is_entry;
wire [{tm1}:0] y;
{name} u(.prod(prod), .lead(lead), .is_exit(is_exit), .is_entry(is_entry), .y(y));
integer i, j, k;
initial begin
   for (i = 0; i < {np}; i = i + 1)
      for (j = 0; j < {LEADS}; j = j + 1)
         for (k = 0; k < 4; k = k + 1) begin
            prod = i; lead = j; is_exit = k[0]; is_entry = k[1];
            #1 $display(\"%0d\", y);
         end
   $finish;
end
endmodule
",
        tm1 = T - 1,
        np = 1u64 << pw,
    );
    let src = dir.join(format!("{name}.v"));
    std::fs::write(&src, format!("{v}\n{bench}")).unwrap();
    tb::verilog_tools::icarus_run(&src)
        .unwrap_or_else(|e| panic!("{e}"))
        .lines()
        .filter_map(|l| l.trim().parse().ok())
        .collect()
}

/// Every input of `pw`-bit products for each scale exponent of `shifts`; returns how many inputs scaled
/// past each end of the t code's range (low, high), before the clamp, so a caller can say which it
/// expects.
fn every_input<const T: usize>(tag: &str, pw: usize, shifts: &[i32]) -> (usize, usize) {
    let (ninf, pinf) = (-(1i64 << (T - 1)), (1i64 << (T - 1)) - 1);
    let mut saturated = (0, 0);
    for &c in shifts {
        let name = format!("bs_{tag}_c{}{}", if c < 0 { "m" } else { "" }, c.abs());
        let got = icarus_table(BoundScale::<T>::new(pw, c), &name, pw);
        assert_eq!(
            got.len(),
            (LEADS as usize * 4) << pw,
            "{name}: Icarus printed too few lines"
        );
        for (n, &y) in got.iter().enumerate() {
            let (p, lead, class) = ((n >> 2) / LEADS as usize, (n >> 2) % LEADS as usize, n & 3);
            let (exit, entry) = (class & 1 == 1, class & 2 == 2);
            let want = if exit || entry {
                let q = sext(p as u64, pw) as i128;
                // The scaled value before the clamp (the model at 64-bit codes, which these small
                // products never reach), to count the inputs that reach past an end.
                let unclamped = scale_product(c, 64, q, lead as u32, exit);
                let (lo, hi) = if exit {
                    (ninf + 1, pinf)
                } else {
                    (ninf, pinf - 1)
                };
                if unclamped < lo {
                    saturated.0 += 1;
                }
                if unclamped > hi {
                    saturated.1 += 1;
                }
                code(scale_product(c, T as u32, q, lead as u32, exit), T)
            } else {
                0
            };
            assert_eq!(
                y, want,
                "{name}: prod {p:#x} lead {lead} exit {exit} entry {entry}"
            );
        }
    }
    saturated
}

/// t codes of 5 bits from 8-bit products: the bounds pass both ends of the t code at small shifts.
#[test]
fn verilog_equals_model_on_every_input_where_it_saturates() {
    let (low, high) = every_input::<5>("sat", 8, &[-3, 0, 2]);
    assert!(
        low > 0 && high > 0,
        "no saturation reached: {low} low, {high} high"
    );
}

/// t codes of 16 bits from 6-bit products: no bound reaches either end.
#[test]
fn verilog_equals_model_on_every_input_where_it_cannot_saturate() {
    let (low, high) = every_input::<16>("nosat", 6, &[-2, 0, 3]);
    assert_eq!(
        (low, high),
        (0, 0),
        "a 6-bit product saturated a 16-bit code"
    );
}
