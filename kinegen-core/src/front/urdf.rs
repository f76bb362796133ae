//! URDF files: the links and joints of a robot, the tree they form, and the path from a
//! base link to a tip link — with errors that name the line.
//!
//! What is read, as the ROS URDF specification and urdfdom define it: the `<robot>`
//! element's `<link name>` and `<joint name type>` children; each joint's `<parent
//! link>`, `<child link>`, `<origin xyz rpy>` (identity when missing), `<axis xyz>`
//! (`1 0 0` when missing), `<limit lower upper>` and `<mimic joint>`. Everything else —
//! `<gazebo>`, `<transmission>`, `<ros2_control>`, `<sensor>`, materials, visuals,
//! collisions, inertia, comments, elements of other XML namespaces — is not kinematics
//! and is skipped. Numbers are kept exactly as the decimals they are written as
//! (`1.5708` is 15708/10⁴); snapping them to exact angles is the chain builder's job
//! ([`crate::chain::urdf`]).
//!
//! A file with xacro left in (`xacro:` elements, `${…}` or `$(…)` substitutions) is
//! refused with a message to run `xacro` first.
//!
//! ```
//! use kinegen_core::front::urdf::Urdf;
//! let src = r#"<robot name="arm">
//!   <link name="base"/><link name="upper"/>
//!   <joint name="shoulder" type="revolute">
//!     <parent link="base"/><child link="upper"/>
//!     <origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>
//!     <limit lower="-3.14" upper="3.14" effort="1" velocity="1"/>
//!   </joint>
//! </robot>"#;
//! let urdf = Urdf::parse(src, "arm.urdf").unwrap();
//! let (base, tip, joints) = urdf.path(None, None).unwrap();
//! assert_eq!((base.as_str(), tip.as_str(), joints.len()), ("base", "upper", 1));
//! let err = Urdf::parse("<robot name=\"x\"><link name=\"a\"/>\n<joint/></robot>", "x.urdf");
//! assert_eq!(err.unwrap_err().to_string(), "x.urdf:2: a <joint> needs a `name`");
//! ```

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path as FsPath;

use roxmltree::{Document, Node};

use crate::front::located::{LoadError, LocatedError};
use crate::model::raw::Path;
use crate::model::value::{parse_decimal, rat_to_f64, Rat};

/// The XML namespace of xacro macros.
const XACRO_NS: &str = "http://www.ros.org/wiki/xacro";

/// A number as written in the file, and its exact value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Number {
    /// The exact decimal.
    pub value: Rat,
    /// The text as written (`1.5708`).
    pub text: String,
}

impl Number {
    /// Exactly zero.
    pub fn zero() -> Self {
        Number {
            value: Rat::from_integer(0.into()),
            text: "0".into(),
        }
    }

    /// The value as `f64`.
    pub fn to_f64(&self) -> f64 {
        rat_to_f64(&self.value)
    }
}

/// A joint's `type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointType {
    /// Turns about its axis, within limits.
    Revolute,
    /// Turns about its axis without limits.
    Continuous,
    /// Slides along its axis.
    Prismatic,
    /// Does not move: a constant transform.
    Fixed,
    /// Six degrees of freedom (not supported on a chain).
    Floating,
    /// Moves in a plane (not supported on a chain).
    Planar,
}

impl JointType {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "revolute" => JointType::Revolute,
            "continuous" => JointType::Continuous,
            "prismatic" => JointType::Prismatic,
            "fixed" => JointType::Fixed,
            "floating" => JointType::Floating,
            "planar" => JointType::Planar,
            _ => return None,
        })
    }

    /// The name in a URDF file.
    pub fn name(self) -> &'static str {
        match self {
            JointType::Revolute => "revolute",
            JointType::Continuous => "continuous",
            JointType::Prismatic => "prismatic",
            JointType::Fixed => "fixed",
            JointType::Floating => "floating",
            JointType::Planar => "planar",
        }
    }
}

