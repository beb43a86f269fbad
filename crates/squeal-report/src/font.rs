//! The embedded font: DejaVu Sans 2.37 (Bitstream Vera licence, see
//! `assets/fonts/LICENSE-DejaVu.txt`), registered with plotters' ab_glyph text renderer under
//! the family name `sans-serif`, so text renders the same on a machine without any system
//! font or fontconfig.

use plotters::style::{FontDesc, FontFamily, FontStyle, register_font};
use std::sync::OnceLock;

static DEJAVU_SANS: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The family every text of a figure uses (SVG viewers substitute their own sans-serif).
pub(crate) const FAMILY: FontFamily<'static> = FontFamily::SansSerif;

/// Registers the embedded font once; `false` if plotters rejected it (it cannot, for the
/// shipped file, but the caller turns that into an error rather than a panic).
pub(crate) fn ensure_registered() -> bool {
    static DONE: OnceLock<bool> = OnceLock::new();
    *DONE.get_or_init(|| register_font(FAMILY.as_str(), FontStyle::Normal, DEJAVU_SANS).is_ok())
}

/// Width and height in pixels of `text` at font size `size` (plotters' size unit).
pub(crate) fn text_size(text: &str, size: f64) -> (f64, f64) {
    let font = FontDesc::new(FAMILY, size, FontStyle::Normal);
    match font.box_size(text) {
        Ok((w, _)) => (f64::from(w), size),
        Err(_) => (0.6 * size * text.chars().count() as f64, size),
    }
}
