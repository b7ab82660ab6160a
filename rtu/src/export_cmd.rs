//! `rtu export`: the Verilog of every exported module, and beside each its datasheet
//! (`<module>.md`, `tb::ip::datasheet`) and its FuseSoC core file (`<module>.core`,
//! `tb::ip::package`).

use crate::out_file::write_file;
use crate::sweep_cmd::{load_area, load_timing};
use std::path::{Path, PathBuf};

/// Options of `rtu export`.
#[derive(clap::Args)]
pub struct Args {
    /// Also write the datasheets into this folder (the project keeps them in docs/ip).
    #[arg(long)]
    pub datasheets: Option<PathBuf>,
}

/// The area and speed lines of a module's datasheet, from the project's synthesis and timing tables.
fn figures(
    module: &str,
    area: &std::collections::HashMap<String, crate::sweep_cmd::Area>,
    timing: &std::collections::HashMap<String, crate::sweep_cmd::Timing>,
) -> Vec<String> {
    let mut f = vec![];
    if let Some(t) = timing.get(module) {
        let opt = |v: Option<u64>| v.map_or("-".to_string(), |v| v.to_string());
        f.push(format!(
            "Lattice ECP5 LFE5U-85F, speed grade 8, after place and route (Yosys `synth_ecp5`, \
             nextpnr-ecp5, seed 1, I/O registered by a wrapper; `docs/timing/timing.csv`): **{:.1} \
             MHz**, {} LUT4, {} FF, {} MULT18X18D.",
            t.fmax_mhz,
            t.lut4,
            opt(t.ff),
            opt(t.mult18)
        ));
    }
    if let Some(a) = area.get(module) {
        f.push(format!(
            "Synthesis only (Yosys; `docs/sweep/area.csv`): iCE40 {} LUT4 (logic depth {}), Xilinx \
             7-series {} LUT and {} DSP48.",
            a.ice40_lut4, a.ice40_depth, a.xilinx_lut, a.xilinx_dsp
        ));
    }
    f
}

/// Writes `<dir>/<module>.v`, `latency.csv`, and per module its datasheet and core file; the
/// datasheets also into `datasheets` when given. Returns the paths written.
pub fn export(dir: &Path, datasheets: Option<&Path>) -> Result<Vec<PathBuf>, String> {
    let mut paths = rtl::export::export_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let area = load_area(None)?;
    let timing = load_timing(None)?;
    if let Some(d) = datasheets {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: {e}", d.display()))?;
    }
    for e in rtl::export::catalog() {
        let vpath = dir.join(format!("{}.v", e.module));
        let verilog =
            std::fs::read_to_string(&vpath).map_err(|x| format!("{}: {x}", vpath.display()))?;
        let ports = tb::verilator::parse_ports(&verilog, &e.module)?;
        let doc = tb::ip::datasheet::family_doc(&e);
        let example = crate::encode_cmd::example(&e, &ports)?;
        let md = tb::ip::datasheet::render(
            &e,
            &ports,
            &doc,
            &figures(&e.module, &area, &timing),
            example.as_ref(),
        );
        let name = format!("{}.md", e.module);
        write_file(&dir.join(&name), &md)?;
        paths.push(dir.join(&name));
        if let Some(d) = datasheets {
            write_file(&d.join(&name), &md)?;
        }
        let first = doc.what.split(". ").next().unwrap_or("").to_string();
        let core = dir.join(format!("{}.core", e.module));
        write_file(
            &core,
            tb::ip::package::fusesoc_core(&e.module, e.latency, &first),
        )?;
        paths.push(core);
        // The save file for the VCD that scripts/cocotb writes beside it (scope: the cocotb toplevel).
        let gtkw = dir.join(format!("{}.gtkw", e.module));
        write_file(
            &gtkw,
            tb::ip::package::gtkw_save(
                &e.module,
                &verilog,
                &format!("{}.vcd", e.module),
                &e.module,
            )?,
        )?;
        paths.push(gtkw);
    }
    let waiver = dir.join(tb::ip::package::WAIVER_FILE);
    write_file(&waiver, tb::ip::package::verilator_waiver())?;
    paths.push(waiver);
    Ok(paths)
}
