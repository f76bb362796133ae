//! A robot description as written, before any check, and where each entry is.
//!
//! Front ends (the `kinematics!` macro, TOML files) fill a [`RawRobot`] with what the
//! user wrote, entry by entry, each at a [`Path`] (`joints[2].alpha`).
//! [`crate::model::validate::validate`] turns it into a [`crate::model::dh::Robot`] or
//! into errors that name the path; the front end maps the path back to a span (macro)
//! or a line (TOML). All rules live there, once.

use std::fmt;

/// One step of a [`Path`].
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PathSeg {
    /// A key (`joints`, `alpha`).
    Key(String),
    /// An index into a list (0-based).
    Index(usize),
}

/// Where an entry is in the input: `joints[2].alpha`.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Path(pub Vec<PathSeg>);

impl Path {
    /// The root.
    pub fn root() -> Self {
        Path(Vec::new())
    }

    /// This path extended by a key.
    pub fn key(&self, k: &str) -> Self {
        let mut p = self.clone();
        p.0.push(PathSeg::Key(k.to_string()));
        p
    }

    /// This path extended by an index.
    pub fn index(&self, i: usize) -> Self {
        let mut p = self.clone();
        p.0.push(PathSeg::Index(i));
        p
    }

    /// The longest proper prefix (for falling back to an enclosing span).
    pub fn parent(&self) -> Option<Self> {
        let mut p = self.clone();
        p.0.pop().map(|_| p)
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, seg) in self.0.iter().enumerate() {
            match seg {
                PathSeg::Key(k) if i == 0 => write!(f, "{k}")?,
                PathSeg::Key(k) => write!(f, ".{k}")?,
                PathSeg::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// An entry as written: text of an expression (`pi/2`, `a2`), a number, or a list.
#[derive(Clone, Debug, PartialEq)]
pub enum RawValue {
    /// Expression text.
    Text(String),
    /// A number as parsed by the front end (TOML floats and integers).
    Number(f64),
    /// A list (`limits`, `xyz`, `rpy`, `task`).
    List(Vec<RawValue>),
    /// `true` / `false` (the `flip` column).
    Bool(bool),
}

/// A joint row as written: `type` and the columns in the order given.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawJoint {
    /// `revolute` / `prismatic` as written, if given.
    pub kind: Option<String>,
    /// Columns: `a`, `alpha`, `d`, `theta`, `offset`, `limits`, `flip`, or unknown ones
    /// (an error).
    pub fields: Vec<(String, RawValue)>,
}

/// A robot as written, before any check.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawRobot {
    /// Display name.
    pub name: Option<String>,
    /// `standard` / `modified` as written.
    pub convention: Option<String>,
    /// Parameters in order.
    pub params: Vec<(String, RawValue)>,
    /// Joint rows.
    pub joints: Vec<RawJoint>,
    /// Base frame entries (`xyz`, `rpy`).
    pub base: Option<Vec<(String, RawValue)>>,
    /// Tool frame entries.
    pub tool: Option<Vec<(String, RawValue)>>,
    /// Task rows as written.
    pub task: Option<Vec<RawValue>>,
    /// `f64` / `f32`.
    pub scalar: Option<String>,
}

/// A problem in the input, at a path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DhError {
    /// Where (`joints[1].alpha`); the root for whole-robot problems.
    pub path: Path,
    /// What is wrong, one sentence, no location.
    pub message: String,
}

impl fmt::Display for DhError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.0.is_empty() {
            f.write_str(&self.message)
        } else {
            write!(f, "{}: {}", self.path, self.message)
        }
    }
}

impl std::error::Error for DhError {}