/// One `<joint>`.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Its name.
    pub name: String,
    /// Its type.
    pub kind: JointType,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// `<origin xyz>` (zeros when missing).
    pub xyz: [Number; 3],
    /// `<origin rpy>`: roll, pitch, yaw (zeros when missing).
    pub rpy: [Number; 3],
    /// `<axis xyz>` as written (`1 0 0` when missing; not normalised; never zero for a
    /// moving joint).
    pub axis: [Number; 3],
    /// `<limit lower upper>` for revolute and prismatic joints that have one.
    pub limits: Option<[f64; 2]>,
    /// `<mimic joint>`: the joint this one follows.
    pub mimic: Option<String>,
    /// Line of the `<joint>` element.
    pub line: usize,
    /// Line of its `<origin>` (of the joint when missing).
    pub origin_line: usize,
    /// Line of its `<axis>` (of the joint when missing).
    pub axis_line: usize,
}

/// A URDF robot: its links and joints, in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct Urdf {
    /// The file as the user named it.
    pub label: String,
    /// `<robot name>`.
    pub name: String,
    /// Link names with the line of each.
    pub links: Vec<(String, usize)>,
    /// Joints.
    pub joints: Vec<Joint>,
    /// Line of the `<robot>` element.
    pub line: usize,
}

/// Errors of one file, collected in file order.
struct Errors<'a> {
    label: &'a str,
    list: Vec<LocatedError>,
}

impl Errors<'_> {
    fn at(&mut self, line: usize, path: Path, message: impl Into<String>) {
        self.list.push(LocatedError {
            file: self.label.to_string(),
            line,
            path,
            message: message.into(),
        });
    }
}

impl Urdf {
    /// Read a URDF file; messages name the file as `path` is written.
    pub fn load_file(path: &FsPath) -> Result<Urdf, LoadError> {
        let label = path.display().to_string();
        match std::fs::read_to_string(path) {
            Ok(src) => Urdf::parse(&src, &label),
            Err(e) => Err(LoadError::at(
                &label,
                0,
                Path::root(),
                format!("cannot read the file: {e}"),
            )),
        }
    }

    /// Parse URDF text. `label` names the file in messages.
    pub fn parse(src: &str, label: &str) -> Result<Urdf, LoadError> {
        let doc = Document::parse(src).map_err(|e| xml_error(&e, label))?;
        let mut errors = Errors {
            label,
            list: Vec::new(),
        };
        // Line of a node: by binary search in the newlines' offsets (roxmltree's
        // `text_pos_at` counts from the start of the file on every call: quadratic,
        // 0.4 s for a 1 000-link file).
        let newlines: Vec<usize> = src.match_indices('\n').map(|(i, _)| i).collect();
        let line = |n: Node| 1 + newlines.partition_point(|&i| i < n.range().start);
        xacro_left(&doc, &mut errors, &line);
        if !errors.list.is_empty() {
            return Err(LoadError {
                errors: errors.list,
            });
        }
        let root = doc.root_element();
        if root.tag_name().name() != "robot" {
            errors.at(
                line(root),
                Path::root(),
                format!(
                    "not a URDF file: the root element is <{}>, not <robot>",
                    root.tag_name().name()
                ),
            );
            return Err(LoadError {
                errors: errors.list,
            });
        }
        let mut urdf = Urdf {
            label: label.to_string(),
            name: root.attribute("name").unwrap_or("robot").to_string(),
            links: Vec::new(),
            joints: Vec::new(),
            line: line(root),
        };
        for el in root.children().filter(Node::is_element) {
            if el
                .tag_name()
                .namespace()
                .is_some_and(|ns| ns != root_ns(root))
            {
                continue;
            }
            match el.tag_name().name() {
                "link" => match el.attribute("name") {
                    Some(n) => urdf.links.push((n.to_string(), line(el))),
                    None => errors.at(line(el), Path::root(), "a <link> needs a `name`"),
                },
                "joint" => {
                    if let Some(j) = joint(el, &mut errors, &line) {
                        urdf.joints.push(j);
                    }
                }
                _ => {}
            }
        }
        urdf.check_tree(&mut errors);
        if errors.list.is_empty() {
            Ok(urdf)
        } else {
            errors.list.sort_by_key(|e| e.line);
            Err(LoadError {
                errors: errors.list,
            })
        }
    }

