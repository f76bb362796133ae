//! The closed-form IK methods of a generated type: `ik` (or `ik_with` for a 7-joint arm),
//! `ik_near`, `ik_seeded`, `ik_geometry`, the constants `IK_FAMILY`, `IK_STEPS` and
//! `REVOLUTE`, and what the runtime's `finish` step needs (`Check`).
//!
//! An f32 robot gets the same methods with f32 poses and joint values, solved in f64: the
//! pose, the free joints and the limits are widened, `ik_geometry` is f64 code reading the
//! widened parameters, the family solver and `finish` run in f64 (the `Check` measures
//! the residual on the geometry's product of exponentials and the singular factors in
//! f64), and the solutions are rounded once (`IkSolutions::to_f32`).

use crate::algebra::graph::Id;
use crate::chain::Chain;
use crate::emit::code::{Body, Coder};
use crate::emit::item::{Const, Item, Method, MethodBody};
use crate::kinematics::ik::family::{Family, Position};
use crate::kinematics::ik::IkModel;
use crate::model::robot::{JointKind, Scalar, TaskRow};

/// How the `Check` impl flags the singular factors that vanish.
#[derive(Clone, Debug)]
pub enum SingularCheck {
    /// No closed-form determinant: no bits.
    None,
    /// `vanishing(&self.singular_factors(q))` (an f64 robot).
    Factors,
    /// The singular factors as f64 code (an f32 robot): its `lets`, then the factors.
    Widened(Body),
}

/// The `impl ::kinegen::ik::solutions::Check<N>` the generated type gets.
#[derive(Clone, Debug)]
pub struct CheckImpl {
    /// Task rows the residual compares (`None`: the whole pose).
    pub task_rows: Option<Vec<usize>>,
    /// How singular branches are flagged.
    pub singular: SingularCheck,
    /// The joint a 7-joint arm's closed form locks.
    pub locked: Option<usize>,
    /// The robot's scalar: an f32 robot's residual is measured on `ik_geometry().fk`
    /// in f64 instead of its f32 `fk` (an f64 robot's too with kinegen's `small-ik`).
    pub scalar: Scalar,
}

/// The paragraph an f32 robot's `ik` doc adds.
const SOLVED_IN_F64: &str = "Solved in f64, returned in f32: the pose is widened, the \
     geometry is evaluated in f64 from the (widened) parameters ([`Self::ik_geometry`]), and the \
     subproblems, the exactness check (residual on the geometry's product of exponentials, \
     `EXACT_TOLERANCE` 1e-10) and the singular factors run in f64; the joint values are rounded \
     to f32 once at the end. In f32 the double-root and on-axis tests would fail (a singular \
     pose's double root splits by ~1e-3 rad) and no branch could be checked exact (f32 rounding \
     is ~1e-7). The f32 `fk` of a solution meets the pose to f32 rounding.";

