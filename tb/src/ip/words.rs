//! Port-word files: the tests of a pipelined core as the words on its ports, one line per test, for
//! any simulator or testbench (`rtu encode` writes them, `rtu decode` reads captured outputs back).
//!
//! A word file is text. Lines starting with `//` are comments; one of them, `// ports: a b c`, names
//! the columns (port names of the module, in any order). Every other non-blank line holds one
//! hexadecimal word per column, separated by blanks, without `0x` (`$readmemh` digits). The encoder
//! writes each word with as many digits as its port needs.
//!
//! Input files list every input port but `clock`, `rst` and `valid_in`: a line is one test, applied
//! with `valid_in` high in one clock. Output files list every output port but `valid_out`: a line is
//! one result, read in a clock where `valid_out` is high, in the order the results leave.
//!
//! [`readmemh`] packs a line's words into one word for Verilog's `$readmemh`: the first column in the
//! most significant bits; the file's comment gives each port's bit range.

use crate::verilator::Port;

/// The ports of a module that a word file of inputs (`inputs = true`) or outputs lists, in declaration
/// order: every input but `clock`, `rst` and `valid_in`; every output but `valid_out`.
pub fn columns(ports: &[Port], inputs: bool) -> Vec<Port> {
    ports
        .iter()
        .filter(|p| p.input == inputs)
        .filter(|p| !matches!(p.name.as_str(), "clock" | "rst" | "valid_in" | "valid_out"))
        .cloned()
        .collect()
}

/// Hex digits of a `width`-bit word.
fn digits(width: usize) -> usize {
    width.div_ceil(4).max(1)
}

/// A word file: comment lines `head` (each written after `// `), the `// ports:` line, then one line per
/// row.
pub fn write(head: &[String], cols: &[Port], rows: &[Vec<u64>]) -> String {
    let mut s = String::new();
    for h in head {
        s += &format!("// {h}\n");
    }
    s += "// ports:";
    for c in cols {
        s += &format!(" {}", c.name);
    }
    s += "\n";
    for r in rows {
        let line: Vec<String> = cols
            .iter()
            .zip(r)
            .map(|(c, w)| format!("{:0d$x}", w, d = digits(c.width)))
            .collect();
        s += &line.join(" ");
        s += "\n";
    }
    s
}

/// Bit range `(msb, lsb)` of each column in the packed word of [`readmemh`], and the packed width.
pub fn packing(cols: &[Port]) -> (Vec<(usize, usize)>, usize) {
    let total: usize = cols.iter().map(|c| c.width).sum();
    let mut hi = total;
    let ranges = cols
        .iter()
        .map(|c| {
            let r = (hi - 1, hi - c.width);
            hi -= c.width;
            r
        })
        .collect();
    (ranges, total)
}

/// A `$readmemh` file of `rows`: one packed word per line (the first column in the most significant
/// bits), with comments naming each column's bit range.
pub fn readmemh(head: &[String], cols: &[Port], rows: &[Vec<u64>]) -> String {
    let (ranges, total) = packing(cols);
    let mut s = String::new();
    for h in head {
        s += &format!("// {h}\n");
    }
    s += &format!("// one {total}-bit word per test: ");
    let parts: Vec<String> = cols
        .iter()
        .zip(&ranges)
        .map(|(c, (m, l))| format!("[{m}:{l}] {}", c.name))
        .collect();
    s += &parts.join(", ");
    s += "\n";
    for r in rows {
        // Hex digits of the packed word, built from the bits (the word may be wider than 128 bits).
        let mut bits = vec![false; total];
        for ((c, (_, l)), w) in cols.iter().zip(&ranges).zip(r) {
            for b in 0..c.width {
                bits[l + b] = (w >> b) & 1 == 1;
            }
        }
        let nd = digits(total);
        let mut line = String::with_capacity(nd);
        for d in (0..nd).rev() {
            let mut v = 0u32;
            for b in 0..4 {
                if bits.get(d * 4 + b).copied().unwrap_or(false) {
                    v |= 1 << b;
                }
            }
            line.push(char::from_digit(v, 16).expect("a hex digit"));
        }
        s += &line;
        s += "\n";
    }
    s
}