    /// Each link's parent joint (the first, where a link has two: an error), looked up
    /// once per step of a walk up the tree. Built for each walk, not kept: a scan of
    /// the joints per step made loading a long chain cubic (2 000 joints: 2.5 s).
    fn parent_joints(&self) -> BTreeMap<&str, &Joint> {
        let mut parents = BTreeMap::new();
        for j in &self.joints {
            parents.entry(j.child.as_str()).or_insert(j);
        }
        parents
    }

    /// Links that are no joint's child.
    pub fn roots(&self) -> Vec<&str> {
        self.roots_of(&self.parent_joints())
    }

    /// [`Urdf::roots`] given [`Urdf::parent_joints`].
    fn roots_of(&self, parents: &BTreeMap<&str, &Joint>) -> Vec<&str> {
        self.links
            .iter()
            .map(|(n, _)| n.as_str())
            .filter(|n| !parents.contains_key(n))
            .collect()
    }

    /// Links that are no joint's parent.
    pub fn leaves(&self) -> Vec<&str> {
        let parent_links: BTreeSet<&str> = self.joints.iter().map(|j| j.parent.as_str()).collect();
        self.links
            .iter()
            .map(|(n, _)| n.as_str())
            .filter(|n| !parent_links.contains(n))
            .collect()
    }

    /// The tree rules: unique names, known links, one parent per link, one root, no
    /// cycle.
    fn check_tree(&self, errors: &mut Errors) {
        let mut seen = BTreeMap::new();
        for (n, line) in &self.links {
            if let Some(first) = seen.insert(n.as_str(), *line) {
                errors.at(
                    *line,
                    Path::root(),
                    format!("link `{n}` is declared twice (first on line {first})"),
                );
            }
        }
        let mut joint_names = BTreeSet::new();
        let mut parent_of: BTreeMap<&str, &Joint> = BTreeMap::new();
        for j in &self.joints {
            let at = Path::root().key(&j.name);
            if !joint_names.insert(j.name.as_str()) {
                errors.at(
                    j.line,
                    at.clone(),
                    format!("joint `{}` is declared twice", j.name),
                );
            }
            for (role, l) in [("parent", &j.parent), ("child", &j.child)] {
                if !seen.contains_key(l.as_str()) {
                    errors.at(
                        j.line,
                        at.clone(),
                        format!("{role} link `{l}` is not declared"),
                    );
                }
            }
            if let Some(other) = parent_of.insert(j.child.as_str(), j) {
                errors.at(
                    j.line,
                    at.clone(),
                    format!(
                        "link `{}` has two parents: joints `{}` (line {}) and `{}`",
                        j.child, other.name, other.line, j.name
                    ),
                );
            }
        }
        if !errors.list.is_empty() {
            return;
        }
        // No link has two parents: `parent_of` is `parent_joints()`.
        let roots = self.roots_of(&parent_of);
        match roots.as_slice() {
            [_] => self.check_cycles(&parent_of, errors),
            [] => self.check_cycles(&parent_of, errors),
            many => errors.at(
                self.line,
                Path::root(),
                format!(
                    "the links form {} trees, a URDF is one: roots {}",
                    many.len(),
                    quoted(many)
                ),
            ),
        }
    }

    /// Every link reaches a root through its `parents` ([`Urdf::parent_joints`]). Each
    /// walk up stops at a link an earlier walk showed to reach one, so every link is
    /// passed once.
    fn check_cycles(&self, parents: &BTreeMap<&str, &Joint>, errors: &mut Errors) {
        let mut rooted: BTreeSet<&str> = BTreeSet::new();
        let mut walk: Vec<&str> = Vec::new();
        for (link, _) in &self.links {
            walk.clear();
            let mut cur = link.as_str();
            while !rooted.contains(cur) {
                let Some(j) = parents.get(cur) else {
                    break;
                };
                walk.push(cur);
                cur = &j.parent;
                if walk.len() > self.joints.len() {
                    errors.at(
                        j.line,
                        Path::root().key(&j.name),
                        format!(
                            "joint `{}` is on a cycle: the links do not form a tree",
                            j.name
                        ),
                    );
                    return;
                }
            }
            rooted.insert(cur);
            rooted.extend(walk.iter().copied());
        }
    }

