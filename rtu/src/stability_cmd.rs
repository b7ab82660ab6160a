//! `rtu stability`: the table of every failure case of the textbook methods across the three testers,
//! naive against ours ([`golden::stability`]).

use std::path::Path;

/// Builds the stability table, writes `<out>/stability.csv` and `<out>/stability.md`, and returns the
/// Markdown table. Fails when one of our models is not conservative on a case (a correctness bug), when
/// a case does not quantise, or when a file cannot be written; the message says which.
pub fn run(out: &Path) -> Result<String, String> {
    let rows = golden::stability::table().map_err(|e| e.to_string())?;
    let md = golden::stability::render_markdown(&rows);
    let csv = golden::stability::render_csv(&rows).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (name, text) in [("stability.csv", &csv), ("stability.md", &md)] {
        let p = out.join(name);
        crate::out_file::write_file(&p, text)?;
    }
    Ok(md)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_both_files_with_one_line_per_row() {
        let dir = std::env::temp_dir().join(format!("rtu_stability_{}", std::process::id()));
        let md = run(&dir).unwrap();
        let rows = golden::stability::table().unwrap().len();
        assert_eq!(md.lines().count(), rows + 2);
        assert_eq!(
            std::fs::read_to_string(dir.join("stability.md")).unwrap(),
            md
        );
        let csv = std::fs::read_to_string(dir.join("stability.csv")).unwrap();
        assert!(csv.starts_with("tester,case,"));
        assert!(md.contains("den_rounds_to_zero") && md.contains("zero_dir_on_slab_plane"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