/// The IK items and the `Check` impl for `chain`; `singular` says how `Check` flags
/// singular factors.
pub fn items(chain: &Chain, model: &IkModel, singular: SingularCheck) -> (Vec<Item>, CheckImpl) {
    let n = chain.dof();
    let plan = &model.plan;
    let k = plan.max_solutions;
    let f = scalar_name(chain.scalar);
    let ty = match chain.scalar {
        Scalar::F64 => format!("::kinegen::ik::IkSolutions<{n}, {k}>"),
        Scalar::F32 => format!("::kinegen::ik::IkSolutions<{n}, {k}, f32>"),
    };
    let pose = format!("pose: &[[{f}; 4]; 4]");
    let pose = pose.as_str();
    let mut items = Vec::new();
    let steps: Vec<String> = plan
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| format!("{}. {s}", i + 1))
        .collect();
    // A robot without a closed-form determinant has no `SINGULARITIES` to name.
    let singular_doc = match singular {
        SingularCheck::None => "singular (a subproblem or a double root met a singularity)",
        _ => "singular (which entries of `SINGULARITIES` vanish)",
    };
    let derivation = format!(
        "Family: **{}** — decided exactly from the joint axes at `q = 0`.\n\n```text\n{}\n```\n\n\
         Each solution is flagged exact or least squares (unreachable pose: the nearest, with its \
         residual), {singular_doc}, and within `LIMITS`; \
         revolute joints are wrapped by whole turns into the limits where that helps. No \
         allocation, no panic: a non-finite pose gives no solutions.{}",
        plan.name,
        steps.join("\n"),
        match chain.scalar {
            Scalar::F64 => String::new(),
            Scalar::F32 => format!("\n\n{SOLVED_IN_F64}"),
        }
    );
    let custom =
        |args: String, lets: Vec<String>, result: String| MethodBody::Custom { args, lets, result };
    match plan.locked {
        None => {
            items.push(Item::Method(Method {
                doc: format!("Inverse kinematics in closed form: every solution of `pose` (at most {k}).\n\n{derivation}"),
                name: "ik",
                rates: false,
                ret: ty.clone(),
                body: custom(pose.into(), vec![], format!("self.ik_seeded(pose, &[0.0; {n}])")),
            }));
            items.push(Item::Method(Method {
                doc: "The exact solution of `pose` nearest to `q_current` (whole turns chosen nearest \
                      to it): the rule for a Cartesian motion. At a singular pose the joints the pose \
                      leaves free keep their values from `q_current`, so the answer is continuous. \
                      `None` when `pose` is out of reach."
                    .into(),
                name: "ik_near",
                rates: false,
                ret: format!("::core::option::Option<[{f}; {n}]>"),
                body: custom(
                    format!("{pose}, q_current: &[{f}; {n}]"),
                    vec![],
                    "self.ik_seeded(pose, q_current).nearest(q_current, &Self::REVOLUTE, &Self::LIMITS)".into(),
                ),
            }));
            items.push(Item::Method(seeded(chain, model, &ty, None)));
        }
        Some(locked) => {
            items.push(Item::Method(Method {
                doc: format!(
                    "Inverse kinematics in closed form with joint {} locked at `q_locked` (the \
                     redundancy parameter): every solution of `pose` (at most {k}).\n\n{derivation}",
                    locked + 1
                ),
                name: "ik_with",
                rates: false,
                ret: ty.clone(),
                body: custom(
                    format!("{pose}, q_locked: {f}"),
                    vec![],
                    format!("self.ik_seeded(pose, q_locked, &[0.0; {n}])"),
                ),
            }));
            items.push(Item::Method(Method {
                doc: format!(
                    "The exact solution of `pose` nearest to `q_current`, with joint {} kept at its \
                     current value (see [`Self::ik_with`]); `None` when `pose` is out of reach.",
                    locked + 1
                ),
                name: "ik_near",
                rates: false,
                ret: format!("::core::option::Option<[{f}; {n}]>"),
                body: custom(
                    format!("{pose}, q_current: &[{f}; {n}]"),
                    vec![],
                    format!(
                        "self.ik_seeded(pose, q_current[{locked}], q_current).nearest(q_current, &Self::REVOLUTE, &Self::LIMITS)"
                    ),
                ),
            }));
            items.push(Item::Method(seeded(chain, model, &ty, Some(locked))));
            if let Some(steps) = &plan.arm_angle {
                items.extend(arm_angle_items(n, steps, chain.scalar));
            }
        }
    }
    items.push(Item::Method(geometry(chain, model)));
    if let Some(ids) = &model.reversed_ids {
        items.push(Item::Method(reversed_geometry(chain, model, ids)));
    }
    items.push(Item::Const(Const {
        doc: "Which joints are revolute (their values wrap by whole turns).".into(),
        name: "REVOLUTE",
        ty: format!("[bool; {n}]"),
        value: format!("[{}]", joints_are(chain, JointKind::Revolute)),
    }));
    items.push(Item::Const(Const {
        doc: "The closed-form IK family, decided exactly at expansion time.".into(),
        name: "IK_FAMILY",
        ty: "&'static str".into(),
        value: format!("{:?}", plan.name),
    }));
    if let Some(k) = plan.locked {
        let others: Vec<String> = plan
            .lockable
            .iter()
            .filter(|&&i| i != k)
            .map(|i| (i + 1).to_string())
            .collect();
        let also = if others.is_empty() {
            "No other joint's locking leaves a closed-form family.".to_string()
        } else {
            format!(
                "Locking joint{} {} would also leave a closed-form family (choose with `ik_free`).",
                if others.len() == 1 { "" } else { "s" },
                others.join(", ")
            )
        };
        items.push(Item::Const(Const {
            doc: format!(
                "The joint (1-based, as in the table) the closed-form IK leaves free: \
                 [`Self::ik_with`] takes its value. {also}"
            ),
            name: "IK_FREE",
            ty: "usize".into(),
            value: format!("{}", k + 1),
        }));
    }
    let steps: Vec<String> = plan.steps.iter().map(|s| format!("{s:?}")).collect();
    items.push(Item::Const(Const {
        doc: "The IK derivation: which subproblem gives which joint, in order.".into(),
        name: "IK_STEPS",
        ty: "&'static [&'static str]".into(),
        value: format!("&[{}]", steps.join(", ")),
    }));
    let task_rows = match &plan.family {
        Family::Planar { .. } | Family::Position(_) | Family::CartesianYaw { .. } => chain
            .task
            .as_ref()
            .map(|t| t.iter().map(|r| TaskRow::index(*r)).collect()),
        _ => None,
    };
    (
        items,
        CheckImpl {
            task_rows,
            singular,
            locked: plan.locked,
            scalar: chain.scalar,
        },
    )
}

