//! Area and logic depth of exported modules with Yosys: the one synthesis flow of the project, behind
//! `rtu synth` (and so `scripts/synth`) and `rtu fit --synth`.
//!
//! Per module, three flattened flows: generic `synth` (cells); iCE40 (`synth_ice40`: LUT4, carries,
//! flip-flops, and logic depth by `ltp` in cells, where `depth` is the longest path from inputs to
//! outputs through the registers and `stage depth` the longest path between registers, the one that sets
//! the clock); Xilinx 7-series (`synth_xilinx`: LUTs, DSP48E1, flip-flops). Logs and reports per module
//! go to `<out>/synth/<module>.*`; the table to `<out>/synth/report.csv` and `report.md`.

use crate::sweep_cmd::Area;
use std::path::Path;
use std::process::Command;

/// Options of `rtu synth`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Synthesise only the exported modules whose name contains this text (all when absent).
    pub filter: Option<String>,
    /// Modules synthesised at a time.
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
}

/// The header of `report.csv`, one column per field of [`SynthRow`] in order.
pub const CSV_HEADER: &str = "module,latency,generic_cells,ice40_lut4,ice40_carry,ice40_ff,ice40_depth,xilinx_lut,xilinx_dsp,xilinx_ff,ice40_stage_depth";

/// One module's row of the synthesis table.
#[derive(Clone, Debug, PartialEq)]
pub struct SynthRow {
    pub module: String,
    pub latency: usize,
    pub generic_cells: u64,
    pub ice40_lut4: u64,
    pub ice40_carry: u64,
    pub ice40_ff: u64,
    /// Longest path in cells from inputs to outputs, through the registers.
    pub ice40_depth: u64,
    pub xilinx_lut: u64,
    pub xilinx_dsp: u64,
    pub xilinx_ff: u64,
    /// Longest path in cells between registers.
    pub ice40_stage_depth: u64,
}

impl SynthRow {
    /// The row's values in the order of [`CSV_HEADER`].
    fn values(&self) -> [String; 11] {
        [
            self.module.clone(),
            self.latency.to_string(),
            self.generic_cells.to_string(),
            self.ice40_lut4.to_string(),
            self.ice40_carry.to_string(),
            self.ice40_ff.to_string(),
            self.ice40_depth.to_string(),
            self.xilinx_lut.to_string(),
            self.xilinx_dsp.to_string(),
            self.xilinx_ff.to_string(),
            self.ice40_stage_depth.to_string(),
        ]
    }

    /// The row of `report.csv`.
    pub fn csv(&self) -> String {
        self.values().join(",")
    }

    /// The row of `report.md`: the columns of `report.csv` with the stage depth beside the depth.
    pub fn markdown(&self) -> String {
        let v = self.values();
        let cols = [0, 1, 2, 3, 4, 5, 6, 10, 7, 8, 9].map(|i| v[i].as_str());
        format!("| {} |", cols.join(" | "))
    }

    /// What the sweep's area table holds of the row.
    pub fn area(&self) -> Area {
        Area {
            latency: self.latency,
            ice40_lut4: self.ice40_lut4,
            ice40_depth: self.ice40_depth,
            xilinx_lut: self.xilinx_lut,
            xilinx_dsp: self.xilinx_dsp,
        }
    }
}

/// Sum of the counts of the cell types matching `keep` in a Yosys `stat` report.
fn count(stat: &str, keep: impl Fn(&str) -> bool) -> u64 {
    stat.lines()
        .filter_map(|l| {
            let mut f = l.split_whitespace();
            let (name, n) = (f.next()?, f.next()?);
            keep(name).then(|| n.parse::<u64>().ok()).flatten()
        })
        .sum()
}

/// The total of the last `Number of cells:` line of a `stat` report.
fn cells(stat: &str) -> Option<u64> {
    stat.lines()
        .filter_map(|l| {
            l.trim()
                .strip_prefix("Number of cells:")?
                .trim()
                .parse()
                .ok()
        })
        .next_back()
}

