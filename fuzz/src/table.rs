//! Structured DH tables for the engine target: every field an `Arbitrary` choice among
//! the shapes real tables have (exact twists, arbitrary twists, named parameters,
//! offsets, base and tool frames, task rows), so most inputs pass validation and reach
//! the engine.

use arbitrary::Arbitrary;
use kinegen_core::model::raw::{RawJoint, RawRobot, RawValue};

/// An angle entry.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum Angle {
    /// `k·π/12` for k in -12..=12 written as text (`"5*pi/12"`): the exact values.
    PiTwelfths(i8),
    /// A decimal (radians), from a 16-bit integer: up to about ±π.
    Decimal(i16),
    /// A named parameter holding a decimal angle.
    Named(i16),
}

/// A length entry.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum Length {
    /// Zero.
    Zero,
    /// A decimal in about ±2 metres.
    Decimal(i16),
    /// A named parameter holding a decimal length.
    Named(i16),
    /// `-name` of a named parameter (sign folded into the expression).
    NegNamed(i16),
}

/// One joint row.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct Row {
    /// Prismatic instead of revolute.
    pub prismatic: bool,
    /// `a`.
    pub a: Length,
    /// `alpha`.
    pub alpha: Angle,
    /// `d` (revolute) — the constant of `d` for a prismatic joint.
    pub d: Length,
    /// `theta` (prismatic) — the constant of `theta` for a revolute joint.
    pub theta: Angle,
    /// An `offset` column.
    pub offset: Option<Angle>,
}

/// A fixed frame `xyz` + `rpy`.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct FixedFrame {
    /// Translation.
    pub xyz: [Length; 3],
    /// Roll, pitch, yaw.
    pub rpy: [Angle; 3],
}

/// A whole table.
#[derive(Arbitrary, Clone, Debug)]
pub struct Table {
    /// Modified (Craig) instead of standard DH.
    pub modified: bool,
    /// Joint rows (only the first [`MAX_ROWS`] are used).
    pub rows: Vec<Row>,
    /// Base frame.
    pub base: Option<FixedFrame>,
    /// Tool frame.
    pub tool: Option<FixedFrame>,
    /// Task rows as a bit set of `[x y z rx ry rz]`, if any.
    pub task: Option<u8>,
    /// Joint values for the comparison.
    pub q: [i16; 8],
}

/// Joint rows used per table.
pub const MAX_ROWS: usize = 7;

struct Builder {
    params: Vec<(String, RawValue)>,
}

impl Builder {
    fn param(&mut self, value: f64) -> String {
        let name = format!("p{}", self.params.len() + 1);
        self.params.push((name.clone(), RawValue::Number(value)));
        name
    }

    fn angle(&mut self, a: Angle) -> RawValue {
        match a {
            Angle::PiTwelfths(k) => {
                let k = i32::from(k).clamp(-12, 12);
                RawValue::Text(format!("{k}*pi/12"))
            }
            Angle::Decimal(x) => RawValue::Number(f64::from(x) / 10_000.0),
            Angle::Named(x) => RawValue::Text(self.param(f64::from(x) / 10_000.0)),
        }
    }

    fn length(&mut self, l: Length) -> RawValue {
        match l {
            Length::Zero => RawValue::Number(0.0),
            Length::Decimal(x) => RawValue::Number(f64::from(x) / 16_384.0),
            Length::Named(x) => RawValue::Text(self.param(f64::from(x) / 16_384.0)),
            Length::NegNamed(x) => {
                RawValue::Text(format!("-{}", self.param(f64::from(x) / 16_384.0)))
            }
        }
    }

    fn frame(&mut self, f: FixedFrame) -> Vec<(String, RawValue)> {
        let xyz = f.xyz.map(|l| self.length(l)).to_vec();
        let rpy = f.rpy.map(|a| self.angle(a)).to_vec();
        vec![
            ("xyz".into(), RawValue::List(xyz)),
            ("rpy".into(), RawValue::List(rpy)),
        ]
    }
}

impl Table {
    /// The table as the front ends hand it to `validate`.
    pub fn raw(&self) -> RawRobot {
        let mut b = Builder { params: Vec::new() };
        let joints = self
            .rows
            .iter()
            .take(MAX_ROWS)
            .map(|r| {
                let mut fields = vec![
                    ("a".to_string(), b.length(r.a)),
                    ("alpha".to_string(), b.angle(r.alpha)),
                ];
                if r.prismatic {
                    fields.push(("theta".into(), b.angle(r.theta)));
                } else {
                    fields.push(("d".into(), b.length(r.d)));
                }
                if let Some(o) = r.offset {
                    fields.push(("offset".into(), b.angle(o)));
                }
                RawJoint {
                    kind: Some(if r.prismatic { "prismatic" } else { "revolute" }.into()),
                    fields,
                }
            })
            .collect();
        let base = self.base.map(|f| b.frame(f));
        let tool = self.tool.map(|f| b.frame(f));
        let task = self.task.map(|bits| {
            ["x", "y", "z", "rx", "ry", "rz"]
                .iter()
                .enumerate()
                .filter(|(i, _)| bits & (1 << i) != 0)
                .map(|(_, n)| RawValue::Text((*n).into()))
                .collect()
        });
        RawRobot {
            name: Some("fuzzed".into()),
            convention: Some(
                if self.modified {
                    "modified"
                } else {
                    "standard"
                }
                .into(),
            ),
            params: b.params,
            joints,
            base,
            tool,
            task,
            scalar: None,
        }
    }

    /// Joint values in radians / metres (about ±3.3).
    pub fn q(&self) -> Vec<f64> {
        self.q.iter().map(|&x| f64::from(x) / 10_000.0).collect()
    }
}