/// The rows of a word file `text` (named `src` in errors), each with its line number, as words of the module's `ports` that the
/// file's `// ports:` line names: each row has one word per port of `want`, in `want`'s order. Errors
/// name the file, the line and the port: a missing or unknown column, a line with too few or too many
/// words, a word that is not hex, a word wider than its port.
pub fn read(
    text: &str,
    src: &str,
    ports: &[Port],
    want: &[Port],
) -> Result<Vec<(usize, Vec<u64>)>, String> {
    let mut cols: Option<Vec<usize>> = None; // for each file column, its index in `want`
    let mut rows = vec![];
    for (n, line) in text.lines().enumerate() {
        let at = format!("{src}:{}", n + 1);
        let l = line.trim().trim_start_matches('\u{feff}');
        if let Some(c) = l.strip_prefix("//") {
            if let Some(names) = c.trim().strip_prefix("ports:") {
                if cols.is_some() {
                    return Err(format!("{at}: a second `// ports:` line"));
                }
                let mut idx = vec![];
                for name in names.split_whitespace() {
                    let Some(k) = want.iter().position(|p| p.name == name) else {
                        let known = ports.iter().any(|p| p.name == name);
                        return Err(format!(
                            "{at}: field `{name}`: {}; this file's ports are {}",
                            if known {
                                "a port of the module, but not one this file carries"
                            } else {
                                "not a port of the module"
                            },
                            want.iter()
                                .map(|p| p.name.as_str())
                                .collect::<Vec<_>>()
                                .join(" ")
                        ));
                    };
                    if idx.contains(&k) {
                        return Err(format!("{at}: field `{name}`: named twice"));
                    }
                    idx.push(k);
                }
                if let Some(p) = want.iter().enumerate().find(|(k, _)| !idx.contains(k)) {
                    return Err(format!(
                        "{at}: field `{}`: missing from the `// ports:` line",
                        p.1.name
                    ));
                }
                cols = Some(idx);
            }
            continue;
        }
        if l.is_empty() {
            continue;
        }
        let Some(idx) = &cols else {
            return Err(format!(
                "{at}: words before the `// ports:` line that names their columns"
            ));
        };
        let words: Vec<&str> = l.split_whitespace().collect();
        if words.len() != idx.len() {
            return Err(format!(
                "{at}: {} words, but the `// ports:` line names {}",
                words.len(),
                idx.len()
            ));
        }
        let mut row = vec![0u64; want.len()];
        for (w, &k) in words.iter().zip(idx) {
            let p = &want[k];
            let field = &p.name;
            let hex = w.strip_prefix("0x").unwrap_or(w);
            let hex: String = hex.chars().filter(|&c| c != '_').collect();
            if hex.is_empty() || !hex.bytes().all(|c| c.is_ascii_hexdigit()) {
                return Err(format!("{at}: field `{field}`: `{w}` is not a hex word"));
            }
            let sig = hex.trim_start_matches('0');
            if sig.len() > 16 {
                return Err(format!(
                    "{at}: field `{field}`: `{w}` is wider than the port's {} bits",
                    p.width
                ));
            }
            let v = u64::from_str_radix(if sig.is_empty() { "0" } else { sig }, 16)
                .expect("checked hex digits");
            if p.width < 64 && v >> p.width != 0 {
                return Err(format!(
                    "{at}: field `{field}`: `{w}` is wider than the port's {} bits",
                    p.width
                ));
            }
            row[k] = v;
        }
        rows.push((n + 1, row));
    }
    if cols.is_none() {
        return Err(format!("{src}: no `// ports:` line naming the columns"));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(name: &str, width: usize, input: bool) -> Port {
        Port {
            name: name.into(),
            width,
            input,
        }
    }

    fn ports() -> Vec<Port> {
        vec![
            p("clock", 1, true),
            p("rst", 1, true),
            p("valid_in", 1, true),
            p("tag_in", 16, true),
            p("a", 5, true),
            p("valid_out", 1, false),
            p("tag_out", 16, false),
            p("t", 20, false),
            p("hit", 1, false),
        ]
    }

    #[test]
    fn columns_leave_out_the_control_ports() {
        let ins: Vec<String> = columns(&ports(), true)
            .into_iter()
            .map(|p| p.name)
            .collect();
        let outs: Vec<String> = columns(&ports(), false)
            .into_iter()
            .map(|p| p.name)
            .collect();
        assert_eq!(ins, ["tag_in", "a"]);
        assert_eq!(outs, ["tag_out", "t", "hit"]);
    }

    #[test]
    fn written_words_read_back_in_any_column_order() {
        let outs = columns(&ports(), false);
        let rows = vec![vec![3, 0xfffff, 1], vec![0, 0, 0]];
        let text = write(&["head".into()], &outs, &rows);
        assert!(
            text.starts_with("// head\n// ports: tag_out t hit\n0003 fffff 1\n"),
            "{text}"
        );
        let back = |t: &str| -> Vec<Vec<u64>> {
            read(t, "f", &ports(), &outs)
                .unwrap()
                .into_iter()
                .map(|r| r.1)
                .collect()
        };
        assert_eq!(back(&text), rows);
        assert_eq!(read(&text, "f", &ports(), &outs).unwrap()[1].0, 4);
        let swapped = "// ports: hit tag_out t\n1 3 fffff\n0 0 0\n";
        assert_eq!(back(swapped), rows);
    }

    #[test]
    fn bad_words_are_errors_naming_line_and_field() {
        let outs = columns(&ports(), false);
        let e = |t: &str| read(t, "cap.hex", &ports(), &outs).unwrap_err();
        let wide = e("// ports: tag_out t hit\n1 100000 0\n");
        assert!(
            wide.starts_with("cap.hex:2: field `t`:") && wide.contains("20 bits"),
            "{wide}"
        );
        let bit = e("// ports: tag_out t hit\n1 0 2\n");
        assert!(bit.starts_with("cap.hex:2: field `hit`:"), "{bit}");
        let nothex = e("// ports: tag_out t hit\n\n1 0 g\n");
        assert!(
            nothex.starts_with("cap.hex:3: field `hit`: `g` is not a hex word"),
            "{nothex}"
        );
        let short = e("// ports: tag_out t hit\n1 0\n");
        assert!(short.starts_with("cap.hex:2: 2 words"), "{short}");
        let unknown = e("// ports: tag_out t hit bogus\n");
        assert!(
            unknown.contains("field `bogus`: not a port of the module"),
            "{unknown}"
        );
        let wrong_side = e("// ports: tag_out t hit a\n");
        assert!(
            wrong_side.contains("field `a`: a port of the module, but not one"),
            "{wrong_side}"
        );
        let missing = e("// ports: tag_out t\n");
        assert!(missing.contains("field `hit`: missing"), "{missing}");
        assert!(e("1 0 0\n").contains("before the `// ports:` line"));
        assert!(e("").contains("no `// ports:` line"));
        let huge = e("// ports: tag_out t hit\n1 10000000000000000 0\n");
        assert!(
            huge.contains("field `t`") && huge.contains("wider"),
            "{huge}"
        );
    }

    #[test]
    fn readmemh_packs_the_first_column_high() {
        let ins = columns(&ports(), true); // tag_in (16) then a (5): 21 bits, 6 hex digits
        let m = readmemh(&[], &ins, &[vec![0x8001, 0x1f]]);
        assert!(m.contains("[20:5] tag_in, [4:0] a"), "{m}");
        assert_eq!(
            m.lines().last().unwrap(),
            format!("{:06x}", (0x8001u64 << 5) | 0x1f)
        );
    }
}
