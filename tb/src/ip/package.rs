//! Packaging of the exported cores: FuseSoC core files and GTKWave save files.
//!
//! Both are text made from the module's name and its exported Verilog, written beside it:
//! - [`fusesoc_core`]: `<module>.core`, a CAPI=2 core beside `<module>.v`, with the targets `default`,
//!   `lint` (Verilator `--lint-only -Wall` with the project's waivers, [`verilator_waiver`], which is
//!   written beside the core as [`WAIVER_FILE`]) and `sim` (Icarus); `scripts/fusesoc_lint` runs the lint
//!   target.
//! - [`gtkw_save`]: a `.gtkw` save file for a VCD of the module, its signals grouped: `inputs`,
//!   `outputs`, one group per pipeline stage (see [`stage_registers`] for the rule), `other registers`.
//!   [`missing_in_vcd`] lists the signals a save file names that a VCD does not hold.

use crate::verilator::{parse_ports, Port};

/// The version of every packaged core (the last field of its VLNV `rtu:ip:<module>:<version>`).
pub const CORE_VERSION: &str = "0.1.0";

/// The file name of the Verilator waivers written beside the cores ([`verilator_waiver`]).
pub const WAIVER_FILE: &str = "verilator_waiver.vlt";

/// The project's Verilator waivers (`rtl/lint/verilator_waiver.vlt`), which the exported Verilog needs
/// to be lint-clean under `-Wall`; the core's `lint` target reads them from [`WAIVER_FILE`] beside it.
pub fn verilator_waiver() -> &'static str {
    include_str!("../../../rtl/lint/verilator_waiver.vlt")
}

/// The VLNV of `module`'s core: `rtu:ip:<module>:0.1.0`.
pub fn core_vlnv(module: &str) -> String {
    format!("rtu:ip:{module}:{CORE_VERSION}")
}

/// A FuseSoC CAPI=2 core file for `module`, to be written as `<module>.core` in the folder of
/// `<module>.v`, with [`verilator_waiver`] beside it as [`WAIVER_FILE`]. `latency` (clocks from inputs to
/// outputs) and `description` (one line) go into the description; double quotes in it become single.
///
/// Targets: `default` (the Verilog, the module as toplevel), `lint` (Verilator `--lint-only -Wall` with
/// the waivers, as `tb::verilog_tools::lint` runs it) and `sim` (Icarus, the module as toplevel: it only
/// elaborates the core, there being no test bench in the core). In the work folder FuseSoC copies the
/// Verilog to `rtl/verilog/<module>.v`, as the waivers match `*/verilog/*.v`.
pub fn fusesoc_core(module: &str, latency: usize, description: &str) -> String {
    let vlnv = core_vlnv(module);
    let desc = description.replace('"', "'").replace(['\n', '\r'], " ");
    format!(
        r#"CAPI=2:
# {module}: a core exported by rtu (rust-hdl ray-tracing intersection testers), packaged for FuseSoC.
#   fusesoc --cores-root <this folder> run --target lint {vlnv}
name: {vlnv}
description: "{desc} (latency {latency} clocks)"

filesets:
  rtl:
    files:
      # Copied to rtl/verilog/ in the work folder: the waivers match the exported files as */verilog/*.v.
      - {module}.v: {{copyto: rtl/verilog/{module}.v}}
    file_type: verilogSource
  lint_waiver:
    files:
      # The project's Verilator waivers (rtl/lint/verilator_waiver.vlt): rust-hdl's one-file-per-design
      # output and its intended zero-extensions.
      - {WAIVER_FILE}
    file_type: vlt

targets:
  default: &default
    filesets: [rtl]
    toplevel: {module}

  # verilator --lint-only -Wall with the waivers: clean, or the run fails.
  lint:
    <<: *default
    default_tool: verilator
    filesets: [lint_waiver, rtl]
    tools:
      verilator:
        mode: lint-only
        verilator_options: [-Wall]

  # Icarus with the core itself as toplevel: this only compiles and elaborates the module (no test
  # bench is packaged); add a test bench fileset and make it the toplevel to simulate.
  sim:
    <<: *default
    default_tool: icarus
"#
    )
}