    /// The chain from `base` to `tip` (defaults: the root link, and the only leaf after a
    /// moving joint — or, with a parallel gripper, the leaf whose moving joints each of
    /// the two or more others has, with prismatic fingers after them): their names and
    /// the joints between them, base to tip (fixed ones included).
    ///
    /// Errors carry the path `base` or `tip` (the option that is wrong) and the line of
    /// the `<robot>` element, or of the link when it exists.
    pub fn path(
        &self,
        base: Option<&str>,
        tip: Option<&str>,
    ) -> Result<(String, String, Vec<&Joint>), LoadError> {
        let parents = self.parent_joints();
        let err = |key: &str, line: usize, msg: String| {
            LoadError::at(&self.label, line, Path::root().key(key), msg)
        };
        let base = match base {
            Some(b) => self.link(b, "base")?.to_string(),
            None => self
                .roots_of(&parents)
                .first()
                .copied()
                .unwrap_or_default()
                .to_string(),
        };
        let tip = match tip {
            Some(t) => self.link(t, "tip")?.to_string(),
            None => {
                let leaves = self.leaves();
                // A leaf hung from the base by fixed joints only (ROS-Industrial's `base`
                // frame beside `base_link`) ends no chain of joints: not a tip to guess.
                let moving: Vec<(&str, Vec<&Joint>)> = leaves
                    .iter()
                    .map(|&l| (l, moving_joints(&parents, &base, l)))
                    .filter(|(_, js)| !js.is_empty())
                    .collect();
                // A parallel gripper's fingers (the Panda's): two or more leaves, each with
                // the moving joints of one other leaf (the hand's TCP) and prismatic ones
                // after them. That leaf ends the arm. (A single leaf beyond, or a revolute
                // joint beyond — a tool past a sensor's frame on the wrist — is no
                // gripper: asked, not guessed.)
                let fingers_of = |js: &[&Joint]| {
                    moving
                        .iter()
                        .filter(|(_, ks)| {
                            ks.len() > js.len()
                                && ks[..js.len()]
                                    .iter()
                                    .zip(js)
                                    .all(|(k, j)| core::ptr::eq(*k, *j))
                                && ks[js.len()..]
                                    .iter()
                                    .all(|k| k.kind == JointType::Prismatic)
                        })
                        .count()
                };
                // Every other leaf a finger, and two of them at least.
                let arm: Vec<&str> = moving
                    .iter()
                    .filter(|(_, js)| moving.len() >= 3 && fingers_of(js) + 1 == moving.len())
                    .map(|(l, _)| *l)
                    .collect();
                let moving: Vec<&str> = moving.iter().map(|(l, _)| *l).collect();
                match (leaves.as_slice(), moving.as_slice(), arm.as_slice()) {
                    ([one], _, _) | (_, [one], _) | (_, _, [one]) => one.to_string(),
                    (all, many, _) if !many.is_empty() && many.len() < all.len() => {
                        return Err(err(
                            "tip",
                            self.line,
                            format!(
                                "the tree has {} leaves, {} of them after a moving joint; \
                                 name the tip link: {}",
                                all.len(),
                                many.len(),
                                quoted(many)
                            ),
                        ))
                    }
                    (all, _, _) => {
                        return Err(err(
                            "tip",
                            self.line,
                            format!(
                                "the tree has {} leaves, name the tip link: {}",
                                all.len(),
                                quoted(all)
                            ),
                        ))
                    }
                }
            }
        };
        let mut joints = Vec::new();
        let mut cur = tip.as_str();
        while cur != base {
            match parents.get(cur).copied() {
                Some(j) => {
                    joints.push(j);
                    cur = &j.parent;
                }
                None => {
                    let line = self.link_line(&tip);
                    return Err(err(
                        "tip",
                        line,
                        format!("tip link `{tip}` is not below base link `{base}`"),
                    ));
                }
            }
        }
        joints.reverse();
        Ok((base, tip, joints))
    }

