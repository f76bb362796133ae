//! The Jacobian determinant in closed form.
//!
//! - [`structural`]: the determinant in a well-chosen frame about a well-chosen point,
//!   taken by structure (single entries split off, memoised Laplace) and factored.
//! - [`closed_form`]: its factors read back as trigonometry, as code, checked.
//! - [`gradient`]: `∂det/∂q` and the singular factors' gradients, differentiated exactly.
//! - [`meaning`]: what each factor's zero set is on the arm, found on its geometry.

pub mod closed_form;
pub mod gradient;
pub mod meaning;
pub mod structural;
