//! Area and logic depth of one exported module with Yosys, the same three flows as `scripts/synth`
//! (generic `synth`, iCE40 with `ltp` depth, Xilinx 7-series; all flattened), for the fit command.

use crate::sweep_cmd::Area;
use std::path::Path;
use std::process::Command;

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

/// Synthesises `module` from `verilog` (logs and reports under `dir`) and returns its row.
pub fn synth(verilog: &Path, module: &str, latency: usize, dir: &Path) -> Result<Area, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let v = verilog.display();
    let f = |s: &str| dir.join(format!("{module}.{s}"));
    let ice_stat = f("ice40.stat");
    let ice_ltp = f("ice40.ltp");
    let xil_stat = f("xilinx.stat");
    yosys(
        &format!(
            "read_verilog {v}; synth_ice40 -flatten -top {module}; tee -q -o {} stat; tee -q -o {} ltp -noff",
            ice_stat.display(),
            ice_ltp.display()
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
    let (ice, ltp, xil) = (read(&ice_stat)?, read(&ice_ltp)?, read(&xil_stat)?);
    Ok(Area {
        latency,
        ice40_lut4: count(&ice, |n| n == "SB_LUT4"),
        ice40_depth: ltp_length(&ltp)
            .ok_or_else(|| format!("{}: no path length", ice_ltp.display()))?,
        xilinx_lut: count(&xil, |n| {
            n.len() == 4 && n.starts_with("LUT") && matches!(n.as_bytes()[3], b'1'..=b'6')
        }),
        xilinx_dsp: count(&xil, |n| n == "DSP48E1"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_and_ltp_reports_are_read() {
        let stat = "   Number of cells:  10\n     SB_LUT4   7\n     SB_CARRY  2\n     LUT2 3\n     LUT6 4\n     LUT6_2 9\n     DSP48E1 1\n";
        assert_eq!(count(stat, |n| n == "SB_LUT4"), 7);
        assert_eq!(
            count(stat, |n| n.len() == 4
                && n.starts_with("LUT")
                && matches!(n.as_bytes()[3], b'1'..=b'6')),
            7
        );
        let ltp = "Longest topological path in top (length=12):\nLongest topological path in top (length=31):\n";
        assert_eq!(ltp_length(ltp), Some(31));
        assert_eq!(ltp_length("nothing"), None);
    }
}