/// The Verilog text of `module` (from its `module <name>(` line to its `endmodule`).
fn module_body<'a>(verilog: &'a str, module: &str) -> Option<&'a str> {
    let start = verilog.find(&format!("module {module}("))?;
    let body = &verilog[start..];
    Some(&body[..body.find("endmodule").unwrap_or(body.len())])
}

/// The sub-module instances of a module body, `(module, instance)` in declaration order: rust-hdl
/// writes each as `    <module> <instance>(` on a line of its own.
fn instances(body: &str) -> Vec<(&str, &str)> {
    body.lines()
        .filter_map(|l| {
            let l = l.trim().strip_suffix('(')?;
            let (m, i) = l.split_once(' ')?;
            let ident =
                |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
            (ident(m) && ident(i) && m != "module").then_some((m, i))
        })
        .collect()
}

/// Whether `module` (a child of ports `clock`, `d`, `q`) holds its input at least one clock: a flip-flop
/// (`always @(posedge clock)`), a cut point that is a register (`localparam registered = 1'b1`; one with
/// `1'b0` is a wire), or a chain of such (a `Wait` or delay line) of which at least one is a register.
fn is_register(verilog: &str, module: &str, depth: usize) -> bool {
    let Some(body) = module_body(verilog, module) else {
        return false;
    };
    if body.contains("localparam  registered = 1'b1;") || body.contains("always @(posedge clock)") {
        return true;
    }
    if body.contains("localparam  registered = 1'b0;") || depth > 4 {
        return false;
    }
    instances(body)
        .iter()
        .any(|(m, _)| register_q(verilog, m, depth + 1).is_some())
}

/// The width of `q` when `module` is a register-like child (ports exactly `clock`, `d`, `q`) that is a
/// register ([`is_register`]).
fn register_q(verilog: &str, module: &str, depth: usize) -> Option<usize> {
    let ports = parse_ports(verilog, module).ok()?;
    let mut names: Vec<&str> = ports.iter().map(|p| p.name.as_str()).collect();
    names.sort_unstable();
    if names != ["clock", "d", "q"] || !is_register(verilog, module, depth) {
        return None;
    }
    ports.iter().find(|p| p.name == "q").map(|p| p.width)
}

/// A pipeline stage as its registers' names tell it.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stage {
    /// `_q<N>`: the cut after step `N` (`valid_q1`, `x_q1_0`, `en_q7_2`).
    Numbered(u32),
    /// `_q<letter>`: a named cut (`_qo` the multipliers' operands and `_qp` the side data beside their
    /// products in the fixed slab tester; `_qw` the wait for the slab result in the fixed plane tester).
    Named(String),
}

impl Stage {
    /// The stage of a register instance named `inst`: its last `_`-separated token after trailing
    /// array indices (`_0`, `_1`, ...), if that token is `q<digits>` or `q<one letter>`; `None` (an other
    /// register) for delay chains (`_d`, `_d1`), the plane's tree levels (`leaf_en_0`) and the bundle
    /// sequencer's state (`busy_q`).
    pub fn of(inst: &str) -> Option<Stage> {
        let mut toks: Vec<&str> = inst.split('_').collect();
        while toks.len() > 1 && toks.last()?.chars().all(|c| c.is_ascii_digit()) {
            toks.pop();
        }
        let rest = toks.last()?.strip_prefix('q')?;
        if !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit()) {
            rest.parse().ok().map(Stage::Numbered)
        } else if rest.len() == 1 && rest.chars().all(|c| c.is_ascii_lowercase()) {
            Some(Stage::Named(format!("q{rest}")))
        } else {
            None
        }
    }

    fn label(&self) -> String {
        match self {
            Stage::Numbered(n) => format!("q{n}"),
            Stage::Named(s) => s.clone(),
        }
    }
}

/// One register of a module: its instance path below the module (`valid_q1`, `all_hit_test.e_q1_0`),
/// the width of its output `q`, and its stage.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Register {
    pub path: String,
    pub width: usize,
    pub stage: Option<Stage>,
}

/// A group of registers: its name and its registers in declaration order.
pub type Group = (String, Vec<Register>);

