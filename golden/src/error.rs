//! One error type for every model: bad input is named, never panicked on or clamped silently.

use thiserror::Error;

/// Errors from building formats, quantising values and reading vector files.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A coordinate, direction or t value is NaN or infinite where that is not allowed.
    #[error("{what} is {value}, which is not allowed here ({why})")]
    BadValue {
        what: String,
        value: f64,
        why: &'static str,
    },
    /// A value does not fit the fixed-point format.
    #[error("{what} = {value} does not fit the format: {why}")]
    DoesNotFit {
        what: String,
        value: f64,
        why: String,
    },
    /// A format parameter is out of range.
    #[error("format parameter {param} = {value} is out of range: {why}")]
    BadFormat {
        param: &'static str,
        value: i64,
        why: String,
    },
    /// A vector file line could not be read.
    #[error("{source_name}:{line}: field `{field}`: {why}")]
    BadLine {
        source_name: String,
        line: usize,
        field: String,
        why: String,
    },
    /// Any other input/output failure, with the path or stream it concerns.
    #[error("{0}")]
    Io(String),
}

impl Error {
    pub(crate) fn bad_value(what: impl Into<String>, value: f64, why: &'static str) -> Self {
        Error::BadValue {
            what: what.into(),
            value,
            why,
        }
    }
}