/// An S-R-S arm's solutions by arm angle: `ik_arm_angle`, `arm_angle`,
/// `arm_angle_intervals`. An f32 robot's take and give f32 (solved in f64 inside, as its
/// `ik` is); its intervals stay f64 radians (their ends are exact crossings).
fn arm_angle_items(n: usize, steps: &[String], scalar: Scalar) -> Vec<Item> {
    let steps: Vec<String> = steps
        .iter()
        .enumerate()
        .map(|(i, s)| format!("{}. {s}", i + 1))
        .collect();
    let custom = |args: &str, lets: Vec<String>, result: String| MethodBody::Custom {
        args: args.into(),
        lets,
        result,
    };
    let f = scalar_name(scalar);
    // The f32 robot's inputs widened, its pose orthonormalized, its limits in f64.
    let widen: Vec<String> = widened_pose(scalar).map(String::from).into_iter().collect();
    let target = target_line(scalar);
    let (limits, to_f32) = match scalar {
        Scalar::F64 => ("&Self::LIMITS", ""),
        Scalar::F32 => ("&Self::LIMITS.map(|l| l.map(f64::from))", ".to_f32()"),
    };
    let mut ik_lets = widen.clone();
    if scalar == Scalar::F32 {
        ik_lets.push("let psi = f64::from(psi);".into());
    }
    ik_lets.extend([
        target.to_string(),
        "if !target.is_finite() || !psi.is_finite() { return ::kinegen::ik::IkSolutions::empty(); }".into(),
        "let g = self.ik_geometry();".into(),
        "let mut candidates = ::kinegen::ik::solutions::Candidates::default();".into(),
        format!("::kinegen::ik::families::srs_arm_angle(&g, &target, psi, ::kinegen::ik::families::WristPair::HalfTurn, &[0.0; {n}], &mut candidates);"),
    ]);
    let mut interval_lets = widen;
    interval_lets.push(target.to_string());
    let (q_value, angle_out) = match scalar {
        Scalar::F64 => ("q", ""),
        Scalar::F32 => ("&q.map(f64::from)", ".map(|psi| psi as f32)"),
    };
    vec![
        Item::Method(Method {
            doc: format!(
                "Every solution of `pose` whose **arm angle** is `psi` (radians): one per global \
                 configuration (the signs of q2, q4, q6), at most 8 — the S-R-S arm's self-motion \
                 in closed form. Flagged as [`Self::ik_with`]'s are; a singular parametrisation \
                 (the shoulder–wrist line along axis 1, or the arm stretched) is flagged singular.\n\n\
                 ```text\n{}\n```",
                steps.join("\n")
            ),
            name: "ik_arm_angle",
            rates: false,
            ret: if scalar == Scalar::F32 {
                format!("::kinegen::ik::IkSolutions<{n}, 8, f32>")
            } else {
                format!("::kinegen::ik::IkSolutions<{n}, 8>")
            },
            body: custom(
                &format!("pose: &[[{f}; 4]; 4], psi: {f}"),
                ik_lets,
                format!("::kinegen::ik::solutions::finish(&candidates, &target, &Self::REVOLUTE, {limits}, self){to_f32}"),
            ),
        }),
        Item::Method(Method {
            doc: "The arm angle of configuration `q` (see [`Self::ik_arm_angle`]), in `(−π, π]`; \
                  `None` where it is undefined (the shoulder–wrist line along axis 1, or the arm \
                  stretched)."
                .into(),
            name: "arm_angle",
            rates: false,
            ret: format!("::core::option::Option<{f}>"),
            body: custom(
                &format!("q: &[{f}; {n}]"),
                vec![],
                format!("::kinegen::ik::families::arm_angle(&self.ik_geometry(), {q_value}){angle_out}"),
            ),
        }),
        Item::Method(Method {
            doc: format!(
                "The exact intervals of arm angle in which configuration `config` (`[q2 ≥ 0, \
                 q4 ≥ 0, q6 ≥ 0]`, see `kinegen::ik::families::configuration`) of `pose` has every \
                 joint inside `LIMITS`: each limit is met where a sinusoid of ψ vanishes, so a \
                 user can pick ψ without sampling. Empty when that configuration cannot reach \
                 the pose within the limits.{}",
                if scalar == Scalar::F32 {
                    " In f64 radians, as the crossings are found."
                } else {
                    ""
                }
            ),
            name: "arm_angle_intervals",
            rates: false,
            ret: "::kinegen::ik::families::ArmAngleIntervals".into(),
            body: custom(
                &format!("pose: &[[{f}; 4]; 4], config: [bool; 3]"),
                interval_lets,
                format!("::kinegen::ik::families::arm_angle_intervals(&self.ik_geometry(), &target, config, {limits})"),
            ),
        }),
    ]
}