/// The register instances among the children of `module` (declaration order).
fn registers_of(verilog: &str, module: &str, prefix: &str) -> Vec<Register> {
    let Some(body) = module_body(verilog, module) else {
        return vec![];
    };
    instances(body)
        .into_iter()
        .filter_map(|(m, i)| {
            register_q(verilog, m, 0).map(|width| Register {
                path: format!("{prefix}{i}"),
                width,
                stage: Stage::of(i),
            })
        })
        .collect()
}

/// Orders the registers of one module into stage groups named `<title>q<N>` and the rest.
fn stage_groups(regs: Vec<Register>, title: &str) -> (Vec<Group>, Vec<Register>) {
    // Numbered stages in numeric order; a named stage after the numbered stage last declared before
    // its first register (or first, when none is).
    let mut numbered: std::collections::BTreeMap<u32, Vec<Register>> = Default::default();
    let mut named: Vec<(Option<u32>, String, Vec<Register>)> = vec![];
    let mut other = vec![];
    let mut last = None;
    for r in regs {
        match r.stage.clone() {
            Some(Stage::Numbered(n)) => {
                last = Some(n);
                numbered.entry(n).or_default().push(r);
            }
            Some(Stage::Named(s)) => match named.iter_mut().find(|(_, k, _)| *k == s) {
                Some((_, _, v)) => v.push(r),
                None => named.push((last, s, vec![r])),
            },
            None => other.push(r),
        }
    }
    let mut groups = vec![];
    let put_named = |after: Option<u32>, groups: &mut Vec<Group>| {
        for (a, s, v) in &named {
            if *a == after {
                groups.push((format!("{title}{s}"), v.clone()));
            }
        }
    };
    put_named(None, &mut groups);
    for (n, v) in numbered {
        groups.push((format!("{title}{}", Stage::Numbered(n).label()), v));
        put_named(Some(n), &mut groups);
    }
    (groups, other)
}

/// The registers of `module` grouped by pipeline stage, and the registers of no stage.
///
/// The rule, from rust-hdl's Verilog where every register is a child instance:
/// - a register is a child instance of ports `clock`, `d`, `q` that holds `d` for at least a clock (a
///   flip-flop, a `Cut` with `registered = 1'b1`, or a delay chain holding one); cuts that are wires in
///   this configuration (`registered = 1'b0`) are left out, and so are the registers inside arithmetic
///   units (the float adders and multipliers, `MulRound`, the plane sums): their stages are their own;
/// - its stage is its name's `_q<N>` or `_q<letter>` token ([`Stage::of`]): groups `stage q1`,
///   `stage q2`, ... in numeric order, a named stage (`qo`, `qp`, `qw`) after the numbered stage declared
///   just before it (the stage names are the RTL's cut names, not clock numbers: in the 6-clock fixed
///   slab tester `qo`, `qp` are clocks 2 and 3 and `q2` is clock 4);
/// - a module without stage registers of its own that wraps testers (children with `valid_in`, `tag_in`,
///   `valid_out`, `tag_out` ports: the all-hit and any-hit testers of a bundle pair) shows theirs,
///   grouped the same way under `<child> stage q<N>`, child after child (a tester inside a module with
///   stages of its own, such as the slab tester in a plane tester, is not shown);
/// - registers without a stage token (delay chains `_d`, `_d1`, the plane's tree levels, the bundle
///   sequencer's state) are returned apart, the caller's group `other registers`.
pub fn stage_registers(verilog: &str, module: &str) -> Result<(Vec<Group>, Vec<Register>), String> {
    let body = module_body(verilog, module)
        .ok_or_else(|| format!("module {module} not in the Verilog"))?;
    let (mut groups, mut other) = stage_groups(registers_of(verilog, module, ""), "stage ");
    if !groups.is_empty() {
        return Ok((groups, other));
    }
    for (m, i) in instances(body) {
        let Ok(ports) = parse_ports(verilog, m) else {
            continue;
        };
        let has = |n: &str| ports.iter().any(|p| p.name == n);
        if ["valid_in", "tag_in", "valid_out", "tag_out"]
            .iter()
            .all(|n| has(n))
        {
            let (g, o) = stage_groups(
                registers_of(verilog, m, &format!("{i}.")),
                &format!("{i} stage "),
            );
            groups.extend(g);
            other.extend(o);
        }
    }
    Ok((groups, other))
}

