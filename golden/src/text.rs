//! Numbers, byte-order marks and field names of users' text files, read one way by every reader (slab
//! and cull-plane vectors in JSON lines and CSV, bundle vectors, OBJ scenes, area tables).
//!
//! - **Numbers** are decimal (or `inf`, `-inf`, `Infinity` where a field allows infinity). A decimal that
//!   names a value f64 cannot hold is an error, not a silent change of meaning: one that rounds to 0 but
//!   is not zero (`1e-400`: a direction component of 0 means "parallel", a different ray), or one beyond
//!   the largest finite f64 (`1e400`, which would read as infinity). Subnormals (down to `5e-324`) are
//!   representable and accepted.
//! - **A UTF-8 byte-order mark** at the start of a file is accepted by every reader and ignored.
//! - **Unknown fields** (JSON keys, CSV columns, OBJ statements) are errors naming the field, with the
//!   expected ones and a near miss when there is one (`tmax` -> `t_max`): a typo must not run silently as
//!   a different input.

/// The UTF-8 byte-order mark, as a char.
pub const BOM: char = '\u{feff}';

/// `s` without a leading byte-order mark.
pub fn strip_bom(s: &str) -> &str {
    s.strip_prefix(BOM).unwrap_or(s)
}

/// True for the spellings of infinity and NaN that [`f64::from_str`] accepts (`inf`, `-Infinity`, `nan`).
fn is_named(t: &str) -> bool {
    t.trim_start_matches(['+', '-'])
        .starts_with(|c: char| c.is_ascii_alphabetic())
}

/// Parses one number. `inf`/`-inf`/`Infinity`/`nan` read as themselves (the caller's validation decides
/// where they are allowed); a decimal that underflows to zero or overflows to infinity is an error saying
/// so; anything else that is not a number is an error quoting it.
pub fn parse_f64(tok: &str) -> Result<f64, String> {
    let t = tok.trim();
    let x: f64 = t.parse().map_err(|_| format!("`{t}` is not a number"))?;
    if is_named(t) {
        return Ok(x);
    }
    range_check(t, x).map(|()| x)
}

/// The range rule of [`parse_f64`] for a decimal `t` that parsed as `x`.
fn range_check(t: &str, x: f64) -> Result<(), String> {
    if x.is_infinite() {
        return Err(format!(
            "`{t}` overflows f64 (its largest finite value is {:e}); write `inf` if infinity is meant",
            f64::MAX
        ));
    }
    let significand = t.split(['e', 'E']).next().unwrap_or("");
    if x == 0.0 && significand.bytes().any(|b| (b'1'..=b'9').contains(&b)) {
        return Err(format!(
            "`{t}` underflows f64: it is not zero, but below the smallest f64 ({:e}) and would read as 0",
            f64::from_bits(1)
        ));
    }
    Ok(())
}

/// Checks one JSON text for what serde_json lets pass silently: every number literal against the range
/// rule of [`parse_f64`] (serde_json reads `1e-400` as 0, and refuses `1e400` with a message that does not
/// say why), and keys given twice in one object (serde_json keeps the last). Literals that are not numbers
/// and malformed text are left to the JSON parser. On a failure, returns the key concerned (for a number
/// the innermost `"key":` before it, `(line)` when none) and the reason.
pub fn check_json_numbers(text: &str) -> Result<(), (String, String)> {
    let b = text.as_bytes();
    let (mut i, mut key, mut last_str) = (0, String::from("(line)"), None::<(usize, usize)>);
    // The keys seen in each open object, innermost last.
    let mut objects: Vec<Vec<String>> = vec![];
    while i < b.len() {
        match b[i] {
            b'{' => {
                objects.push(vec![]);
                last_str = None;
                i += 1;
            }
            b'}' => {
                objects.pop();
                last_str = None;
                i += 1;
            }
            b'"' => {
                let start = i + 1;
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                last_str = Some((start, i.min(b.len())));
                i += 1;
            }
            b':' => {
                if let Some((s, e)) = last_str.take() {
                    key = text.get(s..e).unwrap_or("").to_string();
                    if let Some(keys) = objects.last_mut() {
                        if keys.contains(&key) {
                            return Err((key, "given twice in one object".into()));
                        }
                        keys.push(key.clone());
                    }
                }
                i += 1;
            }
            c if c == b'-' || c.is_ascii_digit() => {
                let start = i;
                while i < b.len() && matches!(b[i], b'0'..=b'9' | b'+' | b'-' | b'.' | b'e' | b'E')
                {
                    i += 1;
                }
                let t = &text[start..i];
                if let Ok(x) = t.parse::<f64>() {
                    range_check(t, x).map_err(|why| (key.clone(), why))?;
                }
                last_str = None;
            }
            _ => i += 1,
        }
    }
    Ok(())
}

