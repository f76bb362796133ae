// The engine's notes (budgets hit, fallbacks taken) are compiler warnings: the
// `deprecated` lint, at the `budget` entry. Denied here, so that this file fails to
// compile and the warnings' text is pinned in the `.stderr`. A robot without notes
// gives none, and `#[allow(deprecated)]` on the struct silences its notes.
#![deny(deprecated)]

kinegen::kinematics! {
    /// Over a tiny normal-form budget: a note.
    pub struct Noted;
    convention: standard,
    params: { L1: 1.0, L2: 0.8 },
    joints: [
        revolute { a: L1, alpha: 0, d: 0 },
        revolute { a: L2, alpha: 0, d: 0 },
    ],
    budget: { nodes: 2 },
}

kinegen::kinematics! {
    /// The default budget: no note, no warning.
    pub struct Clean;
    convention: standard,
    params: { L1: 1.0, L2: 0.8 },
    joints: [
        revolute { a: L1, alpha: 0, d: 0 },
        revolute { a: L2, alpha: 0, d: 0 },
    ],
}

kinegen::kinematics! {
    /// The same note as `Noted`, silenced.
    #[allow(deprecated)]
    pub struct Quiet;
    convention: standard,
    params: { L1: 1.0, L2: 0.8 },
    joints: [
        revolute { a: L1, alpha: 0, d: 0 },
        revolute { a: L2, alpha: 0, d: 0 },
    ],
    budget: { nodes: 2 },
}

fn main() {}
