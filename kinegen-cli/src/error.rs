//! The CLI's errors: each prints as lines naming the problem and its place; all exit 2.

use std::fmt;

use kinegen_core::front::toml_file::LoadError;

/// Why a command did not run.
#[derive(Clone, Debug)]
pub enum CliError {
    /// The robot file did not load (`file:line: path: message`, one line per problem).
    Load(LoadError),
    /// A bad argument (`--q`, an unknown robot name).
    Usage(String),
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Load(e) => write!(f, "{e}"),
            CliError::Usage(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CliError {}