    fn link_line(&self, name: &str) -> usize {
        self.links
            .iter()
            .find(|(n, _)| n == name)
            .map_or(self.line, |(_, l)| *l)
    }

    fn link<'a>(&self, name: &'a str, role: &str) -> Result<&'a str, LoadError> {
        if self.links.iter().any(|(n, _)| n == name) {
            return Ok(name);
        }
        let names: Vec<&str> = self.links.iter().map(|(n, _)| n.as_str()).collect();
        Err(LoadError::at(
            &self.label,
            self.line,
            Path::root().key(role),
            format!(
                "no link `{name}` (the {role}): the links are {}",
                quoted(&names)
            ),
        ))
    }
}

/// The joints that are not fixed between `base` and `leaf`, base to leaf (none when
/// `leaf` is not below `base`), walking up `parents` ([`Urdf::parent_joints`]).
fn moving_joints<'a>(
    parents: &BTreeMap<&'a str, &'a Joint>,
    base: &str,
    leaf: &'a str,
) -> Vec<&'a Joint> {
    let mut cur = leaf;
    let mut moving = Vec::new();
    // The tree was checked (one parent per link, no cycle): the walk ends at the root.
    while cur != base {
        match parents.get(cur).copied() {
            Some(j) => {
                if j.kind != JointType::Fixed {
                    moving.push(j);
                }
                cur = &j.parent;
            }
            None => return Vec::new(),
        }
    }
    moving.reverse();
    moving
}

/// `` `a`, `b` and `c` ``.
fn quoted(names: &[&str]) -> String {
    let q: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    crate::words::and_list(&q)
}

/// The namespace of the `<robot>` element (elements in it are URDF's).
fn root_ns<'a>(root: Node<'a, '_>) -> &'a str {
    root.tag_name().namespace().unwrap_or("")
}

/// A file that is not XML, with the parser's line.
fn xml_error(e: &roxmltree::Error, label: &str) -> LoadError {
    let line = e.pos().row as usize;
    let msg = match e {
        roxmltree::Error::UnknownNamespace(prefix, _) if prefix == "xacro" => {
            return LoadError::at(label, line, Path::root(), XACRO_HINT)
        }
        e => format!("not an XML file: {e}"),
    };
    LoadError::at(label, line, Path::root(), msg)
}

const XACRO_HINT: &str =
    "this is an unexpanded xacro file: run `xacro FILE.urdf.xacro > FILE.urdf` first and give kinegen the output";

/// xacro elements or substitutions anywhere in the file.
fn xacro_left(doc: &Document, errors: &mut Errors, line: &dyn Fn(Node) -> usize) {
    for n in doc.descendants().filter(Node::is_element) {
        let xacro_el = n.tag_name().namespace() == Some(XACRO_NS);
        let subst = n
            .attributes()
            .any(|a| a.value().contains("${") || a.value().contains("$("));
        if xacro_el || subst {
            errors.at(line(n), Path::root(), XACRO_HINT);
            return;
        }
    }
}