/// The `length=N` of the last "Longest topological path" line of an `ltp` report.
fn ltp_length(text: &str) -> Option<u64> {
    text.lines()
        .filter(|l| l.contains("Longest topological path"))
        .filter_map(|l| {
            let i = l.find("(length=")? + 8;
            l[i..].split(')').next()?.parse().ok()
        })
        .next_back()
}

/// A 7-series LUT cell (`LUT1` .. `LUT6`).
fn xilinx_lut(n: &str) -> bool {
    n.len() == 4 && n.starts_with("LUT") && matches!(n.as_bytes()[3], b'1'..=b'6')
}

/// A 7-series flip-flop cell (`FD` and capitals: `FDRE`, `FDSE`, ...).
fn xilinx_ff(n: &str) -> bool {
    n.starts_with("FD") && n[2..].bytes().all(|c| c.is_ascii_uppercase())
}

fn yosys(script: &str, log: &Path) -> Result<(), String> {
    let out = Command::new("yosys")
        .args(["-q", "-l"])
        .arg(log)
        .args(["-p", script])
        .output()
        .map_err(|e| {
            format!(
                "cannot run yosys ({e}): install it (scripts/test does, or apt-get install yosys)"
            )
        })?;
    if !out.status.success() {
        return Err(format!(
            "yosys failed (log {}): {}",
            log.display(),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(())
}

/// Synthesises `module` from `verilog` with the three flows (logs and reports under `dir`) and returns
/// its row.
pub fn synth_module(
    verilog: &Path,
    module: &str,
    latency: usize,
    dir: &Path,
) -> Result<SynthRow, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let v = verilog.display();
    let f = |s: &str| dir.join(format!("{module}.{s}"));
    let (gen_stat, ice_stat, ice_ltp, ice_stage, xil_stat) = (
        f("generic.stat"),
        f("ice40.stat"),
        f("ice40.ltp"),
        f("ice40.stage.ltp"),
        f("xilinx.stat"),
    );
    yosys(
        &format!(
            "read_verilog {v}; synth -flatten -top {module}; tee -q -o {} stat",
            gen_stat.display()
        ),
        &f("generic.log"),
    )?;
    yosys(
        &format!(
            "read_verilog {v}; synth_ice40 -flatten -top {module}; tee -q -o {} stat; tee -q -o {} ltp -noff; tee -q -o {} ltp -noff * t:SB_DFF* %d",
            ice_stat.display(),
            ice_ltp.display(),
            ice_stage.display()
        ),
        &f("ice40.log"),
    )?;
    yosys(
        &format!(
            "read_verilog {v}; synth_xilinx -flatten -top {module}; tee -q -o {} stat",
            xil_stat.display()
        ),
        &f("xilinx.log"),
    )?;
    let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()));
    let depth = |p: &Path| -> Result<u64, String> {
        ltp_length(&read(p)?).ok_or_else(|| format!("{}: no path length", p.display()))
    };
    let (gen, ice, xil) = (read(&gen_stat)?, read(&ice_stat)?, read(&xil_stat)?);
    Ok(SynthRow {
        module: module.to_string(),
        latency,
        generic_cells: cells(&gen).unwrap_or(0),
        ice40_lut4: count(&ice, |n| n == "SB_LUT4"),
        ice40_carry: count(&ice, |n| n == "SB_CARRY"),
        ice40_ff: count(&ice, |n| n.starts_with("SB_DFF")),
        ice40_depth: depth(&ice_ltp)?,
        xilinx_lut: count(&xil, xilinx_lut),
        xilinx_dsp: count(&xil, |n| n == "DSP48E1"),
        xilinx_ff: count(&xil, xilinx_ff),
        ice40_stage_depth: depth(&ice_stage)?,
    })
}