/// An f32 robot's method widens its `pose` to f64 first (`None` for an f64 robot).
fn widened_pose(scalar: Scalar) -> Option<&'static str> {
    match scalar {
        Scalar::F64 => None,
        Scalar::F32 => Some("let pose: &[[f64; 4]; 4] = &pose.map(|row| row.map(f64::from));"),
    }
}

/// The line making `target`, the pose the solver works on, from `pose` (f64 by then).
fn target_line(scalar: Scalar) -> &'static str {
    match scalar {
        Scalar::F64 => "let target = ::kinegen::ik::geometry::Pose::from_matrix(pose);",
        // The f32 rotation is orthonormal to f32 rounding only: solve for the nearest rotation.
        Scalar::F32 => "let target = ::kinegen::ik::solutions::orthonormalized(&::kinegen::ik::geometry::Pose::from_matrix(pose));",
    }
}

fn scalar_name(scalar: Scalar) -> &'static str {
    match scalar {
        Scalar::F64 => "f64",
        Scalar::F32 => "f32",
    }
}

/// `ik_seeded`: the solver call, then `finish`.
fn seeded(chain: &Chain, model: &IkModel, ty: &str, locked: Option<usize>) -> Method {
    let n = chain.dof();
    let family = &model.plan.family;
    let solver = format!("::kinegen::ik::families::{}", family.solver());
    let f = scalar_name(chain.scalar);
    // An f32 robot solves in f64: its inputs and limits widened first.
    let mut lets: Vec<String> = widened_pose(chain.scalar)
        .map(String::from)
        .into_iter()
        .collect();
    if chain.scalar == Scalar::F32 {
        lets.push(format!("let free: &[f64; {n}] = &free.map(f64::from);"));
        lets.push(format!(
            "let limits: [[f64; 2]; {n}] = Self::LIMITS.map(|l| l.map(f64::from));"
        ));
    }
    lets.extend([
        target_line(chain.scalar).to_string(),
        "if !target.is_finite() || free.iter().any(|x| !x.is_finite()) { return ::kinegen::ik::IkSolutions::empty(); }".into(),
        if model.plan.reversed {
            // Read backwards at expansion time: `ik` does not invert the geometry.
            "let g = self.ik_geometry_reversed();".into()
        } else {
            "let g = self.ik_geometry();".into()
        },
    ]);
    if *family == Family::General6r {
        // Which of the elimination's forms are regular for this arm, read on the first call
        // at a reference pose (the same whatever pose comes first).
        lets.push(
            "static HINT: ::kinegen::ik::families::Hint = ::kinegen::ik::families::Hint::new();"
                .into(),
        );
    }
    // The solver fills the candidates in place: returned by value they were copied once
    // more (about 450 bytes) on every call.
    let reversed = model.plan.reversed;
    let call = |g: &str, target: &str, free: &str, out: &str, locked: Option<usize>| {
        let (g_, target_, free_, out_) = if reversed {
            ("g", "t", "f", "o")
        } else {
            (g, target, free, out)
        };
        let args = match family {
            Family::Planar {
                revolute,
                prismatic,
            } => format!("&{g_}, {target_}, &{revolute:?}, {prismatic:?}, {free_}"),
            Family::Position(Position::OneRevolute { revolute_first }) => {
                format!("&{g_}, {target_}, {revolute_first}, {free_}")
            }
            Family::CartesianYaw { revolute } => {
                format!("&{g_}, {target_}, {revolute}, {free_}")
            }
            Family::Position(_) | Family::PitchRoll { .. } => {
                format!("&{g_}, {target_}, {free_}")
            }
            Family::General6r => format!("&{g_}, {target_}, {free_}, &HINT"),
            _ => {
                let pair = if model.plan.wrist_half_turn {
                    "HalfTurn"
                } else {
                    "Solve"
                };
                format!(
                    "{}{g_}, {target_}, {free_}, ::kinegen::ik::families::WristPair::{pair}",
                    if reversed { "" } else { "&" }
                )
            }
        };
        let solve = if reversed {
            // Read from the tool to the base: the inverted pose on the reversed geometry
            // (`g`), the joints put back in the robot's order; a locked joint locked on it.
            let closure = format!("|g, t, f, o| {solver}({args}, o)");
            match locked {
                None => format!(
                    "::kinegen::ik::reversed::solve_reversed(&{g}, {target}, {free}, {closure}, &mut {out});"
                ),
                Some(k) => format!(
                    "::kinegen::ik::reversed::solve_reversed_locked(&{g}, {target}, {k}, q_locked, {free}, {closure}, &mut {out});"
                ),
            }
        } else {
            format!("{solver}({args}, &mut {out_});")
        };
        format!("let mut {out} = ::kinegen::ik::solutions::Candidates::default();\n{solve}")
    };
    let (args, doc) = match locked {
        None => {
            lets.push(call("g", "&target", "free", "candidates", None));
            (
                format!("pose: &[[{f}; 4]; 4], free: &[{f}; {n}]"),
                "Every solution of `pose`, with `free` giving the joints a singular pose leaves \
                 undetermined (see [`Self::ik`], [`Self::ik_near`])."
                    .to_string(),
            )
        }
        Some(k) => {
            lets.push(
                "if !q_locked.is_finite() { return ::kinegen::ik::IkSolutions::empty(); }".into(),
            );
            if chain.scalar == Scalar::F32 {
                lets.push("let q_locked = f64::from(q_locked);".into());
            }
            lets.push(format!(
                "let free6: [f64; {}] = ::kinegen::ik::solutions::without(free, {k});",
                n - 1
            ));
            if reversed {
                lets.push(call("g", "&target", "&free6", "c6", Some(k)));
            } else {
                // The first joint locked moves the target, any other the geometry.
                lets.push(format!(
                    "let (g6, target6) = g.lock_at_pose::<{}>({k}, q_locked, &target);",
                    n - 1
                ));
                lets.push(call("g6", "&target6", "&free6", "c6", None));
            }
            (
                format!("pose: &[[{f}; 4]; 4], q_locked: {f}, free: &[{f}; {n}]"),
                format!(
                    "Every solution of `pose` with joint {} at `q_locked`, `free` giving the joints a \
                     singular pose leaves undetermined.",
                    k + 1
                ),
            )
        }
    };
    // A locked joint goes back in as `finish` settles each candidate.
    let (finish, candidates) = match locked {
        None => ("finish".to_string(), "&candidates".to_string()),
        Some(k) => ("finish_locked".to_string(), format!("&c6, {k}, q_locked")),
    };
    let (limits, to_f32) = match chain.scalar {
        Scalar::F64 => ("&Self::LIMITS", ""),
        Scalar::F32 => ("&limits", ".to_f32()"),
    };
    let result = format!(
        "::kinegen::ik::solutions::{finish}({candidates}, &target, &Self::REVOLUTE, {limits}, self){to_f32}"
    );
    Method {
        doc,
        name: "ik_seeded",
        rates: false,
        ret: ty.into(),
        body: MethodBody::Custom { args, lets, result },
    }
}

