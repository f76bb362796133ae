//! Robots from TOML files, with errors that name the line.
//!
//! The format (see `robots/*.toml`):
//!
//! ```toml
//! name = "planar RR"
//! convention = "standard"          # or "modified"
//! task = ["x", "y"]                # optional: rows of the reduced Jacobian
//! scalar = "f64"                   # optional: "f64" or "f32"
//! [params]
//! L1 = 1.0
//! L2 = 0.5
//! [[joints]]
//! type = "revolute"                # or "prismatic"
//! a = "L1"                         # number, parameter name or expression string
//! alpha = 0
//! d = 0
//! [[joints]]
//! type = "revolute"
//! a = "L2"
//! alpha = 0
//! d = 0
//! limits = ["-pi", "pi"]
//! flip = true                      # optional: θ = −q + θ₀ (the joint runs against z)
//! [tool]                           # optional, likewise [base]
//! xyz = [0, 0, 0.1]
//! rpy = [0, 0, "pi/2"]
//! [budget]                         # optional engine bounds
//! nodes = 5000
//! ```
//!
//! The file is read into a [`RawRobot`] with the byte span of every entry, checked by
//! [`crate::model::validate::validate`], and every error's path is mapped back to a line:
//!
//! ```
//! let src = "name = \"R\"\nconvention = \"standard\"\n[[joints]]\ntype = \"revolute\"\na = 1\nalhpa = 0\nd = 0\n";
//! let err = kinegen_core::front::toml_file::load_str(src, "r.toml").unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "r.toml:3: joints[0]: missing column `alpha`\n\
//!      r.toml:6: joints[0].alhpa: unknown column `alhpa`: expected a, alpha, d, theta, offset, limits or flip"
//! );
//! ```

use std::collections::HashMap;
use std::fmt;
use std::ops::Range;
use std::path::Path as FsPath;

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use toml::Spanned;

use crate::chain::Chain;
pub use crate::front::located::{LoadError, LocatedError};
use crate::front::urdf::Urdf;
use crate::front::urdf_robot::{self, Problem, UrdfOptions, URDF_KEYS};
use crate::model::dh::Robot;
use crate::model::input;
use crate::model::options::{Budget, Options};
use crate::model::raw::{DhError, Path, RawJoint, RawRobot, RawValue};
use crate::model::validate::validate;

/// Load and check a robot from TOML text. `file_label` names the file in messages.
pub fn load_str(src: &str, file_label: &str) -> Result<(Robot, Options), LoadError> {
    let file = RawFile::parse(src, file_label)?;
    if file.urdf.is_some() {
        return Err(LoadError::at(
            file_label,
            file.line_of(&Path::root().key("urdf")),
            Path::root().key("urdf"),
            "this file names a URDF, not a DH table: load it with `load_description_file`",
        ));
    }
    let checks = match validate(&file.robot) {
        Ok(robot) if file.shape_errors.is_empty() => {
            let options = Options {
                budget: file.budget.unwrap_or_default(),
                ik_free: file.ik_free_of(robot.dof())?,
                ..Options::default()
            };
            return Ok((robot, options));
        }
        Ok(_) => Vec::new(),
        Err(errs) => errs,
    };
    let errors = input::combine_errors(file.shape_errors.clone(), checks);
    let mut located = file.locate_all(errors);
    located.errors.sort_by_key(|e| e.line);
    Err(located)
}

/// Load and check a robot from a TOML file; messages name the file as `path` is written.
pub fn load_file(path: &FsPath) -> Result<(Robot, Options), LoadError> {
    let label = path.display().to_string();
    match std::fs::read_to_string(path) {
        Ok(src) => load_str(&src, &label),
        Err(e) => Err(LoadError {
            errors: vec![LocatedError {
                file: label,
                line: 0,
                path: Path::root(),
                message: format!("cannot read the file: {e}"),
            }],
        }),
    }
}

/// What a robot file describes: a DH table, or a chain of a URDF.
#[derive(Clone, Debug, PartialEq)]
pub enum Description {
    /// A DH table (`[[joints]]`).
    Dh(Box<Robot>),
    /// A chain of the URDF the file names (`urdf = "…"`).
    Urdf(Box<Chain>),
}

impl Description {
    /// The engine's input.
    pub fn chain(&self) -> Chain {
        match self {
            Description::Dh(r) => r.chain(),
            Description::Urdf(c) => (**c).clone(),
        }
    }
}

