//! Several names in one sentence, as the engine's messages and notes write them.

/// `a, b and c` (one item: itself; none: empty).
///
/// ```
/// use kinegen_core::words::and_list;
/// assert_eq!(and_list(&["1", "2", "3"]), "1, 2 and 3");
/// assert_eq!(and_list(&["`base`"]), "`base`");
/// ```
pub fn and_list<S: AsRef<str>>(items: &[S]) -> String {
    let items: Vec<&str> = items.iter().map(AsRef::as_ref).collect();
    match items.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => items.concat(),
    }
}