/// `ik_geometry`: the axes, points and tool at `q = 0`, from the parameters.
fn geometry(chain: &Chain, model: &IkModel) -> Method {
    geometry_method(
        chain,
        model,
        &model.ids,
        false,
        "ik_geometry",
        "The joint axes `h`, a point `p` on each, and the tool pose at `q = 0`, in the base \
         frame, from this robot's parameters: the product-of-exponentials geometry the \
         closed-form solver reads."
            .into(),
    )
}

/// `ik_geometry_reversed`, for a plan read from the tool to the base: that chain's
/// geometry, derived at expansion time (see [`IkModel::reversed_ids`]).
fn reversed_geometry(chain: &Chain, model: &IkModel, ids: &[Id]) -> Method {
    geometry_method(
        chain,
        model,
        ids,
        true,
        "ik_geometry_reversed",
        "The same arm read from the tool to the base, as the closed-form solver takes it: \
         joint `i` is joint `N + 1 − i` of [`Self::ik_geometry`] (1-based), its axis reversed and \
         seen from the tool at `q = 0`, and the base frame as the tool. Its forward kinematics \
         at the joints in reverse order is the inverse of the robot's pose; it equals \
         `self.ik_geometry().reversed()`, derived here at expansion time so that `ik` does \
         not invert the geometry on every call."
            .into(),
    )
}