/// The first child element named `name`.
fn child<'a, 'i>(el: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    el.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// One `<joint>` element, or `None` after reporting why not.
fn joint(el: Node, errors: &mut Errors, line: &dyn Fn(Node) -> usize) -> Option<Joint> {
    let at = line(el);
    let Some(name) = el.attribute("name") else {
        errors.at(at, Path::root(), "a <joint> needs a `name`");
        return None;
    };
    let path = Path::root().key(name);
    let before = errors.list.len();
    let kind = match el.attribute("type") {
        Some(t) => JointType::parse(t).or_else(|| {
            errors.at(at, path.clone(), format!(
                "joint `{name}` has unknown type `{t}`: expected revolute, continuous, prismatic, fixed, floating or planar"
            ));
            None
        }),
        None => {
            errors.at(at, path.clone(), format!("joint `{name}` has no `type`"));
            None
        }
    };
    let mut link_of = |role: &str| match child(el, role).and_then(|c| c.attribute("link")) {
        Some(l) => l.to_string(),
        None => {
            errors.at(
                at,
                path.clone(),
                format!("joint `{name}` has no <{role} link=\"…\"/>"),
            );
            String::new()
        }
    };
    let parent = link_of("parent");
    let child_link = link_of("child");
    let origin = child(el, "origin");
    let origin_line = origin.map_or(at, line);
    let mut vector =
        |node: Option<Node>, attr: &str, key: &str, default: [i64; 3]| -> [Number; 3] {
            let line = node.map_or(at, line);
            match node.and_then(|n| n.attribute(attr)) {
                Some(text) => numbers(text, line, &path.key(key), errors),
                None => default.map(|d| Number {
                    value: Rat::from_integer(d.into()),
                    text: d.to_string(),
                }),
            }
        };
    let xyz = vector(origin, "xyz", "xyz", [0, 0, 0]);
    let rpy = vector(origin, "rpy", "rpy", [0, 0, 0]);
    let axis_el = child(el, "axis");
    let axis = vector(axis_el, "xyz", "axis", [1, 0, 0]);
    let axis_line = axis_el.map_or(at, line);
    let moving = matches!(
        kind,
        Some(JointType::Revolute | JointType::Continuous | JointType::Prismatic)
    );
    let zero = axis.iter().all(|n| n.value == Rat::from_integer(0.into()));
    if moving && zero && errors.list.len() == before {
        errors.at(
            axis_line,
            path.key("axis"),
            format!("joint `{name}` has a zero axis"),
        );
    }
    let limits = match kind {
        Some(JointType::Revolute | JointType::Prismatic) => {
            child(el, "limit").and_then(|l| limits(l, line(l), &path, errors))
        }
        _ => None,
    };
    let mimic = child(el, "mimic").and_then(|m| m.attribute("joint").map(str::to_string));
    if errors.list.len() > before {
        return None;
    }
    Some(Joint {
        name: name.to_string(),
        kind: kind?,
        parent,
        child: child_link,
        xyz,
        rpy,
        axis,
        limits,
        mimic,
        line: at,
        origin_line,
        axis_line,
    })
}

/// Three numbers separated by whitespace (`"0 0 0.089159"`).
fn numbers(text: &str, line: usize, path: &Path, errors: &mut Errors) -> [Number; 3] {
    let words: Vec<&str> = text.split_whitespace().collect();
    let mut out = [Number::zero(), Number::zero(), Number::zero()];
    if words.len() != 3 {
        errors.at(
            line,
            path.clone(),
            format!("needs 3 numbers, found {}: `{}`", words.len(), text.trim()),
        );
        return out;
    }
    for (slot, w) in out.iter_mut().zip(&words) {
        match parse_decimal(w) {
            Ok(value) => {
                *slot = Number {
                    value,
                    text: w.to_string(),
                }
            }
            Err(_) => errors.at(line, path.clone(), format!("`{w}` is not a number")),
        }
    }
    out
}

/// `<limit lower upper>`: both default to 0 as in the specification.
fn limits(el: Node, line: usize, path: &Path, errors: &mut Errors) -> Option<[f64; 2]> {
    let mut get = |attr: &str| match el.attribute(attr) {
        None => Some(0.0),
        Some(t) => match parse_decimal(t) {
            Ok(v) => Some(rat_to_f64(&v)),
            Err(_) => {
                errors.at(
                    line,
                    path.key("limit"),
                    format!("`{}` is not a number", t.trim()),
                );
                None
            }
        },
    };
    let (lo, hi) = (get("lower")?, get("upper")?);
    if lo > hi {
        errors.at(
            line,
            path.key("limit"),
            format!("limit lower {lo} is above upper {hi}"),
        );
        return None;
    }
    Some([lo, hi])
}