/// Load a robot file of either kind; a URDF it names is read relative to its directory.
pub fn load_description_file(path: &FsPath) -> Result<(Description, Options), LoadError> {
    let label = path.display().to_string();
    let src = std::fs::read_to_string(path).map_err(|e| {
        LoadError::at(
            &label,
            0,
            Path::root(),
            format!("cannot read the file: {e}"),
        )
    })?;
    let dir = path.parent().unwrap_or(FsPath::new("")).to_path_buf();
    let read = |rel: &str| {
        let p = dir.join(rel);
        std::fs::read_to_string(&p)
            .map(|s| (p.display().to_string(), s))
            .map_err(|e| format!("cannot read `{}`: {e}", p.display()))
    };
    load_description_str(&src, &label, &read)
}

/// The text a URDF file holds, and its label for messages, by the path a robot file
/// gives (`read("urdf/ur5.urdf")`).
pub type ReadUrdf<'a> = &'a dyn Fn(&str) -> Result<(String, String), String>;

/// Load a robot file of either kind from text; `read` gives the URDF it names.
pub fn load_description_str(
    src: &str,
    file_label: &str,
    read: ReadUrdf,
) -> Result<(Description, Options), LoadError> {
    let file = RawFile::parse(src, file_label)?;
    let Some((rel, options)) = &file.urdf else {
        return load_str(src, file_label).map(|(r, o)| (Description::Dh(Box::new(r)), o));
    };
    if !file.shape_errors.is_empty() {
        return Err(file.locate_all(file.shape_errors.clone()));
    }
    let at_key = |message: String| {
        file.locate_all(vec![DhError {
            path: Path::root().key("urdf"),
            message,
        }])
    };
    let (label, text) = read(rel).map_err(at_key)?;
    let urdf = Urdf::parse(&text, &label)?;
    let chain = urdf_robot::chain(&urdf, options).map_err(|problems| LoadError {
        errors: problems
            .into_iter()
            .map(|p| match p {
                Problem::Option(e) => file.locate(e),
                Problem::File(e) => e,
            })
            .collect(),
    })?;
    let options = Options {
        budget: file.budget.unwrap_or_default(),
        ik_free: file.ik_free_of(chain.dof())?,
        ..Options::default()
    };
    Ok((Description::Urdf(Box::new(chain)), options))
}

/// A TOML robot before validation, with the line of every entry.
///
/// Front ends that merge a file with other input (the macro's file form with overrides)
/// validate the merged [`RawRobot`] themselves and use [`RawFile::locate`] for the
/// errors that come from the file.
#[derive(Clone, Debug)]
pub struct RawFile {
    /// The robot as written.
    pub robot: RawRobot,
    /// The `[budget]` table, if given.
    pub budget: Option<Budget>,
    /// `ik_free = 7`, if given: the joint (1-based) a 7-joint arm's closed-form IK leaves
    /// free.
    pub ik_free: Option<usize>,
    /// Top-level keys present in the file.
    pub keys: Vec<String>,
    /// `urdf = "…"` and the options for it, when the file names a URDF instead of a DH
    /// table (then [`RawFile::robot`] is empty).
    pub urdf: Option<(String, UrdfOptions)>,
    /// Entries of the wrong kind (a string where a table belongs, unknown keys, …),
    /// to be reported with [`crate::model::validate::validate`]'s errors through
    /// [`input::combine_errors`].
    pub shape_errors: Vec<DhError>,
    label: String,
    line_starts: Vec<usize>,
    spans: HashMap<Path, Range<usize>>,
}