/// GTKWave's name of a signal `name` of `width` bits under `scope`: `scope.name`, with `[w-1:0]` for a
/// bus (as GTKWave names a VCD variable: `uut.ray_o_lo_0[7:0]`).
fn trace_name(scope: &str, name: &str, width: usize) -> String {
    let path = if scope.is_empty() {
        name.to_string()
    } else {
        format!("{scope}.{name}")
    };
    if width > 1 {
        format!("{path}[{}:0]", width - 1)
    } else {
        path
    }
}

/// GTKWave trace flags: a group's start (open) and end, hex and binary display (right-justified).
const GROUP_BEGIN: &str = "@800200";
const GROUP_END: &str = "@1000200";
const HEX: &str = "@22";
const BIN: &str = "@28";

fn push_group(out: &mut String, name: &str, traces: &[(String, usize)]) {
    if traces.is_empty() {
        return;
    }
    out.push_str(&format!("{GROUP_BEGIN}\n-{name}\n"));
    let mut flag = "";
    for (t, w) in traces {
        let f = if *w > 1 { HEX } else { BIN };
        if f != flag {
            out.push_str(f);
            out.push('\n');
            flag = f;
        }
        out.push_str(t);
        out.push('\n');
    }
    out.push_str(&format!("{GROUP_END}\n-{name}\n"));
}

/// A GTKWave save file (`.gtkw`) for a VCD of `module`: it loads `vcd_file` (as written, relative to
/// where GTKWave starts, or absolute) and shows the groups
/// - `inputs`: `clock`, `rst`, `valid_in`, `tag_in`, then the data inputs in port order;
/// - `outputs`, in port order;
/// - one group per pipeline stage of the module's registers, then its sub-testers' ([`stage_registers`]);
/// - `other registers`: the registers of no stage.
///
/// `scope` is the module's hierarchical path in the VCD (`uut` in rust-hdl's VCDs, the instance path such
/// as `tb.dut` in an Icarus one; empty for none). A register is shown by its output, `<scope>.<inst>.q`
/// (present in both kinds of VCD). Buses are hex (`@22`), single bits binary (`@28`). `Err` when
/// `module` is not in `verilog`.
pub fn gtkw_save(
    module: &str,
    verilog: &str,
    vcd_file: &str,
    scope: &str,
) -> Result<String, String> {
    let ports = parse_ports(verilog, module)?;
    let (groups, other) = stage_registers(verilog, module)?;
    let mut out = format!(
        "[*]\n[*] GTKWave save file for {module} (written by rtu)\n[*]\n\
         [dumpfile] \"{vcd_file}\"\n[timestart] 0\n[sst_expanded] 1\n[signals_width] 320\n"
    );
    let port = |p: &Port| (trace_name(scope, &p.name, p.width), p.width);
    let first = ["clock", "rst", "valid_in", "tag_in"];
    let mut inputs: Vec<&Port> = first
        .iter()
        .filter_map(|n| ports.iter().find(|p| p.input && p.name == *n))
        .collect();
    inputs.extend(
        ports
            .iter()
            .filter(|p| p.input && !first.contains(&p.name.as_str())),
    );
    let inputs: Vec<_> = inputs.into_iter().map(port).collect();
    let outputs: Vec<_> = ports.iter().filter(|p| !p.input).map(port).collect();
    push_group(&mut out, "inputs", &inputs);
    push_group(&mut out, "outputs", &outputs);
    let regs = |v: &[Register]| -> Vec<(String, usize)> {
        v.iter()
            .map(|r| {
                (
                    trace_name(scope, &format!("{}.q", r.path), r.width),
                    r.width,
                )
            })
            .collect()
    };
    for (name, v) in &groups {
        push_group(&mut out, name, &regs(v));
    }
    push_group(&mut out, "other registers", &regs(&other));
    Ok(out)
}

/// The signal names a save file shows (its trace lines), in order.
pub fn gtkw_traces(gtkw: &str) -> Vec<&str> {
    gtkw.lines()
        .filter(|l| !l.is_empty() && !l.starts_with(['[', '@', '-', '*']))
        .collect()
}

