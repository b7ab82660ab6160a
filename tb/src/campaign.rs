//! Streamed vector sources and campaigns: conservativeness of the bit-accurate model against the exact
//! oracle, and cross-simulation of the exported Verilog. Nothing is stored: memory stays flat.

use crate::slab::ctx::SlabVec;
use glam::DVec3;
use golden::format::fixed::{FixBox, FixFormat, FixRay, GridMap};
use golden::slab::check::{check_fix, Verdict};
use golden::slab::gen::{GenKind, SlabGen};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Scene bounds of the campaigns: deliberately off-centre and non-cubic, so grid cells are not aligned
/// with round world numbers.
pub fn campaign_bounds() -> (DVec3, DVec3) {
    (DVec3::new(-100.0, -3.0, 7.0), DVec3::new(100.0, 50.0, 9.5))
}

/// The grid of `fmt` over the campaign bounds.
pub fn campaign_map(fmt: FixFormat) -> GridMap {
    let (lo, hi) = campaign_bounds();
    GridMap::for_bounds(fmt, lo, hi).expect("campaign bounds are finite")
}

/// A world-vector generator over the campaign bounds, snapping some values to the grid of `map`.
pub fn world_gen(map: &GridMap, kind: GenKind, seed: u64) -> SlabGen {
    let (lo, hi) = campaign_bounds();
    SlabGen::new(kind, lo, hi, golden::format::fixed::ldexp(1.0, map.k), seed)
}

/// A quantised vector with every field uniform over its code range (including codes that quantisation
/// never produces, such as `m_lo > m_hi`): the RTL must match the model on all inputs.
pub fn raw_fix_vector<R: Rng>(fmt: &FixFormat, rng: &mut R) -> (FixRay, FixBox) {
    let g = |rng: &mut R| rng.gen_range(fmt.gmin()..=fmt.gmax());
    let m = |rng: &mut R| match rng.gen_range(0..8) {
        0 => fmt.inv_inf(),
        _ => rng.gen_range(0..=fmt.inv_inf()),
    };
    let t = |rng: &mut R| rng.gen_range(fmt.t_neg_inf()..=fmt.t_pos_inf());
    let mut r = FixRay::default();
    let mut b = FixBox::default();
    for a in 0..3 {
        r.o_lo[a] = g(rng);
        r.o_hi[a] = if rng.gen() { r.o_lo[a] } else { g(rng) };
        r.m_lo[a] = m(rng);
        r.m_hi[a] = if rng.gen() { r.m_lo[a] } else { m(rng) };
        r.neg[a] = rng.gen();
        b.lo[a] = g(rng);
        b.hi[a] = g(rng);
    }
    r.t_min = t(rng);
    r.t_max = t(rng);
    (r, b)
}

/// A stream of `n` pipeline tests: `world()` vectors, one in eight replaced by `raw(rng)`, and (when
/// `bubbles`) about one cycle in eight a bubble.
fn test_stream<T: Send + 'static>(
    seed: u64,
    n: u64,
    bubbles: bool,
    mut world: impl FnMut() -> T + Send + 'static,
    mut raw: impl FnMut(&mut Pcg64) -> T + Send + 'static,
) -> impl Iterator<Item = Option<T>> + Send + 'static {
    let mut rng = Pcg64::seed_from_u64(seed ^ 0x9e37_79b9_7f4a_7c15);
    let mut left = n;
    std::iter::from_fn(move || {
        if left == 0 {
            return None;
        }
        if bubbles && rng.gen_ratio(1, 8) {
            return Some(None);
        }
        left -= 1;
        Some(Some(if rng.gen_ratio(1, 8) {
            raw(&mut rng)
        } else {
            world()
        }))
    })
}

/// `n` quantised fixed-point test vectors from a seeded stream: world vectors of `kind` quantised on the
/// campaign grid, one in eight a raw-code vector, and (when `bubbles`) about one cycle in eight a bubble.
pub fn slab_vectors(
    fmt: FixFormat,
    kind: GenKind,
    seed: u64,
    n: u64,
    bubbles: bool,
) -> impl Iterator<Item = SlabVec> + Send + 'static {
    let map = campaign_map(fmt);
    let mut gen = world_gen(&map, kind, seed);
    let world = move || {
        let (r, b) = gen.next().expect("endless");
        (
            map.quantize_ray(&r).expect("campaign vectors fit the grid"),
            map.quantize_box(&b).expect("campaign vectors fit the grid"),
        )
    };
    test_stream(seed, n, bubbles, world, move |rng| {
        raw_fix_vector(&fmt, rng)
    })
}

/// A float vector with every field any pattern of the format (NaN included), specials weighted up.
pub fn raw_float_vector<R: Rng>(
    f: &golden::format::float::FloatFormat,
    rng: &mut R,
) -> (golden::slab::float::FloatRay, golden::slab::float::FloatBox) {
    let specials = f.specials();
    let mut x = || {
        if rng.gen_ratio(1, 4) {
            specials[rng.gen_range(0..specials.len())]
        } else {
            rng.gen::<u32>() & f.mask()
        }
    };
    let mut r = golden::slab::float::FloatRay::default();
    let mut b = golden::slab::float::FloatBox::default();
    for a in 0..3 {
        (r.o_lo[a], r.o_hi[a], r.m_lo[a], r.m_hi[a], b.lo[a], b.hi[a]) =
            (x(), x(), x(), x(), x(), x());
        r.neg[a] = x() & 1 == 1;
    }
    (r.t_min, r.t_max) = (x(), x());
    (r, b)
}

