//! The vocabulary every robot description shares, whatever its front end (DH table,
//! URDF): joint kinds, task rows, the scalar type of the generated code, named
//! parameters.

use crate::model::value::Value;

/// Joint type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// Turns about its axis (DH: θ = q + theta + offset).
    Revolute,
    /// Slides along its axis (DH: d = q + d + offset).
    Prismatic,
}

/// A row of a reduced (task) Jacobian.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TaskRow {
    /// Linear velocity along x.
    X,
    /// Linear velocity along y.
    Y,
    /// Linear velocity along z.
    Z,
    /// Angular velocity about x.
    Rx,
    /// Angular velocity about y.
    Ry,
    /// Angular velocity about z.
    Rz,
}

impl TaskRow {
    /// All rows in the order of the full geometric Jacobian `[vx vy vz ωx ωy ωz]`.
    pub const ALL: [TaskRow; 6] = [
        TaskRow::X,
        TaskRow::Y,
        TaskRow::Z,
        TaskRow::Rx,
        TaskRow::Ry,
        TaskRow::Rz,
    ];

    /// Index of this row in the full 6×N Jacobian.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The name used in DH files (`x`, …, `rz`).
    pub fn name(self) -> &'static str {
        ["x", "y", "z", "rx", "ry", "rz"][self as usize]
    }

    /// The row named `s` (`x`, …, `rz`).
    pub fn parse(s: &str) -> Option<TaskRow> {
        Self::ALL.into_iter().find(|r| r.name() == s)
    }

    /// The next row of a list that has `so_far`: `name` (trimmed) parsed, or why it
    /// cannot be one — unknown, or given twice. The TOML and macro `task` key and the
    /// command line's `--task` read their lists through this, so they say the same.
    ///
    /// ```
    /// use kinegen_core::model::robot::TaskRow;
    /// assert_eq!(TaskRow::next_in_list(" rz", &[TaskRow::X]), Ok(TaskRow::Rz));
    /// assert!(TaskRow::next_in_list("x", &[TaskRow::X]).unwrap_err().contains("twice"));
    /// ```
    pub fn next_in_list(name: &str, so_far: &[TaskRow]) -> Result<TaskRow, String> {
        let name = name.trim();
        match TaskRow::parse(name) {
            Some(r) if so_far.contains(&r) => Err(format!("task row `{name}` given twice")),
            Some(r) => Ok(r),
            None => Err(format!(
                "unknown task row `{name}`: expected x, y, z, rx, ry or rz"
            )),
        }
    }
}

/// Floating-point type of the generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Scalar {
    /// `f64` (default).
    #[default]
    F64,
    /// `f32`, for microcontrollers with a single-precision FPU.
    F32,
}

/// A named link parameter: a field of the generated robot type.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// Identifier, as written.
    pub name: String,
    /// Exact default value (constant: no other parameters).
    pub value: Value,
}
