//! Conservativeness: the bit-accurate fixed-point slab model against the exact rational oracle, on
//! 100,000 uniform and 100,000 adversarial world vectors per width configuration. No false miss, and
//! every reported interval encloses the exact one. (`rtu campaign` runs the same check on 10,000,000.)

use golden::format::fixed::FixFormat;
use golden::slab::gen::GenKind;
use tb::campaign::conservative_campaign;

const VECTORS: u64 = 100_000;

fn conservative(fmt: FixFormat, kind: GenKind, seed: u64) {
    let st = conservative_campaign(fmt, kind, VECTORS, seed, 2, &|_| {});
    assert_eq!(st.vectors, VECTORS);
    assert!(
        st.true_hits > 0,
        "no hits at all: the generator is degenerate"
    );
    assert_eq!(
        st.violation_count,
        0,
        "{} {kind:?}: {} violations, first:\n{}",
        fmt.name(),
        st.violation_count,
        st.violations.join("\n")
    );
}

#[test]
fn b8_uniform() {
    conservative(FixFormat::b8(), GenKind::Uniform, 100);
}
#[test]
fn b8_adversarial() {
    conservative(FixFormat::b8(), GenKind::Adversarial, 101);
}
#[test]
fn b12_uniform() {
    conservative(FixFormat::b12(), GenKind::Uniform, 120);
}
#[test]
fn b12_adversarial() {
    conservative(FixFormat::b12(), GenKind::Adversarial, 121);
}
#[test]
fn b16_uniform() {
    conservative(FixFormat::b16(), GenKind::Uniform, 160);
}
#[test]
fn b16_adversarial() {
    conservative(FixFormat::b16(), GenKind::Adversarial, 161);
}

/// The check can fail: a model that shrinks the exit by one code is caught as non-enclosing.
#[test]
fn a_tightened_interval_is_caught() {
    use golden::exact::slab_exact;
    use golden::slab::check::{judge_fix, Verdict};
    use golden::slab::fix::slab_fix;
    let fmt = FixFormat::b12();
    let map = tb::campaign::campaign_map(fmt);
    let mut caught = 0;
    for (r, b) in tb::campaign::world_gen(&map, GenKind::Uniform, 5).take(20_000) {
        let (fr, fb) = (map.quantize_ray(&r).unwrap(), map.quantize_box(&b).unwrap());
        let mut out = slab_fix(&fmt, &fr, &fb);
        if !out.hit || out.t_exit == fmt.t_pos_inf() {
            continue;
        }
        out.t_exit -= 1 << 8; // 4 t units early: well inside the exact interval for most hits
        if let Verdict::Violation(_) = judge_fix(&fmt, &fr, &out, &slab_exact(&r, &b)) {
            caught += 1;
        }
    }
    assert!(caught > 10, "only {caught} tightened intervals caught");
}
