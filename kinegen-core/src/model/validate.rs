//! The rules a DH description must follow: [`validate`] checks a [`RawRobot`] entry by
//! entry and returns the [`Robot`] or every problem, each at its [`Path`].

use std::collections::{BTreeMap, BTreeSet};

use num_traits::Zero;

use crate::model::dh::{Convention, Frame, Joint, Robot};
use crate::model::raw::{DhError, Path, RawJoint, RawRobot, RawValue};
use crate::model::robot::{JointKind, Param, Scalar, TaskRow};
use crate::model::value::{parse_value, Value};

/// The columns of a joint row.
const COLUMNS: &[&str] = &["a", "alpha", "d", "theta", "offset", "limits", "flip"];

/// Identifiers that cannot be parameter names.
const RESERVED: &[&str] = &["pi", "PI", "q", "self", "Self", "crate", "super"];

/// Rust keywords (strict and reserved, 2021 edition): not usable as field names.
fn is_rust_keyword(s: &str) -> bool {
    const KEYWORDS: &[&str] = &[
        "as", "async", "await", "break", "const", "continue", "dyn", "else", "enum", "extern",
        "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut",
        "pub", "ref", "return", "static", "struct", "trait", "true", "type", "unsafe", "use",
        "where", "while", "abstract", "become", "box", "do", "final", "macro", "override", "priv",
        "try", "typeof", "unsized", "virtual", "yield", "gen",
    ];
    KEYWORDS.contains(&s)
}

/// Names the generated code binds itself: `s1`, `c1`, `c23`, `nc23` (−c23), `s1_2`,
/// `s_k1`, `t4`.
fn is_generated_local(s: &str) -> bool {
    let s = s
        .strip_prefix('n')
        .filter(|r| r.starts_with(['s', 'c']))
        .unwrap_or(s);
    let Some(rest) = s.strip_prefix(['s', 'c', 't']) else {
        return false;
    };
    let rest = rest.strip_prefix("_k").unwrap_or(rest);
    !rest.is_empty()
        && rest.starts_with(|c: char| c.is_ascii_digit())
        && rest.chars().all(|c| c.is_ascii_digit() || c == '_')
}