impl RawFile {
    /// Parse TOML text into a raw robot. Fails only on TOML syntax errors; entries of
    /// the wrong shape are left out of [`RawFile::robot`] and listed in
    /// [`RawFile::shape_errors`]; the DH rules are left to [`crate::model::validate::validate`].
    pub fn parse(src: &str, file_label: &str) -> Result<RawFile, LoadError> {
        let line_starts = std::iter::once(0)
            .chain(src.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let mut file = RawFile {
            robot: RawRobot::default(),
            budget: None,
            ik_free: None,
            keys: Vec::new(),
            urdf: None,
            shape_errors: Vec::new(),
            label: file_label.to_string(),
            line_starts,
            spans: HashMap::new(),
        };
        let root: Spanned<Node> = match toml::from_str(src) {
            Ok(root) => root,
            Err(e) => {
                let line = e.span().map_or(1, |s| file.line_at(s.start));
                return Err(LoadError {
                    errors: vec![LocatedError {
                        file: file.label,
                        line,
                        path: Path::root(),
                        // One line: toml's messages put details on further lines.
                        message: e
                            .message()
                            .lines()
                            .map(str::trim)
                            .filter(|l| !l.is_empty())
                            .collect::<Vec<_>>()
                            .join(": "),
                    }],
                });
            }
        };
        let mut reader = Reader {
            spans: &mut file.spans,
            errors: Vec::new(),
        };
        let names_urdf =
            matches!(root.get_ref(), Node::Table(e) if e.iter().any(|(k, _)| k == "urdf"));
        if names_urdf {
            file.urdf = reader.urdf_root(&root, &mut file.budget, &mut file.keys);
        } else {
            reader.root(&root, &mut file.robot, &mut file.budget, &mut file.keys);
        }
        file.ik_free = reader.ik_free(&root);
        file.shape_errors = reader.errors;
        Ok(file)
    }

    /// The file's `ik_free` checked against the robot's `dof` (0-based), or the error at
    /// its line.
    pub fn ik_free_of(&self, dof: usize) -> Result<Option<usize>, LoadError> {
        let Some(k) = self.ik_free else {
            return Ok(None);
        };
        let path = Path::root().key("ik_free");
        input::check_ik_free(k, dof)
            .map(Some)
            .map_err(|message| LoadError::at(&self.label, self.line_of(&path), path, message))
    }

    /// 1-based line of the entry at `path`, or of the closest enclosing entry that has
    /// one (line 1 for the root).
    pub fn line_of(&self, path: &Path) -> usize {
        let mut p = Some(path.clone());
        while let Some(cur) = p {
            if let Some(span) = self.spans.get(&cur) {
                return self.line_at(span.start);
            }
            p = cur.parent();
        }
        1
    }

    /// An error of this file at its line.
    pub fn locate(&self, err: DhError) -> LocatedError {
        LocatedError {
            file: self.label.clone(),
            line: self.line_of(&err.path),
            path: err.path,
            message: err.message,
        }
    }

    /// All errors of this file at their lines.
    pub fn locate_all(&self, errs: Vec<DhError>) -> LoadError {
        LoadError {
            errors: errs.into_iter().map(|e| self.locate(e)).collect(),
        }
    }

    fn line_at(&self, offset: usize) -> usize {
        self.line_starts.partition_point(|&s| s <= offset).max(1)
    }
}

/// A TOML value with the span of every nested value.
#[derive(Debug)]
enum Node {
    Str(String),
    Int(i64),
    Float(f64),
    Bool(bool),
    Datetime,
    Array(Vec<Spanned<Node>>),
    Table(Vec<(String, Spanned<Node>)>),
}

impl Node {
    fn kind(&self) -> &'static str {
        match self {
            Node::Str(_) => "a string",
            Node::Int(_) | Node::Float(_) => "a number",
            Node::Bool(_) => "a boolean",
            Node::Datetime => "a date",
            Node::Array(_) => "a list",
            Node::Table(_) => "a table",
        }
    }
}

/// The key under which toml hands a datetime to a visitor (`toml_datetime`'s private
/// protocol): we only need to recognise it to refuse dates politely.
const DATETIME_KEY: &str = "$__toml_private_datetime";

impl<'de> Deserialize<'de> for Node {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NodeVisitor)
    }
}

struct NodeVisitor;

