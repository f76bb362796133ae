//! The closed-form IK: the family the engine decided, its derivation steps, and every
//! solution of one pose (the pose `fk` gives at a fixed, generic configuration), solved
//! by the same solver the generated `ik` calls.

use kinegen_core::emit::mathml::escape;
use kinegen_core::model::robot::JointKind;
use kinegen_core::{Chain, Derived};

use super::html::{self, inline_code, Section};
use crate::ik::Solver;

/// The configuration whose pose is solved: generic (no joint at a special angle), the
/// same for every robot, clamped into the joint limits.
const Q0: [f64; 7] = [0.4, -1.0, 1.3, -0.8, 0.9, 0.5, 0.3];

/// The solutions of the report's pose, or why there are none.
#[derive(Clone, Debug)]
pub struct Solutions {
    /// The configuration the pose was made from.
    pub q0: Vec<f64>,
    /// Its pose, row-major 4×4.
    pub pose: [[f64; 4]; 4],
    /// The family's name and its steps (`Err`: why no closed form).
    pub family: Result<(String, Vec<String>), String>,
    /// Every solution: joint values, residual `max |fk(q) − pose|`, within limits.
    pub solutions: Vec<(Vec<f64>, f64, bool)>,
}

impl Solutions {
    /// Solve the pose of a fixed generic configuration (clamped into `chain`'s limits).
    pub fn of(chain: &Chain, derived: &Derived) -> Solutions {
        let q0: Vec<f64> = chain
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let x = match l.motion.kind {
                    JointKind::Revolute => Q0[i % Q0.len()],
                    JointKind::Prismatic => 0.1 + 0.05 * i as f64,
                };
                match l.limits {
                    Some([lo, hi]) => x.clamp(lo, hi),
                    None => x,
                }
            })
            .collect();
        let ids: Vec<_> = derived.model.fk_rows.iter().flatten().copied().collect();
        let v = derived.model.eval(chain, &q0, &ids);
        let mut pose = [[0.0, 0.0, 0.0, 1.0]; 4];
        for (r, row) in pose.iter_mut().take(3).enumerate() {
            row.copy_from_slice(&v[4 * r..4 * r + 4]);
        }
        let mut out = Solutions {
            q0,
            pose,
            family: Err(String::new()),
            solutions: Vec::new(),
        };
        let solver = match Solver::new(chain, derived) {
            Ok(s) => s,
            Err(e) => {
                out.family = Err(e.to_string());
                return out;
            }
        };
        out.family = Ok((solver.family().to_string(), solver.steps().to_vec()));
        // The locked joint of a 7-joint arm takes q0's value (`near`).
        match solver.solve(pose, Some(&out.q0), None, None) {
            Ok(r) => {
                out.solutions = r
                    .branches
                    .iter()
                    .zip(&r.residuals)
                    .map(|(b, res)| (b.q.clone(), *res, b.flags.within_limits))
                    .collect();
            }
            Err(e) => out.family = Err(e.to_string()),
        }
        out
    }
}

/// The section: family, steps, the pose and its solutions.
pub fn section(chain: &Chain, derived: &Derived, s: &Solutions) -> Section {
    let mut body = String::new();
    match &s.family {
        Err(why) => body.push_str(&html::note(&format!(
            "{}: no closed-form inverse kinematics: {why}",
            chain.name
        ))),
        Ok((family, steps)) => {
            body.push_str(&format!("<p>Family: <strong>{}</strong>", escape(family)));
            if let Ok(ik) = &derived.ik {
                let most = match ik.plan.max_solutions {
                    1 => "one solution".to_string(),
                    n => format!("at most {n} solutions"),
                };
                body.push_str(&format!(
                    "; {most} per pose, the family decided exactly from the joint axes at q = 0"
                ));
            }
            body.push_str(".</p>\n<ol>\n");
            for step in steps {
                body.push_str(&format!("<li>{}</li>\n", inline_code(step)));
            }
            body.push_str("</ol>\n");
            body.push_str(&html::p(&format!(
                "The pose of q = [{}] and every solution of it:",
                list(&s.q0)
            )));
            let rows: Vec<Vec<String>> = s
                .solutions
                .iter()
                .enumerate()
                .map(|(i, (q, res, within))| {
                    vec![
                        (i + 1).to_string(),
                        list(q),
                        format!("{res:.1e}"),
                        if *within { "yes" } else { "no" }.to_string(),
                    ]
                })
                .collect();
            body.push_str(&html::table(
                &["#", "q (rad, m)", "max |fk(q) − pose|", "within limits"],
                &rows,
            ));
        }
    }
    Section {
        id: "ik",
        title: "Inverse kinematics".into(),
        body,
    }
}

/// `0.400, -1.000, …`.
pub fn list(q: &[f64]) -> String {
    q.iter()
        .map(|x| format!("{x:.3}"))
        .collect::<Vec<_>>()
        .join(", ")
}
