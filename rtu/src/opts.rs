//! Option parsing the commands share: comma-separated lists and their items.

/// The items of a comma-separated option, each parsed (blank items skipped).
pub fn list<T>(s: &str, parse: impl Fn(&str) -> Result<T, String>) -> Result<Vec<T>, String> {
    s.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .map(parse)
        .collect()
}

/// Planes per node: a number in 1..=8 (`golden::plane::fix::MAX_PLANES`).
pub fn parse_k(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(k) if (1..=golden::plane::fix::MAX_PLANES).contains(&k) => Ok(k),
        _ => Err(format!(
            "K = `{s}`: planes per node must be a number in 1..=8"
        )),
    }
}

/// Fixed formats by preset name (`b8`, `b12`, `b16`), comma separated; empty for none.
pub fn fix_formats(s: &str) -> Result<Vec<golden::format::fixed::FixFormat>, String> {
    list(s, |x| {
        golden::format::fixed::FixFormat::parse(x).map_err(|e| e.to_string())
    })
}

/// Float formats (`fp32`, `bf16`, `fp16`, `eXmY`), comma separated; empty for none.
pub fn float_formats(s: &str) -> Result<Vec<golden::format::float::FloatFormat>, String> {
    list(s, |x| {
        golden::format::float::FloatFormat::parse(x).map_err(|e| e.to_string())
    })
}
