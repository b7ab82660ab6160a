//! `rtu run --bundles` end to end: generated bundles (random and adversarial, given by their rays or by
//! their bounds) written as a vector file, run through the model and the rust-hdl results processor, the
//! two outputs identical line for line, every answer sound against the exact per-ray results; a malformed
//! line is an error naming the line and the field.

use glam::DVec3;
use golden::bundle::check::slab_hit;
use golden::bundle::gen::BundleGen;
use golden::bundle::vectors::{write_bundle_vector, BundleVector};
use serde_json::Value;
use std::process::Command;

fn rtu(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rtu"))
        .args(args)
        .output()
        .expect("rtu runs")
}

#[test]
fn bundle_files_run_on_model_and_rtl_with_sound_answers() {
    let dir = std::env::temp_dir().join(format!("rtu-run-bundles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("bundles.jsonl");
    let mut g = BundleGen::new(11, DVec3::splat(-50.0), DVec3::splat(50.0), 0.6);
    let mut text = vec![];
    let mut vs = vec![];
    while vs.len() < 400 {
        let c = g.next_case();
        if c.rays.len() > 16 {
            continue;
        }
        let with_rays = vs.len() % 4 != 3;
        let v = BundleVector {
            tag: vs.len() as u64,
            bundle: c.bundle,
            rays: if with_rays { c.rays.clone() } else { vec![] },
            bx: c.bounds,
        };
        write_bundle_vector(&mut text, &v).unwrap();
        vs.push((v, c.rays));
    }
    std::fs::write(&input, &text).unwrap();
    let bounds = "--bounds=-50,-50,-50,50,50,50";
    let mut outs = vec![];
    for engine in ["model", "rtl"] {
        let o = rtu(&[
            "run",
            "--bundles",
            input.to_str().unwrap(),
            "--format",
            "b12",
            bounds,
            "--engine",
            engine,
        ]);
        assert!(
            o.status.success(),
            "{engine}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        outs.push(String::from_utf8(o.stdout).unwrap());
    }
    assert_eq!(outs[0], outs[1], "model and rtl engines differ");
    let (mut decided, mut split) = (0, 0);
    for (line, (v, rays)) in outs[0].lines().zip(&vs) {
        let r: Value = serde_json::from_str(line).unwrap();
        assert_eq!(r["tag"].as_u64(), Some(v.tag));
        let truth: Vec<bool> = rays.iter().map(|ray| slab_hit(ray, &v.bx)).collect();
        let (all_hit, all_miss) = (r["all_hit"] == true, r["all_miss"] == true);
        assert!(!(all_hit && all_miss), "{line}");
        assert!(
            !all_hit || truth.iter().all(|&h| h),
            "false all-hit: {line}"
        );
        assert!(
            !all_miss || truth.iter().all(|&h| !h),
            "false all-miss: {line}"
        );
        decided += usize::from(all_hit || all_miss);
        if let Some(hits) = r["hits"].as_array() {
            assert_eq!(hits.len(), truth.len());
            for (h, t) in hits.iter().zip(&truth) {
                assert!(
                    h == true || !t,
                    "a ray that hits is reported a miss: {line}"
                );
            }
            split += usize::from(r["split"] == true);
        } else {
            assert!(v.rays.is_empty(), "{line}");
        }
    }
    println!("{} bundles: {decided} decided, {split} split", vs.len());
    assert!(
        decided > 40 && split > 40,
        "both paths exercised: {decided} {split}"
    );
    std::fs::write(&input, "{\"tag\":1,\"rays\":[{\"origin\":[0,1],\"dir\":[1,0,0]}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}\n").unwrap();
    let o = rtu(&[
        "run",
        "--bundles",
        input.to_str().unwrap(),
        "--format",
        "b12",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains(":1: field `rays[0].origin`"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
