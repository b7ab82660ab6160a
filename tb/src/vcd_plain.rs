//! VCD files with plain signal names: rust-hdl's VCD writer names an array element `ray_o_lo$0` and a
//! child's signal `axis$0$e`; [`PlainVcd`] passes its output through and renames every `$scope` and
//! `$var` reference in the header by [`rtl::verilog::plain_name`], so a waveform shows the names of the
//! exported Verilog (`ray_o_lo_0`, `axis_0_e`).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// A writer that renames the signals of a VCD header as it passes through; see the module documentation.
pub struct PlainVcd<W: Write> {
    inner: W,
    /// The header line being gathered (the header is renamed line by line).
    line: Vec<u8>,
    /// Past `$enddefinitions`: the value changes pass through untouched.
    body: bool,
}

/// A VCD file with plain names, buffered.
pub type VcdFile = PlainVcd<BufWriter<File>>;

/// Creates the VCD file `path` (and its folder) with plain names.
pub fn create(path: &Path) -> std::io::Result<VcdFile> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d)?;
    }
    Ok(PlainVcd::new(BufWriter::new(File::create(path)?)))
}

impl<W: Write> PlainVcd<W> {
    /// Wraps `inner`.
    pub fn new(inner: W) -> Self {
        PlainVcd {
            inner,
            line: vec![],
            body: false,
        }
    }

    /// One header line renamed: the reference of `$scope <kind> <name> $end` and of
    /// `$var <type> <width> <id> <name> ...` (the identifier code, which may itself be `$`, is kept).
    fn rename(line: &str) -> String {
        let toks: Vec<&str> = line.split(' ').collect();
        let at = match toks.iter().position(|t| !t.is_empty()) {
            Some(i) if toks[i] == "$scope" => i + 2,
            Some(i) if toks[i] == "$var" => i + 4,
            _ => return line.to_string(),
        };
        toks.iter()
            .enumerate()
            .map(|(k, t)| {
                if k == at {
                    rtl::verilog::plain_name(t)
                } else {
                    t.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    fn flush_line(&mut self) -> std::io::Result<()> {
        let text = String::from_utf8_lossy(&self.line).into_owned();
        if text.contains("$enddefinitions") {
            self.body = true;
        }
        self.inner.write_all(Self::rename(&text).as_bytes())?;
        self.line.clear();
        Ok(())
    }
}

impl<W: Write> Write for PlainVcd<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.body {
            return self.inner.write(buf);
        }
        for (k, &c) in buf.iter().enumerate() {
            self.line.push(c);
            if c == b'\n' {
                self.flush_line()?;
                if self.body {
                    self.inner.write_all(&buf[k + 1..])?;
                    break;
                }
            }
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        if !self.line.is_empty() {
            self.flush_line()?;
        }
        self.inner.flush()
    }
}

impl<W: Write> Drop for PlainVcd<W> {
    fn drop(&mut self) {
        let _ = self.flush();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_names_become_plain_and_codes_and_values_stay() {
        let src = "$timescale 1ps $end\n$scope module uut $end\n$var wire 12 $ ray_o_lo$0 $end\n\
                   $scope module axis$1 $end\n$var wire 1 % e$q $end\n$upscope $end\n\
                   $enddefinitions $end\n#0\nb101 $\n#5\n";
        let mut w = PlainVcd::new(Vec::new());
        // Written in odd pieces, as a buffered writer might.
        for chunk in src.as_bytes().chunks(7) {
            w.write_all(chunk).unwrap();
        }
        w.flush().unwrap();
        let got = String::from_utf8(std::mem::take(&mut w.inner)).unwrap();
        assert_eq!(
            got,
            "$timescale 1ps $end\n$scope module uut $end\n$var wire 12 $ ray_o_lo_0 $end\n\
             $scope module axis_1 $end\n$var wire 1 % e_q $end\n$upscope $end\n\
             $enddefinitions $end\n#0\nb101 $\n#5\n"
        );
    }
}