/// Whether `s` is an identifier usable as a parameter / struct field.
pub fn is_identifier(s: &str) -> bool {
    let mut ch = s.chars();
    matches!(ch.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && ch.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && s != "_"
}

/// Why `name` cannot name a parameter (a struct field of the generated type), if it
/// cannot: not an identifier, `pi`/`q`, a joint variable, a Rust keyword, or a name the
/// generated code binds itself.
pub fn param_name_problem(name: &str) -> Option<String> {
    if !is_identifier(name) || RESERVED.contains(&name) {
        return Some(format!(
            "`{name}` cannot name a parameter: use an identifier other than `pi` or `q`"
        ));
    }
    if name.starts_with('q') && name[1..].bytes().all(|b| b.is_ascii_digit()) {
        return Some(format!(
            "`{name}` is the name of a joint variable; choose another parameter name"
        ));
    }
    if name
        .strip_prefix("qd")
        .is_some_and(|j| j.bytes().all(|b| b.is_ascii_digit()))
    {
        return Some(format!(
            "`{name}` is the name of the joint rates (`qd`, `qd1`, …); choose another \
             parameter name"
        ));
    }
    if is_rust_keyword(name) {
        return Some(format!(
            "`{name}` is a Rust keyword; choose another parameter name"
        ));
    }
    if is_generated_local(name) {
        return Some(format!(
            "`{name}` is a name the generated code uses (`s1`/`c1` = sin/cos, `c23`/`nc23` angle \
             sums, `t4` intermediates); choose another parameter name"
        ));
    }
    None
}

/// Check the options every description shares, `task` and `scalar`, of a robot that
/// has no DH table (a URDF): the rows and the scalar type, or every problem.
pub fn task_and_scalar(raw: &RawRobot) -> Result<(Option<Vec<TaskRow>>, Scalar), Vec<DhError>> {
    let mut v = Validator {
        errors: Vec::new(),
        params: BTreeSet::new(),
    };
    let root = Path::root();
    let scalar = v.scalar(raw.scalar.as_deref(), &root);
    let task = raw.task.as_ref().map(|t| v.task(t, &root.key("task")));
    if v.errors.is_empty() {
        Ok((task, scalar))
    } else {
        Err(v.errors)
    }
}

/// Check a raw robot. Returns every problem found, in input order.
pub fn validate(raw: &RawRobot) -> Result<Robot, Vec<DhError>> {
    let mut v = Validator {
        errors: Vec::new(),
        params: BTreeSet::new(),
    };
    let root = Path::root();
    let robot = v.robot(raw, &root);
    if v.errors.is_empty() {
        Ok(robot)
    } else {
        Err(v.errors)
    }
}

struct Validator {
    errors: Vec<DhError>,
    params: BTreeSet<String>,
}

#[derive(Clone, Copy, PartialEq)]
enum Quantity {
    Length,
    Angle,
}

impl Validator {
    fn err(&mut self, path: Path, message: impl Into<String>) {
        self.errors.push(DhError {
            path,
            message: message.into(),
        });
    }

    fn robot(&mut self, raw: &RawRobot, root: &Path) -> Robot {
        let name = raw.name.clone().unwrap_or_else(|| "robot".to_string());
        let convention = match raw.convention.as_deref() {
            Some("standard") | Some("dh") | Some("distal") => Convention::Standard,
            Some("modified") | Some("mdh") | Some("craig") | Some("proximal") => {
                Convention::Modified
            }
            Some(other) => {
                self.err(
                    root.key("convention"),
                    format!("unknown convention `{other}`: expected `standard` or `modified`"),
                );
                Convention::Standard
            }
            None => {
                self.err(
                    root.clone(),
                    "missing `convention`: say `standard` (Rz Tz Tx Rx) or `modified` (Rx Tx Rz Tz)",
                );
                Convention::Standard
            }
        };
        let scalar = self.scalar(raw.scalar.as_deref(), root);
        let params = self.params(&raw.params, &root.key("params"));
        if raw.joints.is_empty() {
            self.err(root.key("joints"), "the DH table has no joints");
        }
        let joints = raw
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| self.joint(j, &root.key("joints").index(i)))
            .collect();
        let base = raw.base.as_ref().map(|f| self.frame(f, &root.key("base")));
        let tool = raw.tool.as_ref().map(|f| self.frame(f, &root.key("tool")));
        let task = raw.task.as_ref().map(|t| self.task(t, &root.key("task")));
        let mut robot = Robot {
            name,
            convention,
            params,
            joints,
            base,
            tool,
            task,
            scalar,
        };
        if self.errors.is_empty() {
            self.limits(raw, &mut robot, root);
        }
        robot
    }

    fn scalar(&mut self, raw: Option<&str>, root: &Path) -> Scalar {
        match raw {
            None | Some("f64") => Scalar::F64,
            Some("f32") => Scalar::F32,
            Some(other) => {
                self.err(
                    root.key("scalar"),
                    format!("unknown scalar type `{other}`: expected `f64` or `f32`"),
                );
                Scalar::F64
            }
        }
    }

    fn params(&mut self, raw: &[(String, RawValue)], path: &Path) -> Vec<Param> {
        let mut out = Vec::new();
        for (name, value) in raw {
            let p = path.key(name);
            if let Some(problem) = param_name_problem(name) {
                self.err(p.clone(), problem);
                continue;
            }
            if !self.params.insert(name.clone()) {
                self.err(p, format!("duplicate parameter `{name}`"));
                continue;
            }
            if let Some(val) = self.scalar_value(value, &p) {
                if !val.is_constant() {
                    self.err(
                        p,
                        format!("parameter `{name}` must have a numeric value, not `{val}`"),
                    );
                    continue;
                }
                out.push(Param {
                    name: name.clone(),
                    value: val,
                });
            }
        }
        out
    }

    /// Parse one entry without checking parameter names.
    fn scalar_value(&mut self, raw: &RawValue, path: &Path) -> Option<Value> {
        match raw {
            RawValue::Number(x) => match Value::from_f64(*x) {
                Ok(v) => Some(v),
                Err(e) => {
                    self.err(path.clone(), e.message);
                    None
                }
            },
            RawValue::Text(s) => match parse_value(s) {
                Ok(v) => Some(v),
                Err(e) => {
                    self.err(path.clone(), e.message);
                    None
                }
            },
            RawValue::List(_) => {
                self.err(path.clone(), "expected a single value, found a list");
                None
            }
            RawValue::Bool(b) => {
                self.err(path.clone(), format!("expected a number, found `{b}`"));
                None
            }
        }
    }

    /// Parse an entry and check its parameters exist and its π part fits the quantity.
    fn value(&mut self, raw: &RawValue, path: &Path, q: Quantity) -> Option<Value> {
        let v = self.scalar_value(raw, path)?;
        for name in v.param_names() {
            if !self.params.contains(name) {
                let hint = if name.starts_with('q') && name[1..].bytes().all(|b| b.is_ascii_digit())
                {
                    " (joint variables are implicit: give the constant part, or use `offset`)"
                } else {
                    ""
                };
                self.err(path.clone(), format!("undefined parameter `{name}`{hint}"));
                return None;
            }
        }
        if q == Quantity::Length && !v.pi.is_zero() {
            self.err(
                path.clone(),
                format!("`{v}` contains `pi` but this entry is a length"),
            );
            return None;
        }
        Some(v)
    }

    fn joint(&mut self, raw: &RawJoint, path: &Path) -> Joint {
        let kind = match raw.kind.as_deref() {
            Some("revolute") | Some("R") => JointKind::Revolute,
            Some("prismatic") | Some("P") => JointKind::Prismatic,
            Some(other) => {
                self.err(
                    path.key("type"),
                    format!("unknown joint type `{other}`: expected `revolute` or `prismatic`"),
                );
                JointKind::Revolute
            }
            None => {
                self.err(
                    path.clone(),
                    "missing joint type: `revolute` or `prismatic`",
                );
                JointKind::Revolute
            }
        };
        let mut seen: BTreeMap<&str, &RawValue> = BTreeMap::new();
        for (key, value) in &raw.fields {
            let p = path.key(key);
            if !COLUMNS.contains(&key.as_str()) {
                self.err(
                    p,
                    format!(
                        "unknown column `{key}`: expected a, alpha, d, theta, offset, limits or flip"
                    ),
                );
            } else if seen.insert(key.as_str(), value).is_some() {
                self.err(p, format!("column `{key}` given twice"));
            }
        }
        // The joint variable's own column may be left out (it is q_i); the others may not.
        let required: &[&str] = match kind {
            JointKind::Revolute => &["a", "alpha", "d"],
            JointKind::Prismatic => &["a", "alpha", "theta"],
        };
        for col in required {
            if !seen.contains_key(col) {
                self.err(path.clone(), format!("missing column `{col}`"));
            }
        }
        let get = |this: &mut Self, key: &str, q: Quantity| -> Value {
            match seen.get(key) {
                Some(raw) => this.value(raw, &path.key(key), q).unwrap_or_default(),
                None => Value::zero(),
            }
        };
        let a = get(self, "a", Quantity::Length);
        let alpha = get(self, "alpha", Quantity::Angle);
        let mut d = get(self, "d", Quantity::Length);
        let mut theta = get(self, "theta", Quantity::Angle);
        let offset_q = match kind {
            JointKind::Revolute => Quantity::Angle,
            JointKind::Prismatic => Quantity::Length,
        };
        let offset = get(self, "offset", offset_q);
        let flip = match seen.get("flip") {
            Some(raw) => self.flag(raw, &path.key("flip")),
            None => false,
        };
        match kind {
            JointKind::Revolute => theta = theta.add(&offset),
            JointKind::Prismatic => d = d.add(&offset),
        }
        Joint {
            kind,
            a,
            alpha,
            d,
            theta,
            limits: None,
            flip,
        }
    }

    /// `true` or `false` (also written as text, as the macro passes it).
    fn flag(&mut self, raw: &RawValue, path: &Path) -> bool {
        match raw {
            RawValue::Bool(b) => *b,
            RawValue::Text(t) if t.trim() == "true" => true,
            RawValue::Text(t) if t.trim() == "false" => false,
            _ => {
                self.err(path.clone(), "`flip` is `true` or `false`");
                false
            }
        }
    }

    /// Limits are numbers (parameters allowed, at their default values): checked once
    /// every parameter is known.
    fn limits(&mut self, raw: &RawRobot, robot: &mut Robot, root: &Path) {
        for (i, rj) in raw.joints.iter().enumerate() {
            let Some((_, lim)) = rj.fields.iter().find(|(k, _)| k == "limits") else {
                continue;
            };
            let path = root.key("joints").index(i).key("limits");
            let RawValue::List(items) = lim else {
                self.err(path, "limits must be a list `[min, max]`");
                continue;
            };
            if items.len() != 2 {
                self.err(
                    path,
                    format!("limits must be `[min, max]`, found {} values", items.len()),
                );
                continue;
            }
            let q = match robot.joints[i].kind {
                JointKind::Revolute => Quantity::Angle,
                JointKind::Prismatic => Quantity::Length,
            };
            let lo = self.value(&items[0], &path.index(0), q);
            let hi = self.value(&items[1], &path.index(1), q);
            if let (Some(lo), Some(hi)) = (lo, hi) {
                let (lo, hi) = (robot.eval(&lo), robot.eval(&hi));
                if lo > hi {
                    self.err(path, format!("limits have min {lo} > max {hi}"));
                } else {
                    robot.joints[i].limits = Some([lo, hi]);
                }
            }
        }
    }

    fn frame(&mut self, raw: &[(String, RawValue)], path: &Path) -> Frame {
        let mut xyz: [Value; 3] = Default::default();
        let mut rpy: [Value; 3] = Default::default();
        let mut seen = BTreeSet::new();
        for (key, value) in raw {
            let p = path.key(key);
            let (target, q) = match key.as_str() {
                "xyz" => (&mut xyz, Quantity::Length),
                "rpy" => (&mut rpy, Quantity::Angle),
                _ => {
                    self.err(
                        p,
                        format!("unknown entry `{key}`: a frame has `xyz` and `rpy`"),
                    );
                    continue;
                }
            };
            if !seen.insert(key.clone()) {
                self.err(p, format!("`{key}` given twice"));
                continue;
            }
            match value {
                RawValue::List(items) if items.len() == 3 => {
                    for (k, item) in items.iter().enumerate() {
                        if let Some(v) = self.value(item, &p.index(k), q) {
                            target[k] = v;
                        }
                    }
                }
                RawValue::List(items) => {
                    self.err(p, format!("`{key}` needs 3 values, found {}", items.len()))
                }
                _ => self.err(p, format!("`{key}` must be a list of 3 values")),
            }
        }
        Frame { xyz, rpy }
    }

    fn task(&mut self, raw: &[RawValue], path: &Path) -> Vec<TaskRow> {
        let mut out = Vec::new();
        if raw.is_empty() {
            self.err(
                path.clone(),
                "task rows are empty: list some of x, y, z, rx, ry, rz",
            );
        }
        for (i, item) in raw.iter().enumerate() {
            let p = path.index(i);
            let RawValue::Text(name) = item else {
                self.err(p, "a task row is one of x, y, z, rx, ry, rz");
                continue;
            };
            match TaskRow::next_in_list(name, &out) {
                Ok(r) => out.push(r),
                Err(m) => self.err(p, m),
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(s: &str) -> RawValue {
        RawValue::Text(s.to_string())
    }

    fn rr() -> RawRobot {
        let row = |a: &str| RawJoint {
            kind: Some("revolute".into()),
            fields: vec![
                ("a".into(), t(a)),
                ("alpha".into(), RawValue::Number(0.0)),
                ("d".into(), RawValue::Number(0.0)),
            ],
        };
        RawRobot {
            name: Some("RR".into()),
            convention: Some("standard".into()),
            params: vec![
                ("L1".into(), RawValue::Number(1.0)),
                ("L2".into(), RawValue::Number(0.5)),
            ],
            joints: vec![row("L1"), row("L2")],
            task: Some(vec![t("x"), t("y")]),
            ..Default::default()
        }
    }

    #[test]
    fn accepts_planar_rr() {
        let r = validate(&rr()).unwrap();
        assert_eq!(r.dof(), 2);
        assert_eq!(r.joints[1].a, Value::param("L2"));
        assert_eq!(r.param_value("L2"), 0.5);
        assert_eq!(r.task, Some(vec![TaskRow::X, TaskRow::Y]));
    }

    #[test]
    fn reports_paths() {
        let mut raw = rr();
        raw.joints[1].fields[0].1 = t("L3");
        raw.joints[0].fields.push(("alhpa".into(), t("0")));
        raw.task = Some(vec![t("x"), t("x")]);
        let errs = validate(&raw).unwrap_err();
        let got: Vec<String> = errs.iter().map(|e| e.to_string()).collect();
        assert_eq!(
            got,
            vec![
                "joints[0].alhpa: unknown column `alhpa`: expected a, alpha, d, theta, offset, limits or flip",
                "joints[1].a: undefined parameter `L3`",
                "task[1]: task row `x` given twice",
            ]
        );
    }

    #[test]
    fn offsets_fold_into_the_joint_column() {
        let mut raw = rr();
        raw.joints[0].fields.push(("offset".into(), t("-pi/2")));
        let r = validate(&raw).unwrap();
        assert_eq!(r.joints[0].theta, parse_value("-pi/2").unwrap());
    }

    #[test]
    fn lengths_reject_pi_and_limits_are_ordered() {
        let mut raw = rr();
        raw.joints[0].fields[0].1 = t("pi/2");
        assert!(validate(&raw).unwrap_err()[0].message.contains("length"));
        let mut raw = rr();
        raw.joints[0]
            .fields
            .push(("limits".into(), RawValue::List(vec![t("pi"), t("-pi")])));
        assert!(validate(&raw).unwrap_err()[0].message.contains("min"));
    }
}
