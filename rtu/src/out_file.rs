//! Output files that are complete or absent, and errors that name them.
//!
//! A named output is written to a temporary file beside it and renamed over it only when the command
//! succeeds: after any error (a line that does not parse, a vector that does not fit the format, a full
//! disk) the named file is untouched, and the temporary file is removed. An existing path that is not a
//! regular file (`/dev/stdout`, a pipe) is written in place; a symbolic link is followed, so the file it
//! names is replaced and the link stays; an existing file's permissions carry over. Standard output gets
//! its header only with the first line of results, so an input rejected before any result prints
//! nothing. Every error names the path. A run killed part-way (Ctrl-C) leaves its temporary file,
//! `.<name>.rtu-<pid>.tmp`, beside the target; the target itself is untouched.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

enum Sink {
    Stdout(BufWriter<std::io::Stdout>),
    File {
        w: BufWriter<File>,
        /// The temporary file, renamed to the target on [`Output::commit`]; `None` when written in place.
        tmp: Option<PathBuf>,
        target: PathBuf,
    },
}

/// A results stream: a named file (see the module doc) or standard output.
pub struct Output {
    sink: Sink,
    /// Written before the first byte of results (or at commit when there are none).
    header: Vec<u8>,
}

/// The temporary name of `target`: a hidden file in the same folder, so the rename stays on one file
/// system.
fn temp_path(target: &Path) -> PathBuf {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    target.with_file_name(format!(".{name}.rtu-{}.tmp", std::process::id()))
}

impl Output {
    /// Results to `path`, or to standard output when `None`.
    pub fn open(path: Option<&Path>) -> Result<Output, String> {
        let sink = match path {
            None => Sink::Stdout(BufWriter::new(std::io::stdout())),
            Some(p) => {
                let meta = std::fs::metadata(p).ok();
                let in_place = meta.as_ref().is_some_and(|m| !m.is_file());
                // Through a symbolic link: write beside, and rename over, the file it names.
                let real = std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
                let tmp = (!in_place).then(|| temp_path(&real));
                let open = tmp.as_deref().unwrap_or(p);
                let f = File::create(open).map_err(|e| {
                    format!(
                        "{}: cannot create the output file ({}): {e}",
                        p.display(),
                        open.display()
                    )
                })?;
                if let (Some(m), true) = (&meta, tmp.is_some()) {
                    f.set_permissions(m.permissions()).ok();
                }
                Sink::File {
                    w: BufWriter::new(f),
                    tmp,
                    target: if in_place { p.to_path_buf() } else { real },
                }
            }
        };
        Ok(Output {
            sink,
            header: vec![],
        })
    }

    /// What the output is called in messages.
    pub fn name(&self) -> String {
        match &self.sink {
            Sink::Stdout(_) => "stdout".into(),
            Sink::File { target, .. } => target.display().to_string(),
        }
    }

    /// Bytes to write before the first results (a CSV header line).
    pub fn set_header(&mut self, header: impl Into<Vec<u8>>) {
        self.header = header.into();
    }

    /// An I/O error of this output, naming it.
    pub fn err(&self, e: std::io::Error) -> String {
        format!("{}: cannot write: {e}", self.name())
    }

    fn raw(&mut self) -> &mut dyn Write {
        match &mut self.sink {
            Sink::Stdout(w) => w,
            Sink::File { w, .. } => w,
        }
    }

    fn write_header(&mut self) -> std::io::Result<()> {
        if !self.header.is_empty() {
            let h = std::mem::take(&mut self.header);
            self.raw().write_all(&h)?;
        }
        Ok(())
    }

    /// Flushes the results and, for a named file, renames the temporary file over the target.
    pub fn commit(mut self) -> Result<(), String> {
        self.write_header()
            .and_then(|()| self.raw().flush())
            .map_err(|e| self.err(e))?;
        if let Sink::File { tmp, target, w } = &mut self.sink {
            w.get_ref().sync_all().ok();
            if let Some(t) = tmp.take() {
                std::fs::rename(&t, &*target).map_err(|e| {
                    std::fs::remove_file(&t).ok();
                    format!(
                        "{}: cannot move the finished output into place: {e}",
                        target.display()
                    )
                })?;
            }
        }
        Ok(())
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.write_header()?;
        self.raw().write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.raw().flush()
    }
}

impl Drop for Output {
    /// An output dropped without [`Output::commit`] (an error on the way) leaves no file behind.
    fn drop(&mut self) {
        if let Sink::File { tmp: Some(t), .. } = &self.sink {
            std::fs::remove_file(t).ok();
        }
    }
}

/// Writes a whole file the same way: complete or not at all, errors naming the path.
pub fn write_file(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), String> {
    let mut o = Output::open(Some(path))?;
    o.write_all(bytes.as_ref()).map_err(|e| o.err(e))?;
    o.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rtu-out-file-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_named_output_appears_only_when_committed() {
        let d = dir("commit");
        let p = d.join("r.csv");
        std::fs::write(&p, "old\n").unwrap();
        {
            let mut o = Output::open(Some(&p)).unwrap();
            o.set_header("h\n");
            writeln!(o, "1").unwrap();
            // Dropped without commit: the old file stays and no temporary file is left.
        }
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old\n");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        let mut o = Output::open(Some(&p)).unwrap();
        o.set_header("h\n");
        writeln!(o, "1").unwrap();
        o.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "h\n1\n");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        write_file(&d.join("w.md"), "x").unwrap();
        assert_eq!(std::fs::read_to_string(d.join("w.md")).unwrap(), "x");
        // Through a link: the linked file gets the results, the link stays a link.
        #[cfg(unix)]
        {
            let link = d.join("link.csv");
            std::os::unix::fs::symlink(&p, &link).unwrap();
            write_file(&link, "via link\n").unwrap();
            assert!(std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink());
            assert_eq!(std::fs::read_to_string(&p).unwrap(), "via link\n");
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn errors_name_the_path() {
        let p = Path::new("/nonexistent-rtu-dir/r.csv");
        let e = Output::open(Some(p)).err().expect("cannot create");
        assert!(
            e.starts_with("/nonexistent-rtu-dir/r.csv: cannot create"),
            "{e}"
        );
        assert!(
            e.contains("/nonexistent-rtu-dir/.r.csv.rtu-"),
            "the temporary path: {e}"
        );
        if Path::new("/dev/full").exists() {
            let e = write_file(Path::new("/dev/full"), vec![0u8; 1 << 16]).unwrap_err();
            assert!(e.starts_with("/dev/full: cannot write"), "{e}");
        }
    }
}
