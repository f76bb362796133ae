//! What the plotting examples share (`#[path]`-included, not an example of its own): the
//! font and where the pictures go.

use std::error::Error;
use std::path::{Path, PathBuf};

use plotters::style::{register_font, FontStyle};

/// Registers a TrueType font as "sans-serif" for plotters' pure-Rust (`ab_glyph`) text.
pub fn load_font() -> Result<(), Box<dyn Error>> {
    let candidates = std::env::var_os("KINEGEN_FONT")
        .map(PathBuf::from)
        .into_iter()
        .chain(
            [
                "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", // Debian, Ubuntu
                "/usr/share/fonts/TTF/DejaVuSans.ttf",             // Arch
                "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf", // Fedora
                "/Library/Fonts/Arial.ttf",
                "/System/Library/Fonts/Supplemental/Arial.ttf",
                "C:\\Windows\\Fonts\\arial.ttf",
            ]
            .into_iter()
            .map(PathBuf::from),
        );
    for path in candidates {
        if let Ok(bytes) = std::fs::read(&path) {
            // plotters keeps the font for the whole run: leak the bytes once.
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            register_font("sans-serif", FontStyle::Normal, bytes)
                .map_err(|_| format!("{} is not a usable TrueType font", path.display()))?;
            return Ok(());
        }
    }
    Err(
        "no TrueType font found: install the Debian package `fonts-dejavu-core` \
         or set KINEGEN_FONT=/path/to/font.ttf"
            .into(),
    )
}

/// The directory the pictures are written to: the first command-line argument, else the
/// repository's `docs/img`; created if missing.
pub fn output_dir() -> Result<PathBuf, Box<dyn Error>> {
    let out: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/img"));
    std::fs::create_dir_all(&out)?;
    Ok(out)
}
