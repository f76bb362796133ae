//! The colour scale of every picture the command draws (reach slices, the report's
//! maps): viridis, perceptually uniform and readable in grey and by colour-blind
//! readers.

/// Viridis at `t ∈ [0, 1]` (clamped; NaN as 0) as RGB: eleven of its stops, linearly
/// interpolated.
///
/// ```
/// assert_eq!(kinegen_cli::colour::viridis(0.0), [68, 1, 84]);
/// assert_eq!(kinegen_cli::colour::viridis(1.0), [253, 231, 37]);
/// ```
pub fn viridis(t: f64) -> [u8; 3] {
    const STOPS: [[u8; 3]; 11] = [
        [68, 1, 84],
        [72, 36, 117],
        [65, 68, 135],
        [53, 95, 141],
        [42, 120, 142],
        [33, 145, 140],
        [34, 168, 132],
        [68, 191, 112],
        [122, 209, 81],
        [189, 223, 38],
        [253, 231, 37],
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) } * 10.0;
    let i = (t.floor() as usize).min(9);
    let f = t - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    std::array::from_fn(|k| {
        (f64::from(a[k]) + f * (f64::from(b[k]) - f64::from(a[k]))).round() as u8
    })
}