/// `n` float test vectors for format `f`, as [`slab_vectors`] does for the fixed datapath.
pub fn float_vectors(
    f: golden::format::float::FloatFormat,
    kind: GenKind,
    seed: u64,
    n: u64,
    bubbles: bool,
) -> impl Iterator<Item = Option<(golden::slab::float::FloatRay, golden::slab::float::FloatBox)>>
       + Send
       + 'static {
    let (lo, hi) = campaign_bounds();
    let mut gen = SlabGen::new(kind, lo, hi, 1.0 / 64.0, seed);
    let world = move || {
        let (r, b) = gen.next().expect("endless");
        (
            golden::slab::float::quantize_ray(&f, &r).expect("campaign vectors fit the format"),
            golden::slab::float::quantize_box(&f, &b).expect("campaign vectors fit the format"),
        )
    };
    test_stream(seed, n, bubbles, world, move |rng| {
        raw_float_vector(&f, rng)
    })
}

/// Tally of a conservativeness campaign.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ConservativeStats {
    pub vectors: u64,
    pub true_hits: u64,
    pub false_hits: u64,
    /// The first few violations (false misses or non-enclosing intervals), described.
    pub violations: Vec<String>,
    pub violation_count: u64,
}

impl ConservativeStats {
    fn merge(&mut self, o: ConservativeStats) {
        self.vectors += o.vectors;
        self.true_hits += o.true_hits;
        self.false_hits += o.false_hits;
        self.violation_count += o.violation_count;
        self.violations.extend(o.violations);
        self.violations.truncate(10);
    }
    /// Tallies one judged test: `hit` is the datapath's answer and `v` the verdict of the judge against
    /// the exact oracle (a violation counts as a true hit, since the oracle hits); `describe(why)` words
    /// a violation for the report and is called for the first ten only.
    pub fn record(&mut self, hit: bool, v: Verdict, describe: impl FnOnce(&str) -> String) {
        self.vectors += 1;
        match v {
            Verdict::Agree => self.true_hits += hit as u64,
            Verdict::FalseHit => self.false_hits += 1,
            Verdict::Violation(why) => {
                self.true_hits += 1;
                self.violation_count += 1;
                if self.violations.len() < 10 {
                    self.violations.push(describe(&why));
                }
            }
        }
    }
    /// False hits per true miss.
    pub fn false_hit_rate(&self) -> f64 {
        self.false_hits as f64 / (self.vectors - self.true_hits).max(1) as f64
    }
}

/// Runs `n` world vectors of `kind` (snapped sometimes to cells of `cell` world units) through `judge` —
/// quantisation, a bit-accurate model and the exact oracle — on `threads` threads (thread `k` uses seed
/// `seed + k`). `progress(done)` is called from the threads every 4,096 vectors with the count of that
/// batch. `judge` returns the verdict and a description of the datapath's result for reports.
pub fn judge_campaign(
    kind: GenKind,
    cell: f64,
    n: u64,
    seed: u64,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
    judge: &(dyn Fn(&golden::Ray, &golden::Aabb) -> (bool, Verdict, String) + Sync),
) -> ConservativeStats {
    let (lo, hi) = campaign_bounds();
    let threads = threads.max(1) as u64;
    let mut total = ConservativeStats::default();
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let share = n / threads + u64::from(k < n % threads);
                s.spawn(move || {
                    let mut st = ConservativeStats::default();
                    let gen = SlabGen::new(kind, lo, hi, cell, seed.wrapping_add(k));
                    for (i, (r, b)) in gen.take(share as usize).enumerate() {
                        let (hit, v, what) = judge(&r, &b);
                        st.record(hit, v, |why| {
                            format!("{why}\n  ray {r:?}\n  box {b:?}\n  {what}")
                        });
                        if i % 4096 == 4095 {
                            progress(4096);
                        }
                    }
                    st
                })
            })
            .collect();
        for h in handles {
            total.merge(h.join().expect("campaign thread"));
        }
    });
    total
}

/// The fixed-point datapath's conservativeness campaign on the campaign grid of `fmt`.
pub fn conservative_campaign(
    fmt: FixFormat,
    kind: GenKind,
    n: u64,
    seed: u64,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> ConservativeStats {
    let map = campaign_map(fmt);
    let judge = move |r: &golden::Ray, b: &golden::Aabb| {
        let (fr, fb, out, v) = check_fix(&map, r, b).expect("campaign vectors fit the grid");
        (
            out.hit,
            v,
            format!("quantised {fr:?} {fb:?}\n  result {out:?}"),
        )
    };
    judge_campaign(
        kind,
        golden::format::fixed::ldexp(1.0, map.k),
        n,
        seed,
        threads,
        progress,
        &judge,
    )
}

/// The float datapath's conservativeness campaign in format `f`.
pub fn float_campaign(
    f: golden::format::float::FloatFormat,
    kind: GenKind,
    n: u64,
    seed: u64,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> ConservativeStats {
    use golden::slab::float::{judge_float, quantize_box, quantize_ray, slab_float};
    let judge = move |r: &golden::Ray, b: &golden::Aabb| {
        let (fr, fb) = (
            quantize_ray(&f, r).expect("fits"),
            quantize_box(&f, b).expect("fits"),
        );
        let out = slab_float(&f, &fr, &fb);
        let v = judge_float(&f, &out, &golden::exact::slab_exact(r, b));
        (
            out.hit,
            v,
            format!("quantised {fr:?} {fb:?}\n  result {out:?}"),
        )
    };
    judge_campaign(kind, 1.0 / 64.0, n, seed, threads, progress, &judge)
}