/// The names GTKWave gives the variables of a VCD: scopes joined by `.`, and a bus's range, from the
/// VCD (`q [8:0]`, as Icarus writes) or `[size-1:0]` (rust-hdl writes none).
pub fn vcd_signal_names(vcd: &str) -> Vec<String> {
    let mut names = vec![];
    let mut scope: Vec<&str> = vec![];
    let mut toks = vcd.split_whitespace();
    while let Some(t) = toks.next() {
        match t {
            "$scope" => {
                let _kind = toks.next();
                scope.extend(toks.next());
            }
            "$upscope" => {
                scope.pop();
            }
            "$var" => {
                let decl: Vec<&str> = toks.by_ref().take_while(|t| *t != "$end").collect();
                if decl.len() < 4 {
                    continue;
                }
                let size: usize = decl[1].parse().unwrap_or(1);
                let mut name = scope
                    .iter()
                    .chain([&decl[3]])
                    .copied()
                    .collect::<Vec<_>>()
                    .join(".");
                match decl.get(4) {
                    Some(r) if r.starts_with('[') => name.push_str(r),
                    _ if size > 1 && !name.ends_with(']') => {
                        name.push_str(&format!("[{}:0]", size - 1))
                    }
                    _ => {}
                }
                names.push(name);
            }
            "$enddefinitions" => break,
            _ => {}
        }
    }
    names
}