/// `rtu synth`: exports every module into `<out>/verilog`, synthesises those whose name contains the
/// filter (`jobs` at a time, in the catalogue's order) and writes `<out>/synth/report.csv` and
/// `report.md`; returns the markdown table. An error names every module whose synthesis failed.
pub fn run(a: &Args, out: &Path) -> Result<String, String> {
    let vdir = out.join("verilog");
    crate::export_cmd::export(&vdir, None)?;
    let modules: Vec<(String, usize)> = rtl::export::catalog()
        .into_iter()
        .filter(|e| a.filter.as_deref().is_none_or(|f| e.module.contains(f)))
        .map(|e| (e.module, e.latency))
        .collect();
    if modules.is_empty() {
        return Err(format!(
            "no exported module matches `{}`",
            a.filter.as_deref().unwrap_or_default()
        ));
    }
    let dir = out.join("synth");
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results: std::sync::Mutex<Vec<Option<Result<SynthRow, String>>>> =
        std::sync::Mutex::new(vec![None; modules.len()]);
    std::thread::scope(|s| {
        for _ in 0..a.jobs.clamp(1, modules.len()) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some((m, lat)) = modules.get(i) else {
                    break;
                };
                eprintln!("synthesising {m} ...");
                let r = synth_module(&vdir.join(format!("{m}.v")), m, *lat, &dir);
                results.lock().expect("no panics while held")[i] = Some(r);
            });
        }
    });
    let results = results.into_inner().expect("no panics while held");
    let mut csv = format!("{CSV_HEADER}\n");
    let mut md = String::from("| module | latency (clocks) | generic cells | iCE40 LUT4 | iCE40 carry | iCE40 FF | iCE40 depth | iCE40 stage depth | 7-series LUT | DSP48E1 | 7-series FF |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    let mut failed = vec![];
    for ((m, _), r) in modules.iter().zip(results) {
        match r.expect("every module was taken") {
            Ok(row) => {
                csv += &format!("{}\n", row.csv());
                md += &format!("{}\n", row.markdown());
            }
            Err(e) => failed.push(format!("{m}: {e}")),
        }
    }
    if !failed.is_empty() {
        return Err(format!(
            "synthesis failed (logs in {}):\n{}",
            dir.display(),
            failed.join("\n")
        ));
    }
    crate::out_file::write_file(&dir.join("report.csv"), csv)?;
    crate::out_file::write_file(&dir.join("report.md"), md.clone())?;
    eprintln!(
        "wrote {} and {}",
        dir.join("report.csv").display(),
        dir.join("report.md").display()
    );
    Ok(md)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_and_ltp_reports_are_read() {
        let stat = "   Number of cells:  10\n     SB_LUT4   7\n     SB_CARRY  2\n     SB_DFFE 3\n     SB_DFF 1\n     LUT2 3\n     LUT6 4\n     LUT6_2 9\n     DSP48E1 1\n     FDRE 5\n     FDSE 2\n     FDx 7\n";
        assert_eq!(count(stat, |n| n == "SB_LUT4"), 7);
        assert_eq!(count(stat, |n| n.starts_with("SB_DFF")), 4);
        assert_eq!(count(stat, xilinx_lut), 7);
        assert_eq!(count(stat, xilinx_ff), 7);
        assert_eq!(cells(stat), Some(10));
        assert_eq!(cells("nothing"), None);
        let ltp = "Longest topological path in top (length=12):\nLongest topological path in top (length=31):\n";
        assert_eq!(ltp_length(ltp), Some(31));
        assert_eq!(ltp_length("nothing"), None);
    }

    #[test]
    fn a_row_is_written_in_the_header_order() {
        let r = SynthRow {
            module: "m".into(),
            latency: 1,
            generic_cells: 2,
            ice40_lut4: 3,
            ice40_carry: 4,
            ice40_ff: 5,
            ice40_depth: 6,
            xilinx_lut: 7,
            xilinx_dsp: 8,
            xilinx_ff: 9,
            ice40_stage_depth: 10,
        };
        assert_eq!(r.csv(), "m,1,2,3,4,5,6,7,8,9,10");
        assert_eq!(CSV_HEADER.split(',').count(), r.csv().split(',').count());
        assert_eq!(
            r.markdown(),
            "| m | 1 | 2 | 3 | 4 | 5 | 6 | 10 | 7 | 8 | 9 |"
        );
    }
}
