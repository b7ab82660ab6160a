//! Conservativeness of the float slab datapath against the exact rational oracle, on 100,000 uniform and
//! 100,000 adversarial world vectors per format: fp32, E8M15, bf16, fp16 and the small E6M5. No false
//! miss, and every reported interval encloses the exact one.

use golden::format::float::FloatFormat;
use golden::slab::gen::GenKind;
use tb::campaign::float_campaign;

const VECTORS: u64 = 100_000;

fn conservative(f: FloatFormat, kind: GenKind, seed: u64) {
    let st = float_campaign(f, kind, VECTORS, seed, 2, &|_| {});
    assert_eq!(st.vectors, VECTORS);
    assert!(
        st.true_hits > 0,
        "no hits at all: the generator is degenerate"
    );
    eprintln!(
        "{} {kind:?}: {} true hits, {} false hits",
        f.name(),
        st.true_hits,
        st.false_hits
    );
    assert_eq!(
        st.violation_count,
        0,
        "{} {kind:?}: {} violations, first:\n{}",
        f.name(),
        st.violation_count,
        st.violations.join("\n")
    );
}

macro_rules! formats {
    ($($name:ident: $f:expr, $seed:expr;)*) => {$(
        mod $name {
            use super::*;
            #[test]
            fn uniform() {
                conservative($f, GenKind::Uniform, $seed);
            }
            #[test]
            fn adversarial() {
                conservative($f, GenKind::Adversarial, $seed + 1);
            }
        }
    )*};
}

formats! {
    e8m23: FloatFormat::FP32, 10;
    e8m15: FloatFormat::E8M15, 20;
    e8m7: FloatFormat::BF16, 30;
    e5m10: FloatFormat::FP16, 40;
    e6m5: FloatFormat::new(6, 5).unwrap(), 50;
}
