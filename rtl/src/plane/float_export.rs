//! Verilog export of the chained float node tester [`crate::PlaneFloat`]: module names carry format,
//! reciprocal table bits and plane count, e.g. `plane_float_e5m10_r8_k2`.

use crate::export::verilog_named;
use golden::format::float::FloatFormat;
use golden::plane::float::CullFloatFormat;

/// The (float format, planes) pairs with an instantiated `PlaneFloat` (type aliases in `rtl/src/plane/registry.rs`).
pub const PLANE_FLOAT_CONFIGS: [(FloatFormat, usize); 9] = [
    (FloatFormat::FP16, 1),
    (FloatFormat::FP16, 2),
    (FloatFormat::FP16, 4),
    (FloatFormat::BF16, 1),
    (FloatFormat::BF16, 2),
    (FloatFormat::BF16, 4),
    (FloatFormat::FP32, 1),
    (FloatFormat::FP32, 2),
    (FloatFormat::FP32, 4),
];

/// Runs `$body` with `$t` bound to the `PlaneFloat` type of a float format and plane count, or returns an
/// error for a configuration without an instantiated block.
#[macro_export]
macro_rules! with_plane_float {
    ($f:expr, $k:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        let k: usize = $k;
        match (f.e, f.m, k) {
            (5, 10, 1) => {
                type $t = $crate::PlaneFloatE5M10K1;
                Ok($body)
            }
            (5, 10, 2) => {
                type $t = $crate::PlaneFloatE5M10K2;
                Ok($body)
            }
            (5, 10, 4) => {
                type $t = $crate::PlaneFloatE5M10K4;
                Ok($body)
            }
            (8, 7, 1) => {
                type $t = $crate::PlaneFloatE8M7K1;
                Ok($body)
            }
            (8, 7, 2) => {
                type $t = $crate::PlaneFloatE8M7K2;
                Ok($body)
            }
            (8, 7, 4) => {
                type $t = $crate::PlaneFloatE8M7K4;
                Ok($body)
            }
            (8, 23, 1) => {
                type $t = $crate::PlaneFloatE8M23K1;
                Ok($body)
            }
            (8, 23, 2) => {
                type $t = $crate::PlaneFloatE8M23K2;
                Ok($body)
            }
            (8, 23, 4) => {
                type $t = $crate::PlaneFloatE8M23K4;
                Ok($body)
            }
            _ => Err(format!(
                "no PlaneFloat instance for {} with {k} planes: instantiated are e5m10, e8m7, e8m23 \
                 with 1, 2, 4 planes (add a type alias in rtl/src/plane/registry.rs for another)",
                f.name()
            )),
        }
    }};
}

/// Module name of the chained float node tester, e.g. `plane_float_e5m10_r8_k2`.
pub fn plane_float_module(cf: &CullFloatFormat, k: usize) -> String {
    format!("plane_float_{}_k{k}", cf.name())
}

/// Verilog of the chained float node tester for an instantiated format and plane count, with the
/// default table (`R = min(M, 8)`).
pub fn plane_float_verilog(f: &FloatFormat, k: usize) -> Result<String, String> {
    crate::with_plane_float!(f, k, P, {
        let mut uut = P::new();
        verilog_named(&mut uut, &plane_float_module(&CullFloatFormat::over(*f), k))
    })
}

/// Writes `<dir>/<module>.v` for every instantiated configuration and returns `(module, path, latency)`.
pub fn export_plane_float_all(
    dir: &std::path::Path,
) -> std::io::Result<Vec<(String, std::path::PathBuf, usize)>> {
    std::fs::create_dir_all(dir)?;
    let mut out = vec![];
    for (f, k) in PLANE_FLOAT_CONFIGS {
        let module = plane_float_module(&CullFloatFormat::over(f), k);
        let v = plane_float_verilog(&f, k).expect("instantiated");
        let p = dir.join(format!("{module}.v"));
        std::fs::write(&p, v)?;
        out.push((module, p, crate::PLANE_FLOAT_LATENCY));
    }
    Ok(out)
}
