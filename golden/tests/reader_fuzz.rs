//! Fuzzing of every reader of users' files: slab and cull-plane vectors (JSON lines and CSV), bundle
//! vectors, OBJ scenes. Inputs are arbitrary bytes, and valid files with a few bytes deleted, replaced,
//! inserted or a span repeated. For every input: no panic; every rejected input is an error naming the
//! source, and a line-level error a line the input has; reading twice gives the same result; every
//! accepted vector written back and read again is the same vector.
//!
//! Cases per reader and generator: `RTU_FUZZ_CASES` (default 2000; `scripts/fuzz` runs more).

use glam::DVec3;
use golden::bundle::gen::BundleGen;
use golden::bundle::vectors::{read_bundles, write_bundle_vector, BundleVector};
use golden::scene::tri_scene::parse_obj;
use golden::slab::gen::{GenKind, SlabGen};
use golden::slab::vectors::{
    csv_vector_header_with_planes, read_vectors, write_vector, VecFormat, Vector,
};
use golden::Error;
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

fn cases() -> u32 {
    std::env::var("RTU_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

const SRC: &str = "fuzz.in";

/// The error names the source, and a line error a line of the input.
fn check_error(e: &Error, bytes: &[u8]) -> Result<(), TestCaseError> {
    let text = e.to_string();
    prop_assert!(
        text.starts_with(SRC),
        "error does not name the source: {text}"
    );
    let lines = bytes.split(|&b| b == b'\n').count();
    if let Error::BadLine { line, .. } = e {
        prop_assert!((1..=lines).contains(line), "line {line} of {lines}: {text}");
    }
    Ok(())
}

fn slab_vectors(bytes: &[u8], fmt: VecFormat) -> Vec<Result<Vector, Error>> {
    read_vectors(std::io::Cursor::new(bytes.to_vec()), fmt, SRC).collect()
}

fn check_slab(bytes: &[u8], fmt: VecFormat) -> Result<(), TestCaseError> {
    let got = slab_vectors(bytes, fmt);
    prop_assert_eq!(&got, &slab_vectors(bytes, fmt), "read twice");
    for r in &got {
        match r {
            Err(e) => check_error(e, bytes)?,
            Ok(v) => {
                let mut buf = vec![];
                if fmt == VecFormat::Csv {
                    buf.extend(csv_vector_header_with_planes(v.planes.len()).bytes());
                    buf.push(b'\n');
                }
                write_vector(&mut buf, fmt, v).unwrap();
                prop_assert_eq!(slab_vectors(&buf, fmt), vec![Ok(v.clone())], "round trip");
            }
        }
    }
    Ok(())
}

fn bundles(bytes: &[u8]) -> Vec<Result<BundleVector, Error>> {
    read_bundles(std::io::Cursor::new(bytes.to_vec()), SRC).collect()
}

fn check_bundles(bytes: &[u8]) -> Result<(), TestCaseError> {
    let got = bundles(bytes);
    prop_assert_eq!(&got, &bundles(bytes), "read twice");
    for r in &got {
        match r {
            Err(e) => check_error(e, bytes)?,
            Ok(v) => {
                let mut buf = vec![];
                write_bundle_vector(&mut buf, v).unwrap();
                prop_assert_eq!(bundles(&buf), vec![Ok(v.clone())], "round trip");
            }
        }
    }
    Ok(())
}

fn check_obj(bytes: &[u8]) -> Result<(), TestCaseError> {
    let text = String::from_utf8_lossy(bytes);
    let got = parse_obj(&text, SRC);
    let again = parse_obj(&text, SRC);
    match (&got, &again) {
        (Ok(a), Ok(b)) => prop_assert_eq!(&a.tris, &b.tris, "read twice"),
        (Err(a), Err(b)) => {
            prop_assert_eq!(a, b, "read twice");
            check_error(a, bytes)?;
        }
        _ => prop_assert!(false, "read twice: one accepted, one rejected"),
    }
    Ok(())
}

/// Valid files of each reader, to mutate.
fn seeds() -> (Vec<u8>, Vec<u8>, Vec<u8>, Vec<u8>) {
    let (lo, hi) = (DVec3::splat(-8.0), DVec3::splat(8.0));
    let mut json = b"# generated\n".to_vec();
    let mut csv = csv_vector_header_with_planes(0).into_bytes();
    csv.push(b'\n');
    for (tag, (ray, bx)) in SlabGen::new(GenKind::Mixed, lo, hi, 1.0 / 64.0, 3)
        .take(4)
        .enumerate()
    {
        let v = Vector {
            tag: tag as u64,
            ray,
            bx,
            planes: if tag == 1 {
                vec![golden::plane::clip::Plane {
                    n: DVec3::new(1.0, -0.5, 0.0),
                    w: 0.25,
                }]
            } else {
                vec![]
            },
        };
        write_vector(&mut json, VecFormat::JsonLines, &v).unwrap();
        if v.planes.is_empty() {
            write_vector(&mut csv, VecFormat::Csv, &v).unwrap();
        }
    }
    let mut bundle = vec![];
    let mut g = BundleGen::new(5, lo, hi, 0.5);
    for tag in 0..3 {
        let c = g.next_case();
        let v = BundleVector {
            tag,
            bundle: c.bundle,
            rays: if tag == 2 {
                vec![]
            } else {
                c.rays.into_iter().take(3).collect()
            },
            bx: c.bounds,
        };
        let v = BundleVector {
            bundle: if v.rays.is_empty() {
                v.bundle
            } else {
                golden::bundle::edge::Bundle::around(&v.rays).unwrap()
            },
            ..v
        };
        write_bundle_vector(&mut bundle, &v).unwrap();
    }
    let obj = b"# tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1.5\nvn 0 0 1\nf 1 2 3\nf -1 -2 -3\nf 1/1/1 2//1 4\n"
        .to_vec();
    (json, csv, bundle, obj)
}

/// A valid file with a few edits: delete, replace or insert a byte, or repeat a span.
fn mutated(seed: Vec<u8>) -> impl Strategy<Value = Vec<u8>> {
    const BYTES: &[u8] = b"\"',:[]{}-+.eE0129 \n\t#infa\xff\xef\xbb\xbf/";
    let n = seed.len();
    prop::collection::vec((0..4u8, 0..n, 0..BYTES.len(), 0..24usize), 1..4).prop_map(move |edits| {
        let mut b = seed.clone();
        for (op, at, byte, len) in edits {
            let at = at.min(b.len());
            let c = BYTES[byte];
            match op {
                0 if at < b.len() => {
                    b.remove(at);
                }
                1 if at < b.len() => b[at] = c,
                2 => b.insert(at, c),
                _ => {
                    let end = (at + len).min(b.len());
                    let span = b[at..end].to_vec();
                    b.splice(at..at, span);
                }
            }
        }
        b
    })
}

fn arbitrary() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(any::<u8>(), 0..300)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn slab_json_arbitrary_bytes(b in arbitrary()) { check_slab(&b, VecFormat::JsonLines)?; }
    #[test]
    fn slab_csv_arbitrary_bytes(b in arbitrary()) { check_slab(&b, VecFormat::Csv)?; }
    #[test]
    fn bundle_arbitrary_bytes(b in arbitrary()) { check_bundles(&b)?; }
    #[test]
    fn obj_arbitrary_bytes(b in arbitrary()) { check_obj(&b)?; }

    #[test]
    fn slab_json_mutated(b in mutated(seeds().0)) { check_slab(&b, VecFormat::JsonLines)?; }
    #[test]
    fn slab_csv_mutated(b in mutated(seeds().1)) { check_slab(&b, VecFormat::Csv)?; }
    #[test]
    fn bundle_mutated(b in mutated(seeds().2)) { check_bundles(&b)?; }
    #[test]
    fn obj_mutated(b in mutated(seeds().3)) { check_obj(&b)?; }
}

/// The seeds themselves are accepted, so the mutated cases start from valid files.
#[test]
fn seeds_are_valid() {
    let (json, csv, bundle, obj) = seeds();
    assert!(slab_vectors(&json, VecFormat::JsonLines)
        .iter()
        .all(Result::is_ok));
    assert_eq!(slab_vectors(&json, VecFormat::JsonLines).len(), 4);
    assert_eq!(slab_vectors(&csv, VecFormat::Csv).len(), 3);
    assert!(slab_vectors(&csv, VecFormat::Csv).iter().all(Result::is_ok));
    assert!(bundles(&bundle).iter().all(Result::is_ok));
    assert_eq!(bundles(&bundle).len(), 3);
    assert_eq!(
        parse_obj(std::str::from_utf8(&obj).unwrap(), SRC)
            .unwrap()
            .tris
            .len(),
        3
    );
}
