//! The names of angle sums and differences in generated code, and what they mean.
//!
//! `c23` is cos(q2 + q3), `s234` sin(q2 + q3 + q4); a joint whose angle is subtracted
//! carries an `m` ("minus"): `c2m3` is cos(q2 − q3), `s2m34` sin(q2 − q3 + q4). Robots
//! with ten or more joints separate the joints by `_` (`c1_2`, `c9_m10`). An `n` in front
//! is the negated value the sign pass may compute instead (`nc23` = −cos(q2 + q3)). The
//! first angle is never subtracted: cos(−q2 + q3) is `c2m3` and sin(−q2 + q3) is `ns2m3`.
//!
//! Differences come from joints that turn the other way: a URDF joint about −y after
//! one about +y moves the tool by q2 − q3, and its formulas read `cos(q2 − q3)`.
//!
//! ```
//! use kinegen_core::emit::angle_names::AngleName;
//! let n = AngleName::parse("c2m3").unwrap();
//! assert_eq!(n.text(), "cos(q2 - q3)");
//! assert_eq!(n.latex(), r"\cos\left(q_{2} - q_{3}\right)");
//! assert_eq!(AngleName::parse("ns1_2").unwrap().text(), "-sin(q1 + q2)");
//! assert_eq!(AngleName::parse("t12"), None);
//! ```

/// A parsed angle-sum name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AngleName {
    /// The value is negated (`nc23`).
    pub negated: bool,
    /// sin (`s…`) or cos (`c…`).
    pub sin: bool,
    /// The joints (1-based), each with `true` where its angle is subtracted.
    pub joints: Vec<(usize, bool)>,
}

impl AngleName {
    /// The suffix after `s`/`c` for a run of joints (1-based, with the subtracted ones
    /// marked), for a robot of `dof` joints: `23`, `2m3`, `9_m10`.
    pub fn label(joints: &[(usize, bool)], dof: usize) -> String {
        let sep = if dof >= 10 { "_" } else { "" };
        joints
            .iter()
            .map(|&(j, minus)| format!("{}{j}", if minus { "m" } else { "" }))
            .collect::<Vec<_>>()
            .join(sep)
    }

    /// The name read back; `None` if it names no sum of two or more joints.
    pub fn parse(name: &str) -> Option<AngleName> {
        if let Some(mut n) = name.strip_prefix('n').and_then(AngleName::parse) {
            if !n.negated {
                n.negated = true;
                return Some(n);
            }
            return None;
        }
        let sin = match name.chars().next()? {
            's' => true,
            'c' => false,
            _ => return None,
        };
        let rest = &name[1..];
        // Single digits, or `_`-separated numbers; each may start with `m`.
        let parts: Vec<&str> = if rest.contains('_') {
            rest.split('_').collect()
        } else {
            let mut v = Vec::new();
            let mut start = 0;
            for (i, ch) in rest.char_indices() {
                if ch.is_ascii_digit() {
                    v.push(&rest[start..=i]);
                    start = i + 1;
                }
            }
            if start != rest.len() {
                return None;
            }
            v
        };
        let mut joints = Vec::new();
        for p in parts {
            let (minus, digits) = match p.strip_prefix('m') {
                Some(d) => (true, d),
                None => (false, p),
            };
            if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) {
                return None;
            }
            joints.push((digits.parse().ok()?, minus));
        }
        let first_plus = joints.first().is_some_and(|&(_, minus)| !minus);
        (joints.len() >= 2 && first_plus).then_some(AngleName {
            negated: false,
            sin,
            joints,
        })
    }

    /// The angle's terms with their signs: `(q2, false), (q3, true)` for q2 − q3, each
    /// joint written by `joint`.
    fn angle(&self, joint: impl Fn(usize) -> String) -> String {
        let mut s = String::new();
        for (k, &(j, minus)) in self.joints.iter().enumerate() {
            if k > 0 {
                s.push_str(if minus { " - " } else { " + " });
            }
            s.push_str(&joint(j));
        }
        s
    }

    /// Plain text: `cos(q2 - q3)`, `-sin(q1 + q2)`.
    pub fn text(&self) -> String {
        format!(
            "{}{}({})",
            if self.negated { "-" } else { "" },
            if self.sin { "sin" } else { "cos" },
            self.angle(|j| format!("q{j}"))
        )
    }

    /// Compact, for a code comment: `cos(q2-q3)`, `−sin(q1+q2)`.
    pub fn compact_text(&self) -> String {
        self.text()
            .replace(' ', "")
            .replacen('-', "−", self.negated as usize)
    }

    /// LaTeX: `\cos\left(q_{2} - q_{3}\right)`.
    pub fn latex(&self) -> String {
        format!(
            r"{}\{}\left({}\right)",
            if self.negated { "-" } else { "" },
            if self.sin { "sin" } else { "cos" },
            self.angle(|j| format!("q_{{{j}}}"))
        )
    }

    /// The subscript of the name in LaTeX: `23`, `2-3`, `1,2` (ten or more joints).
    pub fn latex_subscript(&self, name: &str) -> String {
        let any_minus = self.joints.iter().any(|&(_, minus)| minus);
        if !any_minus {
            let sep = if name.contains('_') { "," } else { "" };
            return self
                .joints
                .iter()
                .map(|(j, _)| j.to_string())
                .collect::<Vec<_>>()
                .join(sep);
        }
        // With a difference the signs are written out: `c_{2-3+4}`.
        self.angle(|j| j.to_string()).replace(' ', "")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_read_back_with_their_signs() {
        let p = |s: &str| AngleName::parse(s).map(|n| n.text());
        assert_eq!(p("c23").unwrap(), "cos(q2 + q3)");
        assert_eq!(p("s234").unwrap(), "sin(q2 + q3 + q4)");
        assert_eq!(p("s2m34").unwrap(), "sin(q2 - q3 + q4)");
        assert_eq!(p("c1_2_3").unwrap(), "cos(q1 + q2 + q3)");
        assert_eq!(p("c9_m10").unwrap(), "cos(q9 - q10)");
        assert_eq!(p("nc2m3").unwrap(), "-cos(q2 - q3)");
        for not_a_sum in [
            "c1", "t12", "s_k1", "cm23", "c2m", "nnc23", "c", "sm", "c2x3",
        ] {
            assert_eq!(p(not_a_sum), None, "{not_a_sum}");
        }
    }

    #[test]
    fn labels_parse_back_to_their_joints() {
        for (joints, dof) in [
            (vec![(2, false), (3, true)], 6),
            (vec![(2, false), (3, true), (4, false)], 6),
            (vec![(9, false), (10, true)], 12),
            (vec![(1, false), (2, false)], 12),
        ] {
            let name = format!("c{}", AngleName::label(&joints, dof));
            assert_eq!(AngleName::parse(&name).unwrap().joints, joints, "{name}");
        }
    }
}
