//! Errors that name the line of a file: what every text front end reports.

use std::fmt;

use crate::model::raw::Path;

/// An error at a line of a file: renders as `file:LINE: path: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LocatedError {
    /// The file as the user named it.
    pub file: String,
    /// 1-based line; 0 when the file could not be read at all.
    pub line: usize,
    /// Where in the model (the root for whole-file problems).
    pub path: Path,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for LocatedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Line 0: the problem is with the file as a whole (it cannot be read).
        if self.line == 0 {
            write!(f, "{}: ", self.file)?;
        } else {
            write!(f, "{}:{}: ", self.file, self.line)?;
        }
        if !self.path.0.is_empty() {
            write!(f, "{}: ", self.path)?;
        }
        f.write_str(&self.message)
    }
}

/// Why a file did not load: every problem found, one per line when displayed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    /// The problems, in file order where the parser allows.
    pub errors: Vec<LocatedError>,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.errors.iter().enumerate() {
            if i > 0 {
                f.write_str("\n")?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for LoadError {}

impl LoadError {
    /// One error, at `line` of `file` (0: the file as a whole).
    pub fn at(file: &str, line: usize, path: Path, message: impl Into<String>) -> Self {
        LoadError {
            errors: vec![LocatedError {
                file: file.to_string(),
                line,
                path,
                message: message.into(),
            }],
        }
    }
}