/// The traces of the save file `gtkw` that the VCD text `vcd` does not hold (empty when GTKWave will
/// find every signal).
pub fn missing_in_vcd(gtkw: &str, vcd: &str) -> Vec<String> {
    let have: std::collections::HashSet<String> = vcd_signal_names(vcd).into_iter().collect();
    gtkw_traces(gtkw)
        .into_iter()
        .filter(|t| !have.contains(*t))
        .map(str::to_string)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn verilog(module: &str) -> String {
        rtl::export::find(module).expect("exported").verilog()
    }

    /// The group names of a save file, in order.
    fn groups(gtkw: &str) -> Vec<&str> {
        let lines: Vec<&str> = gtkw.lines().collect();
        lines
            .windows(2)
            .filter(|w| w[0] == GROUP_BEGIN)
            .map(|w| &w[1][1..])
            .collect()
    }

    /// The traces of group `name`.
    fn group<'a>(gtkw: &'a str, name: &str) -> Vec<&'a str> {
        let begin = format!("{GROUP_BEGIN}\n-{name}\n");
        let start = gtkw
            .find(&begin)
            .unwrap_or_else(|| panic!("no group {name}"))
            + begin.len();
        let end = start + gtkw[start..].find(GROUP_END).expect("group end");
        gtkw_traces(&gtkw[start..end])
    }

    #[test]
    fn core_file_names_the_module_its_files_and_targets() {
        let c = fusesoc_core("slab_fix_g8_i12f8_t14f4", 4, "fixed \"slab\" tester");
        assert!(c.starts_with("CAPI=2:\n"));
        assert!(c.contains("\nname: rtu:ip:slab_fix_g8_i12f8_t14f4:0.1.0\n"));
        assert!(c.contains("description: \"fixed 'slab' tester (latency 4 clocks)\""));
        assert!(c.contains(
            "- slab_fix_g8_i12f8_t14f4.v: {copyto: rtl/verilog/slab_fix_g8_i12f8_t14f4.v}"
        ));
        assert!(c.contains("file_type: verilogSource"));
        assert!(c.contains(&format!("- {WAIVER_FILE}\n    file_type: vlt")));
        assert!(c.contains("toplevel: slab_fix_g8_i12f8_t14f4\n"));
        for t in ["  default: &default\n", "  lint:\n", "  sim:\n"] {
            assert!(c.contains(t), "no target {t}");
        }
        assert!(c.contains("mode: lint-only"));
        assert!(c.contains("verilator_options: [-Wall]"));
        assert!(c.contains("default_tool: icarus"));
        // Tabs are not YAML indentation.
        assert!(!c.contains('\t'));
    }

    #[test]
    fn waiver_is_the_project_waiver_the_lint_uses() {
        let w = verilator_waiver();
        assert!(w.starts_with("`verilator_config"));
        assert!(w.contains("-rule DECLFILENAME -file \"*/verilog/*.v\""));
        let on_disk = std::fs::read_to_string(crate::verilog_tools::waiver_file()).unwrap();
        assert_eq!(w, on_disk);
    }

    #[test]
    fn stage_token_of_register_names() {
        assert_eq!(Stage::of("valid_q1"), Some(Stage::Numbered(1)));
        assert_eq!(Stage::of("x_q1_0"), Some(Stage::Numbered(1)));
        assert_eq!(Stage::of("en_q27_3"), Some(Stage::Numbered(27)));
        assert_eq!(Stage::of("ea_qo_2"), Some(Stage::Named("qo".into())));
        assert_eq!(
            Stage::of("slab_valid_qw_4"),
            Some(Stage::Named("qw".into()))
        );
        assert_eq!(Stage::of("m_lo_d_0"), None);
        assert_eq!(Stage::of("o_lo_d1_2"), None);
        assert_eq!(Stage::of("busy_q"), None);
        assert_eq!(Stage::of("box_lo_q_0"), None);
        assert_eq!(Stage::of("leaf_en_7"), None);
    }

    #[test]
    fn slab_fix_save_file_groups_ports_and_stages() {
        let m = "slab_fix_g8_i12f8_t14f4";
        let g = gtkw_save(m, &verilog(m), "slab.vcd", "uut").unwrap();
        assert!(g.contains("[dumpfile] \"slab.vcd\"\n"));
        assert_eq!(
            groups(&g),
            ["inputs", "outputs", "stage q1", "stage q2", "stage q3", "stage q4"],
            "the wires qo, qp of the 4-clock tester are no stage"
        );
        let inputs = group(&g, "inputs");
        assert_eq!(
            inputs[..5],
            [
                "uut.clock",
                "uut.rst",
                "uut.valid_in",
                "uut.tag_in[15:0]",
                "uut.ray_o_lo_0[7:0]"
            ]
        );
        assert_eq!(inputs.len(), 27);
        assert_eq!(
            group(&g, "outputs"),
            [
                "uut.valid_out",
                "uut.tag_out[15:0]",
                "uut.hit",
                "uut.t_entry[13:0]",
                "uut.t_exit[13:0]"
            ]
        );
        let q1 = group(&g, "stage q1");
        assert!(q1.contains(&"uut.x_q1_0.q[8:0]"));
        assert!(q1.contains(&"uut.valid_q1.q"));
        assert_eq!(q1.len(), 17);
        assert_eq!(
            group(&g, "stage q4"),
            [
                "uut.entry_q4.q[13:0]",
                "uut.exit_q4.q[13:0]",
                "uut.hit_q4.q",
                "uut.valid_q4.q",
                "uut.tag_q4.q[15:0]"
            ]
        );
        // Flags: a bus in hex, a bit in binary, each right before its traces.
        assert!(g.contains("@28\nuut.clock\nuut.rst\nuut.valid_in\n@22\nuut.tag_in[15:0]\n"));
        assert!(!g.contains("other registers"));
    }

    #[test]
    fn deep_slab_fix_puts_named_stages_after_q1() {
        let m = "slab_fix_g8_i12f8_t14f4_p6";
        let g = gtkw_save(m, &verilog(m), "x.vcd", "tb.dut").unwrap();
        assert_eq!(
            groups(&g)[2..],
            ["stage q1", "stage qo", "stage qp", "stage q2", "stage q3", "stage q4"]
        );
        assert!(group(&g, "stage qo").contains(&"tb.dut.ea_qo_0.q[8:0]"));
    }

    #[test]
    fn slab_float_delays_are_other_registers() {
        let m = "slab_float_e5m10";
        let g = gtkw_save(m, &verilog(m), "f.vcd", "uut").unwrap();
        assert_eq!(
            groups(&g),
            [
                "inputs",
                "outputs",
                "stage q7",
                "stage q8",
                "stage q9",
                "other registers"
            ]
        );
        let other = group(&g, "other registers");
        assert!(other.contains(&"uut.m_lo_d_0.q[15:0]"));
        assert!(other.contains(&"uut.empty_d.q"));
    }

    #[test]
    fn bundle_pair_groups_its_two_testers() {
        let m = "bundle_fix_g8_i12f8_t14f4_d6";
        let g = gtkw_save(m, &verilog(m), "b.vcd", "uut").unwrap();
        let names = groups(&g);
        assert_eq!(names[..2], ["inputs", "outputs"]);
        for t in ["all_hit_test", "any_hit_test"] {
            for q in 1..=3 {
                assert!(
                    names.contains(&format!("{t} stage q{q}").as_str()),
                    "{t} q{q}: {names:?}"
                );
            }
        }
        assert!(group(&g, "all_hit_test stage q1").contains(&"uut.all_hit_test.valid_q1.q"));
    }

    #[test]
    fn plane_fix_groups_its_stages() {
        // Building a plane tester needs more than a test thread's stack.
        let (v, v11) = crate::plane::float::with_big_stack(|| {
            let v = verilog("plane_fix_g8_i12f8_t14f4_n8_fd8_r8_k1");
            (v, verilog("plane_fix_g8_i12f8_t14f4_n8_fd8_r8_k1_p11"))
        });
        let stages = [
            "stage q1", "stage q2", "stage q3", "stage q4", "stage q5", "stage q6",
        ];
        let g = gtkw_save("plane_fix_g8_i12f8_t14f4_n8_fd8_r8_k1", &v, "p.vcd", "uut").unwrap();
        // The slab result's waits are all wires at this depth (the slab tester takes the 6 clocks).
        assert_eq!(groups(&g)[2..], stages);
        assert!(group(&g, "stage q6").contains(&"uut.valid_q6.q"));
        // In the 11-clock tester, 3 of the 5 waits of each slab result are registers.
        let g = gtkw_save(
            "plane_fix_g8_i12f8_t14f4_n8_fd8_r8_k1_p11",
            &v11,
            "p.vcd",
            "uut",
        )
        .unwrap();
        assert_eq!(groups(&g)[2], "stage qw");
        assert_eq!(groups(&g)[3..], stages);
        let qw = group(&g, "stage qw");
        assert_eq!(qw.len(), 5 * 3, "{qw:?}");
        assert!(qw.contains(&"uut.slab_valid_qw_2.q") && !qw.contains(&"uut.slab_valid_qw_3.q"));
    }

    #[test]
    fn unknown_module_is_an_error() {
        assert!(gtkw_save("nope", &verilog("slab_fix_g8_i12f8_t14f4"), "x", "uut").is_err());
    }

    #[test]
    fn vcd_names_follow_gtkwave() {
        let vcd = "$timescale 1ps $end\n$scope module tb $end\n$scope module dut $end\n\
                   $var wire 1 ! clock $end\n$var wire 9 \" q [8:0] $end\n$scope module r $end\n\
                   $var wire 9 # q $end\n$upscope $end\n$upscope $end\n$upscope $end\n\
                   $enddefinitions $end\n#0\n";
        assert_eq!(
            vcd_signal_names(vcd),
            ["tb.dut.clock", "tb.dut.q[8:0]", "tb.dut.r.q[8:0]"]
        );
        let gtkw = "[dumpfile] \"x\"\n@28\ntb.dut.clock\n@22\ntb.dut.r.q[8:0]\ntb.dut.nope\n";
        assert_eq!(missing_in_vcd(gtkw, vcd), ["tb.dut.nope"]);
    }

    /// Every trace of the save file is in a VCD the rust-hdl simulation writes of the same block.
    #[test]
    fn save_file_names_only_signals_of_the_rust_hdl_vcd() {
        let fmt = golden::format::fixed::FixFormat::b8();
        let dir = std::env::temp_dir().join(format!("rtu-gtkw-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("slab.vcd");
        {
            use crate::dut::PipelinedDut;
            let mut sim =
                crate::rtl_sim::TesterSim::<rtl::SlabFixB8>::with_vcd(&fmt, &path).unwrap();
            for _ in 0..3 {
                sim.step(None);
            }
        }
        let vcd = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let m = "slab_fix_g8_i12f8_t14f4";
        let g = gtkw_save(m, &verilog(m), "slab.vcd", "uut").unwrap();
        assert!(gtkw_traces(&g).len() > 50);
        assert_eq!(missing_in_vcd(&g, &vcd), Vec::<String>::new());
    }
}
