//! Vector I/O of the cull-plane testers (`rtu run --k K`): users' world vectors with planes, written
//! and read back through the vector file format, quantised by `fix_vector` / `float_vector` (planes fitted
//! outward to the part of the box they keep), are judged against the exact clip by the *world* planes —
//! the contract the user sees — and the model, rust-hdl and Verilator engines give the same results.

use golden::format::fixed::{FixFormat, GridMap};
use golden::format::float::FloatFormat;
use golden::plane::clip::{clip_exact, ExactPlane, Plane};
use golden::plane::fix::CullFixFormat;
use golden::plane::float::{out_interval, CullFloatFormat};
use golden::plane::gen::CullGen;
use golden::slab::check::{judge, Verdict};
use golden::slab::vectors::{read_vectors, write_vector, VecFormat, Vector};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use tb::engine::{run_cull_fix, run_cull_float, Engine};
use tb::plane::fix::{cull_map, fix_vector, CullFixCtx};
use tb::plane::float::{float_vector, CullFloatCtx};
use tb::xsim::TesterCtx;

/// `n` world vectors with `k` planes each, through a JSON-lines file and back: half the planes fitted
/// to the case's triangle (the generator's normals), half with a random offset anywhere across the box
/// (planes that cut nothing, part of the box, or all of it).
fn vectors(seed: u64, n: usize, k: usize) -> Vec<Vector> {
    let mut gen = CullGen::new(seed, 0.5, k, tb::plane::fix::CULL_R);
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut text = Vec::new();
    for tag in 0..n {
        let c = gen.case();
        let planes = c
            .normals
            .iter()
            .map(|&n| {
                let reach = n.abs().dot(c.bounds.max - c.bounds.min) * 0.5;
                let w = if rng.gen_bool(0.5) {
                    golden::plane::generate::fit_offset(n, &c.tri, &c.bounds)
                } else {
                    rng.gen_range(-1.2 * reach..=1.2 * reach)
                };
                Plane { n, w }
            })
            .collect();
        let v = Vector {
            tag: tag as u64,
            ray: c.ray,
            bx: c.bounds,
            planes,
        };
        write_vector(&mut text, VecFormat::JsonLines, &v).unwrap();
    }
    read_vectors(
        std::io::Cursor::new(text),
        VecFormat::JsonLines,
        "generated",
    )
    .map(|v| v.unwrap())
    .collect()
}

fn world_exact(v: &Vector) -> golden::exact::ExactHit {
    let planes: Vec<ExactPlane> = v
        .planes
        .iter()
        .map(|p| ExactPlane::from_world(p, &v.bx))
        .collect();
    clip_exact(&v.ray, &v.bx, &planes)
}

/// Panics on a violation of the world contract, naming the datapath and the vector.
fn check(what: &str, v: &Vector, verdict: Verdict) {
    if let Verdict::Violation(why) = verdict {
        panic!("{what}: vector {v:?}: {why}");
    }
}

#[test]
fn user_vectors_with_planes_are_conservative_against_the_world_planes() {
    let k = 4;
    let vs = vectors(3, 20_000, k);
    let cf = CullFixFormat::over(FixFormat::b12());
    let map: GridMap = cull_map(cf.base);
    let ff = CullFloatFormat::over(FloatFormat::FP16);
    let (mut exact_culls, mut fix_culls, mut float_culls, mut run) = (0u64, 0u64, 0u64, 0u64);
    for v in &vs {
        let exact = world_exact(v);
        let (Ok((r, node)), Ok((fr, fnode))) = (fix_vector(&cf, &map, v), float_vector(&ff, v))
        else {
            continue; // out of a format's range
        };
        run += 1;
        exact_culls += u64::from(!exact.hit);
        let o = golden::plane::fix::node_fix(&cf, k, &r, &node);
        fix_culls += u64::from(!o.hit);
        let verdict = judge(&exact, o.hit, || {
            Some((
                r.ray.t_world(&cf.base, o.t_entry),
                r.ray.t_world(&cf.base, o.t_exit),
            ))
        });
        check("b12", v, verdict);
        let o = golden::plane::float::node_float(&ff, k, &fr, &fnode);
        float_culls += u64::from(!o.hit);
        let verdict = judge(&exact, o.hit, || out_interval(&ff.f, &o));
        check("fp16", v, verdict);
    }
    eprintln!("{run} vectors: exact culls {exact_culls}, b12 {fix_culls}, fp16 {float_culls}");
    assert!(run > 15_000, "{run} of 20000 vectors fit both formats");
    // The planes do cull (not a vacuous check), and the datapaths get most of it.
    assert!(exact_culls > run / 10, "{exact_culls}");
    assert!(fix_culls > exact_culls / 2 && float_culls > exact_culls / 2);
}