/// The error text of an unknown field `got`: the expected names, and the near miss when `got` differs from
/// one only in case, underscores or a plural `s`.
pub fn unknown_field(got: &str, expected: &[&str]) -> String {
    let fold = |s: &str| {
        let f = s.replace(['_', '-'], "").to_ascii_lowercase();
        f.strip_suffix('s').map(str::to_string).unwrap_or(f)
    };
    let near = expected.iter().find(|e| fold(e) == fold(got));
    match near {
        Some(n) => format!(
            "unknown field; did you mean `{n}`? (expected {})",
            expected.join(", ")
        ),
        None => format!("unknown field (expected {})", expected.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_out_of_f64_range_are_refused_and_subnormals_kept() {
        assert_eq!(parse_f64("5e-324"), Ok(f64::from_bits(1)));
        assert_eq!(parse_f64(" -0.0 "), Ok(-0.0));
        assert_eq!(parse_f64("0e-999"), Ok(0.0));
        assert_eq!(parse_f64("-inf"), Ok(f64::NEG_INFINITY));
        assert_eq!(parse_f64("Infinity"), Ok(f64::INFINITY));
        assert!(parse_f64("nan").unwrap().is_nan());
        assert_eq!(parse_f64("1.7976931348623157e308"), Ok(f64::MAX));
        for (t, want) in [
            ("1e-400", "underflows"),
            ("-2.5E-330", "underflows"),
            ("1e400", "overflows"),
            ("-1.8e308", "overflows"),
            ("1,5", "not a number"),
            ("", "not a number"),
        ] {
            let e = parse_f64(t).unwrap_err();
            assert!(
                e.contains(want) && e.contains(&format!("`{}`", t.trim())),
                "{t}: {e}"
            );
        }
    }

    #[test]
    fn json_numbers_are_checked_with_their_key() {
        assert_eq!(
            check_json_numbers(r#"{"a": [1, -2e-300], "b": "1e-400"}"#),
            Ok(())
        );
        let (k, why) =
            check_json_numbers(r#"{"origin": [0, 0, 0], "dir": [0, 1e-400, 1]}"#).unwrap_err();
        assert_eq!(k, "dir");
        assert!(why.contains("`1e-400` underflows"), "{why}");
        let (k, why) = check_json_numbers(r#"{"t_max": 1e400}"#).unwrap_err();
        assert_eq!((k.as_str(), why.contains("overflows")), ("t_max", true));
        // Escaped quotes inside strings do not end them.
        assert_eq!(check_json_numbers(r#"{"a\"1e-400": 0}"#), Ok(()));
        assert_eq!(check_json_numbers("1e-400").unwrap_err().0, "(line)");
        // Keys twice in one object are refused; the same key in sibling or nested objects is not.
        let (k, why) = check_json_numbers(r#"{"a": 1, "b": {"a": 2}, "a": 3}"#).unwrap_err();
        assert_eq!((k.as_str(), why.contains("twice")), ("a", true));
        assert_eq!(
            check_json_numbers(r#"{"r": [{"o": 1}, {"o": 2}], "o": {"o": 0}}"#),
            Ok(())
        );
    }

    #[test]
    fn unknown_fields_name_the_near_miss() {
        let e = unknown_field("tmax", &["t_min", "t_max"]);
        assert!(e.contains("did you mean `t_max`"), "{e}");
        let e = unknown_field("plane", &["planes", "tag"]);
        assert!(
            e.contains("did you mean `planes`") && e.contains("planes, tag"),
            "{e}"
        );
        let e = unknown_field("colour", &["planes", "tag"]);
        assert!(!e.contains("did you mean"), "{e}");
    }
}