impl<'de> Visitor<'de> for NodeVisitor {
    type Value = Node;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a TOML value")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Node, E> {
        Ok(Node::Bool(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Node, E> {
        Ok(Node::Int(v))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Node, E> {
        match i64::try_from(v) {
            Ok(v) => Ok(Node::Int(v)),
            Err(_) => Ok(Node::Float(v as f64)),
        }
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Node, E> {
        Ok(Node::Float(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Node, E> {
        Ok(Node::Str(v.to_string()))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Node, E> {
        Ok(Node::Str(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Node, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element()? {
            items.push(item);
        }
        Ok(Node::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Node, A::Error> {
        let mut entries = Vec::new();
        while let Some(key) = map.next_key::<String>()? {
            if key == DATETIME_KEY {
                let _: String = map.next_value()?;
                return Ok(Node::Datetime);
            }
            entries.push((key, map.next_value()?));
        }
        Ok(Node::Table(entries))
    }
}

/// Turns the node tree into a [`RawRobot`], recording spans and shape errors.
struct Reader<'a> {
    spans: &'a mut HashMap<Path, Range<usize>>,
    errors: Vec<DhError>,
}

impl Reader<'_> {
    fn err(&mut self, path: Path, message: impl Into<String>) {
        self.errors.push(DhError {
            path,
            message: message.into(),
        });
    }

    fn mark(&mut self, path: &Path, node: &Spanned<Node>) {
        self.spans.insert(path.clone(), node.span());
    }

    fn root(
        &mut self,
        node: &Spanned<Node>,
        robot: &mut RawRobot,
        budget: &mut Option<Budget>,
        keys: &mut Vec<String>,
    ) {
        let Node::Table(entries) = node.get_ref() else {
            self.err(Path::root(), "a robot file is a TOML table");
            return;
        };
        let root = Path::root();
        for (key, value) in entries {
            let p = root.key(key);
            self.mark(&p, value);
            keys.push(key.clone());
            match key.as_str() {
                "name" => robot.name = self.string(value, &p),
                "convention" => robot.convention = self.string(value, &p),
                "scalar" => robot.scalar = self.string(value, &p),
                "params" => robot.params = self.entries(value, &p).unwrap_or_default(),
                "joints" => robot.joints = self.joints(value, &p),
                "task" => match value.get_ref() {
                    Node::Array(items) => {
                        robot.task = Some(
                            items
                                .iter()
                                .enumerate()
                                .filter_map(|(i, it)| self.value(it, &p.index(i)))
                                .collect(),
                        )
                    }
                    other => self.err(
                        p,
                        format!(
                            "`task` must be a list of rows such as [\"x\", \"y\", \"rz\"], found {}",
                            other.kind()
                        ),
                    ),
                },
                "base" => robot.base = self.entries(value, &p),
                "tool" => robot.tool = self.entries(value, &p),
                "budget" => *budget = self.budget(value, &p),
                "ik_free" => {}
                _ => self.err(p, input::unknown_top_level_key(key)),
            }
        }
    }

    /// A file that names a URDF: `urdf`, `base`, `tip`, `snap`, named lengths and the
    /// shared options.
    fn urdf_root(
        &mut self,
        node: &Spanned<Node>,
        budget: &mut Option<Budget>,
        keys: &mut Vec<String>,
    ) -> Option<(String, UrdfOptions)> {
        let Node::Table(entries) = node.get_ref() else {
            return None;
        };
        let mut o = UrdfOptions::default();
        let mut file = None;
        for (key, value) in entries {
            let p = Path::root().key(key);
            self.mark(&p, value);
            keys.push(key.clone());
            match key.as_str() {
                "urdf" => file = self.string(value, &p),
                "name" => o.name = self.string(value, &p),
                "base" => o.base = self.string(value, &p),
                "tip" => o.tip = self.string(value, &p),
                "scalar" => o.scalar = self.string(value, &p),
                "snap" => match value.get_ref() {
                    Node::Float(x) => o.snap = Some(*x),
                    Node::Int(i) => o.snap = Some(*i as f64),
                    other => self.err(
                        p,
                        format!(
                            "`snap` is a tolerance in radians / metres, found {}",
                            other.kind()
                        ),
                    ),
                },
                "params" => match value.get_ref() {
                    Node::Str(s) if s == "auto" => o.symbolic = true,
                    _ => o.params = self.entries(value, &p).unwrap_or_default(),
                },
                "task" => {
                    o.task = self.value(value, &p).map(|v| match v {
                        RawValue::List(items) => items,
                        other => vec![other],
                    })
                }
                "budget" => *budget = self.budget(value, &p),
                "ik_free" => {}
                "convention" | "joints" | "tool" => self.err(
                    p,
                    format!(
                        "`{key}` belongs to a DH table; a file with `urdf` takes {}",
                        URDF_KEYS.join(", ")
                    ),
                ),
                _ => self.err(
                    p,
                    format!(
                        "unknown key `{key}`: a file with `urdf` takes {}",
                        URDF_KEYS.join(", ")
                    ),
                ),
            }
        }
        file.map(|f| (f, o))
    }

    fn string(&mut self, node: &Spanned<Node>, path: &Path) -> Option<String> {
        match node.get_ref() {
            Node::Str(s) => Some(s.clone()),
            other => {
                self.err(
                    path.clone(),
                    format!("expected a string, found {}", other.kind()),
                );
                None
            }
        }
    }

    /// A number, parameter name, expression string, or a list of those.
    fn value(&mut self, node: &Spanned<Node>, path: &Path) -> Option<RawValue> {
        self.mark(path, node);
        match node.get_ref() {
            Node::Str(s) => Some(RawValue::Text(s.clone())),
            // i64 → f64 is exact below 2⁵³, far beyond any DH entry.
            Node::Int(i) => Some(RawValue::Number(*i as f64)),
            Node::Float(x) => Some(RawValue::Number(*x)),
            Node::Array(items) => {
                let mut out = Vec::new();
                for (i, it) in items.iter().enumerate() {
                    out.push(self.value(it, &path.index(i))?);
                }
                Some(RawValue::List(out))
            }
            other => {
                self.err(
                    path.clone(),
                    format!(
                        "expected a number, a parameter name or an expression string, found {}",
                        other.kind()
                    ),
                );
                None
            }
        }
    }

    /// A table of `key = value` entries (params, base, tool).
    fn entries(&mut self, node: &Spanned<Node>, path: &Path) -> Option<Vec<(String, RawValue)>> {
        let Node::Table(entries) = node.get_ref() else {
            self.err(
                path.clone(),
                format!("expected a table, found {}", node.get_ref().kind()),
            );
            return None;
        };
        Some(
            entries
                .iter()
                .filter_map(|(k, v)| Some((k.clone(), self.value(v, &path.key(k))?)))
                .collect(),
        )
    }

    fn joints(&mut self, node: &Spanned<Node>, path: &Path) -> Vec<RawJoint> {
        let Node::Array(rows) = node.get_ref() else {
            self.err(
                path.clone(),
                format!(
                    "`joints` must be a list of tables ([[joints]] sections), found {}",
                    node.get_ref().kind()
                ),
            );
            return Vec::new();
        };
        let mut out = Vec::new();
        for (i, row) in rows.iter().enumerate() {
            let p = path.index(i);
            self.mark(&p, row);
            let Node::Table(entries) = row.get_ref() else {
                self.err(
                    p,
                    format!("a joint must be a table, found {}", row.get_ref().kind()),
                );
                continue;
            };
            let mut joint = RawJoint::default();
            for (key, value) in entries {
                let kp = p.key(key);
                if key == "type" {
                    self.mark(&kp, value);
                    joint.kind = self.string(value, &kp);
                } else if let (Node::Bool(b), "flip") = (value.get_ref(), key.as_str()) {
                    self.mark(&kp, value);
                    joint.fields.push((key.clone(), RawValue::Bool(*b)));
                } else if let Some(v) = self.value(value, &kp) {
                    joint.fields.push((key.clone(), v));
                }
            }
            out.push(joint);
        }
        out
    }

    /// `ik_free`, read from the root table (either kind of file), if given.
    fn ik_free(&mut self, root: &Spanned<Node>) -> Option<usize> {
        let Node::Table(entries) = root.get_ref() else {
            return None;
        };
        let (_, value) = entries.iter().find(|(k, _)| k == "ik_free")?;
        let n = match value.get_ref() {
            Node::Int(i) => Some(i128::from(*i)),
            _ => None,
        };
        match input::ik_free_value(n) {
            Ok(k) => Some(k),
            Err(message) => {
                self.err(Path::root().key("ik_free"), message);
                None
            }
        }
    }

    fn budget(&mut self, node: &Spanned<Node>, path: &Path) -> Option<Budget> {
        let Node::Table(entries) = node.get_ref() else {
            self.err(
                path.clone(),
                format!("expected a table, found {}", node.get_ref().kind()),
            );
            return None;
        };
        let mut budget = Budget::default();
        for (key, value) in entries {
            let p = path.key(key);
            self.mark(&p, value);
            let n = match value.get_ref() {
                Node::Int(i) => Some(i128::from(*i)),
                _ => None,
            };
            if let Err(message) = input::set_budget(&mut budget, key, n) {
                self.err(p, message);
            }
        }
        Some(budget)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::dh::Convention;
    use crate::model::robot::{JointKind, TaskRow};

    const GOOD: &str = r#"
name = "planar RR"
convention = "standard"
task = ["x", "y"]
scalar = "f32"

[params]
L1 = 1.0
L2 = 0.5

[[joints]]
type = "revolute"
a = "L1"
alpha = 0
d = 0
limits = ["-pi", "pi"]

[[joints]]
type = "prismatic"
a = "L2"
alpha = "pi/2"
theta = 0
offset = 0.1

[tool]
xyz = [0, 0, 0.1]
rpy = [0, 0, "pi/2"]

[budget]
nodes = 2000
time_ms = 300
"#;

    fn errors(src: &str) -> Vec<String> {
        load_str(src, "r.toml")
            .unwrap_err()
            .errors
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    #[test]
    fn loads_a_good_file() {
        let (robot, options) = load_str(GOOD, "good.toml").unwrap();
        assert_eq!(robot.name, "planar RR");
        assert_eq!(robot.convention, Convention::Standard);
        assert_eq!(robot.dof(), 2);
        assert_eq!(robot.joints[1].kind, JointKind::Prismatic);
        assert_eq!(robot.param_value("L2"), 0.5);
        assert_eq!(robot.task, Some(vec![TaskRow::X, TaskRow::Y]));
        assert_eq!(robot.scalar, crate::model::robot::Scalar::F32);
        let lim = robot.joints[0].limits.unwrap();
        assert_eq!(lim, [-core::f64::consts::PI, core::f64::consts::PI]);
        assert!(robot.tool.is_some() && robot.base.is_none());
        assert_eq!(options.budget.nodes, 2000);
        assert_eq!(options.budget.time_ms, 300);
        assert_eq!(options.budget.iterations, Budget::default().iterations);
    }

    #[test]
    fn syntax_errors_give_the_parsers_line() {
        let got = errors("name = \"x\"\nconvention = \"standard\"\n[[joints]\ntype = 1\n");
        assert_eq!(got.len(), 1);
        assert!(got[0].starts_with("r.toml:3: "), "{got:?}");
        let got = errors("name = \"x\"\n[params]\na = 1\na = 2\n");
        assert!(got[0].starts_with("r.toml:4: "), "{got:?}");
        assert!(got[0].contains("duplicate key"), "{got:?}");
    }

    #[test]
    fn validation_errors_give_the_entrys_line() {
        let src = "convention = \"standard\"\n[params]\nL1 = 1\n[[joints]]\ntype = \"revolute\"\na = \"L3\"\nalpha = 0\nd = 0\n[[joints]]\ntype = \"revolute\"\na = 0\nd = 0\n";
        assert_eq!(
            errors(src),
            vec![
                "r.toml:6: joints[0].a: undefined parameter `L3`",
                "r.toml:9: joints[1]: missing column `alpha`",
            ]
        );
    }

    #[test]
    fn root_errors_have_no_path() {
        let src = "[[joints]]\ntype = \"revolute\"\na = 0\nalpha = 0\nd = 0\n";
        assert_eq!(
            errors(src),
            vec!["r.toml:1: missing `convention`: say `standard` (Rz Tz Tx Rx) or `modified` (Rx Tx Rz Tz)"]
        );
    }

    #[test]
    fn shape_errors() {
        let src = "convention = \"standard\"\ncolour = \"red\"\ntask = \"x\"\njoints = 3\n[budget]\nnodes = -1\ndepth = 3\n[base]\nxyz = [0, true, 0]\n";
        assert_eq!(
            errors(src),
            vec![
                "r.toml:2: colour: unknown key `colour`: expected name, convention, params, joints, task, base, tool, scalar, budget or ik_free",
                "r.toml:3: task: `task` must be a list of rows such as [\"x\", \"y\", \"rz\"], found a string",
                "r.toml:4: joints: `joints` must be a list of tables ([[joints]] sections), found a number",
                "r.toml:6: budget.nodes: `nodes` must be a positive integer (at most 4294967295)",
                "r.toml:7: budget.depth: unknown budget entry `depth`: expected nodes, iterations or time_ms",
                "r.toml:9: base.xyz[1]: expected a number, a parameter name or an expression string, found a boolean",
            ]
        );
    }

    #[test]
    fn inline_tables_and_non_finite_numbers() {
        let src = "convention = \"modified\"\njoints = [\n  { type = \"revolute\", a = 0, alpha = 0, d = 0 },\n  { type = \"revolute\", a = inf, alpha = 0, d = 0 },\n]\n";
        assert_eq!(
            errors(src),
            vec!["r.toml:4: joints[1].a: `inf` is not a finite number"]
        );
    }

    #[test]
    fn dates_are_refused_not_panicked_on() {
        let src = "convention = \"standard\"\nname = 1979-05-27\n";
        assert_eq!(
            errors(src),
            vec![
                "r.toml:1: joints: the DH table has no joints",
                "r.toml:2: name: expected a string, found a date",
            ]
        );
    }

    #[test]
    fn missing_file() {
        let err = load_file(FsPath::new("/nonexistent/robot.toml")).unwrap_err();
        assert!(err
            .to_string()
            .starts_with("/nonexistent/robot.toml: cannot read the file"));
    }
}
