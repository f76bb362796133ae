//! `time_ms` bounds the whole engine (issue 8): the Panda with a 1 ms budget expands
//! with most simplification skipped, and the code it gets is still right. Which phases
//! the deadline cuts depends on the machine (the notes, compiler warnings, say which;
//! `kinegen-core/tests/budget.rs` pins them at 0 ms); the values do not.

mod common;

use common::configurations;
use kinegen::Kinematics;
use kinegen_core::numeric::NumericRobot;

kinegen::kinematics! {
    /// Panda, expanded within 1 ms of engine time.
    // Over budget on purpose: its notes (compiler warnings) are expected.
    #[allow(deprecated)]
    pub struct PandaRushed = "robots/panda.toml";
    budget: { time_ms: 1 },
}

#[test]
fn rushed_panda_matches_the_numeric_reference_and_the_full_expansion() {
    let robot = kinegen_core::front::toml_file::load_file(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/panda.toml"),
    )
    .unwrap()
    .0;
    let num = NumericRobot::new(&robot).unwrap();
    let rushed = PandaRushed::default();
    let full = kinegen_robots::Panda::default();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
    for q in configurations::<7>(7, 200) {
        let (t, j) = rushed.fk_and_jacobian(&q);
        let (tr, jr) = (num.fk(&q).unwrap(), num.jacobian(&q).unwrap());
        let jee = rushed.jacobian_ee(&q);
        let jeer = num.jacobian_ee(&q).unwrap();
        for r in 0..6 {
            for c in 0..7 {
                assert!(close(j[r][c], jr[(r, c)]), "J[{r}][{c}] at {q:?}");
                assert!(close(jee[r][c], jeer[(r, c)]), "Jee[{r}][{c}] at {q:?}");
            }
        }
        for r in 0..3 {
            for c in 0..4 {
                assert!(close(t[r][c], tr[(r, c)]), "T[{r}][{c}] at {q:?}");
            }
        }
        let frames = rushed.frames(&q);
        let want = full.frames(&q);
        for (i, (a, b)) in frames.iter().zip(&want).enumerate() {
            for r in 0..4 {
                for c in 0..4 {
                    assert!(close(a[r][c], b[r][c]), "frame {i} [{r}][{c}] at {q:?}");
                }
            }
        }
        // Through the trait too.
        assert_eq!(Kinematics::jacobian(&rushed, &q), j);
    }
}
