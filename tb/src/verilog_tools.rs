//! The real tools' verdict on exported Verilog: Verilator's lint and Icarus' compiler.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The project's one-line-per-waiver Verilator configuration.
pub fn waiver_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("rtl")
        .join("lint")
        .join("verilator_waiver.vlt")
}

/// Writes `verilog` to `out/verilog/<module>.v` and returns the path.
pub fn write(verilog: &str, module: &str) -> PathBuf {
    let dir = crate::out_dir().join("verilog");
    std::fs::create_dir_all(&dir).expect("create out/verilog");
    let path = dir.join(format!("{module}.v"));
    // Written beside and renamed into place, so a test of the same block running at the same time in the
    // same test binary reads either the old file or the new one, never a half-written one.
    let tmp = dir.join(format!(
        ".{module}.v.{}.{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::write(&tmp, verilog).expect("write Verilog");
    std::fs::rename(&tmp, &path).expect("rename Verilog into place");
    path
}

fn run(tool: &str, args: &[&std::ffi::OsStr]) -> (bool, String) {
    let out = Command::new(tool)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {tool} ({e}); scripts/test installs it"));
    (
        out.status.success(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    )
}

/// `verilator --lint-only -Wall` with the waivers: `Err` with the tool's output unless clean.
pub fn lint(path: &Path) -> Result<(), String> {
    let w = waiver_file();
    let (ok, text) = run(
        "verilator",
        &[
            "--lint-only".as_ref(),
            "-Wall".as_ref(),
            w.as_os_str(),
            path.as_os_str(),
        ],
    );
    if ok && !text.contains("%Warning") && !text.contains("%Error") {
        Ok(())
    } else {
        Err(format!("{}:\n{text}", path.display()))
    }
}

/// Compiles `path` with Icarus into an object file of its own (two tests may compile the same module
/// at once) and returns its path: `Err` with Icarus's output otherwise.
fn icarus_compile(path: &Path) -> Result<PathBuf, String> {
    static CALLS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let obj = path.with_extension(format!("{}.{n}.vvp", std::process::id()));
    let (ok, text) = run(
        "iverilog",
        &["-o".as_ref(), obj.as_os_str(), path.as_os_str()],
    );
    if ok {
        Ok(obj)
    } else {
        let _ = std::fs::remove_file(&obj);
        Err(format!("iverilog rejects {}:\n{text}", path.display()))
    }
}

/// Icarus compiles the file: `Err` with its output otherwise.
pub fn icarus(path: &Path) -> Result<(), String> {
    let obj = icarus_compile(path)?;
    let _ = std::fs::remove_file(&obj);
    Ok(())
}

/// Compiles `path` (a design with its own test bench) with Icarus and runs it with `vvp`: its standard
/// output, or `Err` with the tools' output.
pub fn icarus_run(path: &Path) -> Result<String, String> {
    let obj = icarus_compile(path)?;
    let out = Command::new("vvp")
        .arg(&obj)
        .output()
        .map_err(|e| format!("cannot run vvp ({e}); scripts/test installs it"));
    let _ = std::fs::remove_file(&obj);
    let out = out?;
    if out.status.success() {
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    } else {
        Err(format!(
            "vvp {} failed:\n{}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}