/// A method returning the geometry whose nodes are `ids` (in [`IkModel::ids`]' order),
/// with the joints' kinds in reverse order if `reversed`.
fn geometry_method(
    chain: &Chain,
    model: &IkModel,
    ids: &[Id],
    reversed: bool,
    name: &'static str,
    doc: String,
) -> Method {
    let n = chain.dof();
    // f64 code for every robot (an f32 robot's parameters widened): the solver's input.
    let coder = Coder::new(chain, &model.zero).in_f64();
    let body = coder.body(ids);
    let o = &body.outputs;
    let v3 = |x: &[String]| {
        format!(
            "::kinegen::ik::geometry::V3::new({}, {}, {})",
            x[0], x[1], x[2]
        )
    };
    let h: Vec<String> = (0..n).map(|i| v3(&o[6 * i..6 * i + 3])).collect();
    let p: Vec<String> = (0..n).map(|i| v3(&o[6 * i + 3..6 * i + 6])).collect();
    let r = &o[6 * n..6 * n + 9];
    let mut prismatic = joint_flags(chain, JointKind::Prismatic);
    if reversed {
        prismatic.reverse();
    }
    let result = format!(
        "::kinegen::ik::geometry::Geometry {{ h: [{}], p: [{}], prismatic: [{}], r_tool: ::kinegen::ik::geometry::M3::new({}), p_tool: {} }}",
        h.join(", "),
        p.join(", "),
        prismatic.join(", "),
        r.join(", "),
        v3(&o[6 * n + 9..6 * n + 12])
    );
    Method {
        doc: format!(
            "{doc}{}",
            match chain.scalar {
                Scalar::F64 => "",
                Scalar::F32 => " In f64, from the widened f32 parameters: the solve runs in f64.",
            }
        ),
        name,
        rates: false,
        ret: format!("::kinegen::ik::geometry::Geometry<{n}>"),
        body: MethodBody::Custom {
            args: String::new(),
            lets: body.lets,
            result,
        },
    }
}

/// `true, false, …`: which joints are of `kind`, as a Rust array's elements.
fn joints_are(chain: &Chain, kind: JointKind) -> String {
    joint_flags(chain, kind).join(", ")
}

/// `"true"` or `"false"` per joint: whether it is of `kind`.
fn joint_flags(chain: &Chain, kind: JointKind) -> Vec<&'static str> {
    chain
        .kinds()
        .map(|k| if k == kind { "true" } else { "false" })
        .collect()
}
