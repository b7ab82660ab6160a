//! Verilog text of a rust-hdl block: the top module renamed after the configuration and every rust-hdl
//! `$` identifier made plain. A leaf of the crate: blocks, [`crate::names`] and [`crate::export`] use it,
//! it uses none of them.

use rust_hdl::prelude::*;

/// Verilog of a block, with its top module (and children) renamed to `name` and every identifier made
/// plain ([`plain_verilog`]).
pub fn verilog_named<B: Block>(uut: &mut B, name: &str) -> String {
    uut.connect_all();
    let v = generate_verilog(uut);
    let v = v
        .replace("module top(", &format!("module {name}("))
        .replace("module top$", &format!("module {name}$"))
        .replace("\ntop$", &format!("\n{name}$"))
        .replace(" top$", &format!(" {name}$"));
    plain_verilog(&v).unwrap_or_else(|e| panic!("exporting {name}: {e}"))
}

/// The plain name of a rust-hdl signal path: every `$` (rust-hdl's separator of an array index and of a
/// child's field, as in `ray_o_lo$1` or `axis$0$e`) becomes `_` (`ray_o_lo_1`, `axis_0_e`). Element `k`
/// of a rust-hdl array port `ray_o_lo[k]` is the Verilog and VCD port `ray_o_lo_k`; over the axes, 0, 1
/// and 2 are x, y and z. The exported Verilog, the VCDs and the datasheets all use these names, legal
/// identifiers in Verilog, VHDL, cocotb and Tcl constraint files alike.
pub fn plain_name(path: &str) -> String {
    path.replace('$', "_")
}

/// A port name split into the rust-hdl field and the array index: `ray_o_lo_1` is `("ray_o_lo",
/// Some(1))`, `ray_t_min` is `("ray_t_min", None)`. Unambiguous for the exported modules' ports, since
/// [`plain_verilog`] refuses a module whose scalar port ends in `_` and digits.
pub fn split_port(port: &str) -> (&str, Option<usize>) {
    match port.rsplit_once('_') {
        Some((base, idx))
            if !base.is_empty() && !idx.is_empty() && idx.bytes().all(|c| c.is_ascii_digit()) =>
        {
            match idx.parse() {
                Ok(i) => (base, Some(i)),
                Err(_) => (port, None),
            }
        }
        _ => (port, None),
    }
}

/// `v` (Verilog as rust-hdl writes it) with every identifier that holds a `$` renamed by
/// [`plain_name`]; system functions (`$signed`) are left alone. An error when a new name would
/// collide with another identifier of the same module, or when a scalar port's name of the top module
/// would read as an array element.
pub fn plain_verilog(v: &str) -> Result<String, String> {
    use std::collections::{BTreeMap, BTreeSet};
    let mut out = String::with_capacity(v.len());
    let mut plain: BTreeSet<&str> = BTreeSet::new();
    let mut renamed: BTreeMap<String, &str> = BTreeMap::new();
    let b = v.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b'"' {
            // A string literal: copied as it is.
            let end = v[i + 1..].find('"').map(|e| i + 2 + e).unwrap_or(b.len());
            out += &v[i..end];
            i = end;
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'$') {
                i += 1;
            }
            let id = &v[start..i];
            if id == "module" {
                // A new module: a new scope for the collision check (module names are renamed the
                // same way everywhere, so they cannot collide with one another unless identical).
                check_scope(&plain, &renamed)?;
                plain.clear();
                renamed.clear();
            }
            if id.contains('$') {
                let p = plain_name(id);
                out += &p;
                if let Some(other) = renamed.insert(p.clone(), id) {
                    if other != id {
                        return Err(format!("{other} and {id} would both be named {p}"));
                    }
                }
            } else {
                out += id;
                plain.insert(id);
            }
        } else if c.is_ascii_digit() {
            // A number (or the size of a sized literal): never an identifier.
            let start = i;
            while i < b.len() && b[i].is_ascii_alphanumeric() {
                i += 1;
            }
            out += &v[start..i];
        } else {
            let ch = v[i..].chars().next().expect("in bounds");
            out.push(ch);
            i += ch.len_utf8();
        }
    }
    check_scope(&plain, &renamed)?;
    // The top module's ports: a scalar must not look like an element of an array port.
    if let Some(h) = v.find("module ") {
        let header = &v[h..];
        let header = &header[..header.find(')').unwrap_or(header.len())];
        if let Some((_, list)) = header.split_once('(') {
            for port in list.split(',').map(str::trim) {
                if !port.contains('$') && split_port(port).1.is_some() {
                    return Err(format!(
                        "scalar port {port} ends in _ and digits, as an array element's name does"
                    ));
                }
            }
        }
    }
    Ok(out)
}

/// The collision check of one module's identifiers: no renamed identifier may equal a plain one.
fn check_scope(
    plain: &std::collections::BTreeSet<&str>,
    renamed: &std::collections::BTreeMap<String, &str>,
) -> Result<(), String> {
    match renamed.iter().find(|(p, _)| plain.contains(p.as_str())) {
        Some((p, id)) => Err(format!(
            "{id} would be named {p}, which is already an identifier of the same module"
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod plain_tests {
    use super::*;

    #[test]
    fn dollar_names_become_plain_and_system_functions_stay() {
        let v = "module top(clock,ray_o_lo$0,hit);\n  input wire [11:0] ray_o_lo$0;\n  \
                 assign x = $signed(ray_o_lo$0) + 12'h0a;\n  top$axis$1 axis$1(.e(axis$1$e));\n\
                 $display(\"a$b\");\nendmodule\n";
        let p = plain_verilog(v).unwrap();
        assert!(p.contains("module top(clock,ray_o_lo_0,hit);"), "{p}");
        assert!(p.contains("$signed(ray_o_lo_0) + 12'h0a"), "{p}");
        assert!(p.contains("top_axis_1 axis_1(.e(axis_1_e));"), "{p}");
        assert!(p.contains("$display(\"a$b\")"), "{p}");
    }

    #[test]
    fn a_collision_is_an_error_naming_both() {
        let e = plain_verilog("module top(a$0,a_0);\nendmodule\n").unwrap_err();
        assert!(e.contains("a$0") && e.contains("a_0"), "{e}");
    }

    #[test]
    fn names_in_different_modules_do_not_collide() {
        let v =
            "module top(a);\n  wire r$q;\nendmodule\nmodule top$u(b);\n  wire r_q;\nendmodule\n";
        assert!(plain_verilog(v).is_ok());
        let e = plain_verilog("module top(a);\n  wire r$q;\n  wire r_q;\nendmodule\n").unwrap_err();
        assert!(e.contains("r$q"), "{e}");
    }

    #[test]
    fn a_scalar_port_that_reads_as_an_element_is_refused() {
        let e = plain_verilog("module top(clock,t_1);\nendmodule\n").unwrap_err();
        assert!(e.contains("t_1"), "{e}");
    }

    #[test]
    fn ports_split_into_field_and_index() {
        assert_eq!(split_port("ray_o_lo_2"), ("ray_o_lo", Some(2)));
        assert_eq!(split_port("ray_t_min"), ("ray_t_min", None));
        assert_eq!(split_port("hit"), ("hit", None));
    }
}