/// Runs vectors through every engine of a tester and returns each engine's results.
fn all_engines<R>(engines: &[Engine], run: impl Fn(Engine) -> Vec<R>) -> Vec<Vec<R>> {
    engines.iter().map(|&e| run(e)).collect()
}

#[test]
fn plane_fix_engines_agree_on_user_vectors() {
    let ctx = CullFixCtx {
        cf: CullFixFormat::over(FixFormat::b12()),
        k: 2,
    };
    let map = cull_map(ctx.cf.base);
    let vs = vectors(5, 3_000, 2);
    let dir = tb::out_dir().join("verilator");
    let res = all_engines(&[Engine::Model, Engine::Rtl, Engine::Verilator], |e| {
        let tests: Vec<_> = vs
            .iter()
            .filter_map(|v| {
                fix_vector(&ctx.cf, &map, v)
                    .ok()
                    .map(|(r, n)| (v.tag, r, n))
            })
            .collect();
        let mut out = vec![];
        run_cull_fix(e, ctx, tests.into_iter(), &dir, None, |tag, r, o| {
            out.push((tag, ctx.world(r, &o)));
            Ok(())
        })
        .unwrap();
        out
    });
    assert!(res[0].len() > 2_500, "{}", res[0].len());
    assert!(res[0].iter().any(|x| !x.1 .0) && res[0].iter().any(|x| x.1 .0));
    assert_eq!(res[0], res[1], "model vs rust-hdl");
    assert_eq!(res[0], res[2], "model vs Verilator");
}

#[test]
fn plane_float_engines_agree_on_user_vectors() {
    let ctx = CullFloatCtx::new(CullFloatFormat::over(FloatFormat::FP16), 2);
    let vs = vectors(6, 2_000, 2);
    let dir = tb::out_dir().join("verilator");
    let res = all_engines(&[Engine::Model, Engine::Rtl, Engine::Verilator], |e| {
        let tests: Vec<_> = vs
            .iter()
            .filter_map(|v| float_vector(&ctx.cf, v).ok().map(|(r, n)| (v.tag, r, n)))
            .collect();
        let mut out = vec![];
        run_cull_float(e, ctx, tests.into_iter(), &dir, None, |tag, r, o| {
            out.push((tag, ctx.world(r, &o)));
            Ok(())
        })
        .unwrap();
        out
    });
    assert!(res[0].len() > 1_500, "{}", res[0].len());
    assert!(res[0].iter().any(|x| !x.1 .0) && res[0].iter().any(|x| x.1 .0));
    assert_eq!(res[0], res[1], "model vs rust-hdl");
    assert_eq!(res[0], res[2], "model vs Verilator");
}

#[test]
fn the_hardware_engines_refuse_what_has_no_block() {
    let ctx = CullFixCtx {
        cf: CullFixFormat::over(FixFormat::b12()),
        k: 9,
    };
    let dir = tb::out_dir().join("verilator");
    let e = run_cull_fix(
        Engine::Rtl,
        ctx,
        std::iter::empty::<(u64, _, _)>(),
        &dir,
        None,
        |_, _, _| Ok(()),
    )
    .unwrap_err();
    assert!(e.contains("1 to 8"), "{e}");
    let ctx = CullFloatCtx::new(CullFloatFormat::over(FloatFormat::FP16), 3);
    let e = run_cull_float(
        Engine::Rtl,
        ctx,
        std::iter::empty::<(u64, _, _)>(),
        &dir,
        None,
        |_, _, _| Ok(()),
    )
    .unwrap_err();
    assert!(e.contains("no PlaneFloat instance"), "{e}");
}
