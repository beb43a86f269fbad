//! A small software rasteriser for mode shapes: triangulated surfaces, coloured by a value per
//! vertex (the displacement's magnitude), drawn with a depth buffer in an orthographic view,
//! shaded by a fixed light, anti-aliased by 2 x 2 supersampling. PNG and animated PNG (APNG)
//! output; no GPU, window or system library.
//!
//! Engineers look at a mode before they read about it: [`render`] gives the picture that the
//! report shows beside the numbers, and [`write_apng`] the animation beside the ParaView series.

use crate::ReportError;
use squeal_element::geometry::{cross, dot};
use std::path::Path;

/// A triangulated surface with one value per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surface {
    /// Vertex positions (m), already deformed if a deformed shape is drawn.
    pub positions: Vec<[f64; 3]>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// The coloured value at each vertex, in `[0, 1]` of the colour map (clamped).
    pub values: Vec<f64>,
}

/// An orthographic view: the camera looks at the scene from `azimuth` degrees about +z
/// (measured from +x towards +y) and `elevation` degrees above the x-y plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub azimuth_deg: f64,
    pub elevation_deg: f64,
}

impl View {
    /// Straight down the z axis (x to the right, y up).
    pub const TOP: View = View {
        azimuth_deg: -90.0,
        elevation_deg: 90.0,
    };
    /// From the front-right, above: the usual three-quarter view.
    pub const ISO: View = View {
        azimuth_deg: -60.0,
        elevation_deg: 30.0,
    };
    /// Level with the disc, from -y: the profile, where out-of-plane motion shows.
    pub const SIDE: View = View {
        azimuth_deg: -90.0,
        elevation_deg: 0.0,
    };

    /// The camera's right, up and towards-viewer unit vectors.
    fn axes(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        // Towards the viewer.
        let w = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
        // Right: horizontal, perpendicular to the viewing direction. Looking straight down,
        // the azimuth alone sets it.
        let r = [-a.sin(), a.cos(), 0.0];
        let u = cross(w, r);
        (r, u, w)
    }
}

/// The colour map: viridis (perceptually uniform, readable in grey and with the common colour
/// vision deficiencies), from its published anchor colours, linearly interpolated.
pub fn colormap(t: f64) -> [u8; 3] {
    const ANCHORS: [[f64; 3]; 9] = [
        [68.0, 1.0, 84.0],
        [71.0, 44.0, 122.0],
        [59.0, 81.0, 139.0],
        [44.0, 113.0, 142.0],
        [33.0, 144.0, 141.0],
        [39.0, 173.0, 129.0],
        [92.0, 200.0, 99.0],
        [170.0, 220.0, 50.0],
        [253.0, 231.0, 37.0],
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (ANCHORS.len() - 1) as f64;
    let i = (x.floor() as usize).min(ANCHORS.len() - 2);
    let f = x - i as f64;
    let c = |k: usize| (ANCHORS[i][k] * (1.0 - f) + ANCHORS[i + 1][k] * f).round() as u8;
    [c(0), c(1), c(2)]
}

/// The extent of every surface in the view's screen coordinates: `(min, max)` of (right, up).
pub fn screen_bounds(surfaces: &[&Surface], view: &View) -> Option<([f64; 2], [f64; 2])> {
    let (r, u, _) = view.axes();
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for s in surfaces {
        for p in &s.positions {
            let q = [dot(*p, r), dot(*p, u)];
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
    }
    (lo[0].is_finite() && hi[0] > lo[0] - 1.0).then_some((lo, hi))
}

/// Draws `surfaces` into an RGB image of `width x height` pixels on white, fitted to `bounds`
/// (screen coordinates, from [`screen_bounds`]; give the same bounds to every frame of an
/// animation so that it does not jump). Returns `3 * width * height` bytes.
pub fn render(
    surfaces: &[&Surface],
    view: &View,
    bounds: ([f64; 2], [f64; 2]),
    width: u32,
    height: u32,
) -> Vec<u8> {
    let (w2, h2) = (2 * width as usize, 2 * height as usize);
    let mut rgb = vec![255u8; 3 * w2 * h2];
    let mut depth = vec![f64::NEG_INFINITY; w2 * h2];
    let (r, u, w) = view.axes();
    let (lo, hi) = bounds;
    let margin = 0.06;
    let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
    let scale = ((w2 as f64) * (1.0 - 2.0 * margin) / span[0])
        .min((h2 as f64) * (1.0 - 2.0 * margin) / span[1]);
    let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    let to_px = |p: [f64; 3]| -> [f64; 3] {
        [
            0.5 * w2 as f64 + (dot(p, r) - centre[0]) * scale,
            0.5 * h2 as f64 - (dot(p, u) - centre[1]) * scale,
            dot(p, w),
        ]
    };
    // Light from over the viewer's left shoulder.
    let light = {
        let l = [
            -0.4 * r[0] + 0.5 * u[0] + w[0],
            -0.4 * r[1] + 0.5 * u[1] + w[1],
            -0.4 * r[2] + 0.5 * u[2] + w[2],
        ];
        let n = dot(l, l).sqrt();
        [l[0] / n, l[1] / n, l[2] / n]
    };
    for s in surfaces {
        let px: Vec<[f64; 3]> = s.positions.iter().map(|&p| to_px(p)).collect();
        for t in &s.triangles {
            let [a, b, c] = t.map(|i| i as usize);
            let (Some(pa), Some(pb), Some(pc)) = (px.get(a), px.get(b), px.get(c)) else {
                continue;
            };
            let (p0, p1, p2) = (s.positions[a], s.positions[b], s.positions[c]);
            let n = cross(
                [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]],
                [p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]],
            );
            let nn = dot(n, n).sqrt();
            // A degenerate (or NaN) triangle has no normal to shade with.
            if nn.is_nan() || nn <= 0.0 {
                continue;
            }
            // Two-sided lighting: a surface seen from behind is lit as from the front.
            let shade = 0.35 + 0.65 * (dot(n, light) / nn).abs();
            let vals = [a, b, c].map(|i| s.values.get(i).copied().unwrap_or(0.0));
            fill_triangle(&mut rgb, &mut depth, w2, h2, [*pa, *pb, *pc], vals, shade);
        }
    }
    crate::downsample_2x2(&rgb, width as usize, height as usize)
}

/// Scan-converts one triangle with depth test and interpolated colour value.
#[allow(clippy::too_many_arguments)]
fn fill_triangle(
    rgb: &mut [u8],
    depth: &mut [f64],
    w: usize,
    h: usize,
    p: [[f64; 3]; 3],
    v: [f64; 3],
    shade: f64,
) {
    let area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if area.abs() < 1e-12 {
        return;
    }
    let xmin = p
        .iter()
        .map(|q| q[0])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as usize;
    let xmax = (p
        .iter()
        .map(|q| q[0])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil() as i64)
        .min(w as i64 - 1);
    let ymin = p
        .iter()
        .map(|q| q[1])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as usize;
    let ymax = (p
        .iter()
        .map(|q| q[1])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil() as i64)
        .min(h as i64 - 1);
    if xmax < 0 || ymax < 0 {
        return;
    }
    for y in ymin..=ymax as usize {
        let py = y as f64 + 0.5;
        for x in xmin..=xmax as usize {
            let px = x as f64 + 0.5;
            let l0 = ((p[1][0] - px) * (p[2][1] - py) - (p[2][0] - px) * (p[1][1] - py)) / area;
            let l1 = ((p[2][0] - px) * (p[0][1] - py) - (p[0][0] - px) * (p[2][1] - py)) / area;
            let l2 = 1.0 - l0 - l1;
            if l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9 {
                continue;
            }
            let z = l0 * p[0][2] + l1 * p[1][2] + l2 * p[2][2];
            let k = y * w + x;
            if z <= depth[k] {
                continue;
            }
            depth[k] = z;
            let c = colormap(l0 * v[0] + l1 * v[1] + l2 * v[2]);
            for ch in 0..3 {
                rgb[3 * k + ch] = (f64::from(c[ch]) * shade).round().clamp(0.0, 255.0) as u8;
            }
        }
    }
}

/// A horizontal colour bar of the map, `width x height` pixels, for a legend.
pub fn colour_bar(width: u32, height: u32) -> Vec<u8> {
    let mut out = Vec::with_capacity(3 * (width * height) as usize);
    for _ in 0..height {
        for x in 0..width {
            out.extend_from_slice(&colormap(f64::from(x) / f64::from(width.max(2) - 1)));
        }
    }
    out
}

/// Pixels of the scale row under [`colour_bar_with_scale`]'s bar.
const SCALE_ROW: u32 = 18;

/// A horizontal colour bar `width x bar_height` with its scale in a row of text underneath:
/// `0` under the left end, `1` under the right end and `caption` (what the colour measures)
/// between them, in the embedded font. Returns the RGB pixels and the height.
pub fn colour_bar_with_scale(
    width: u32,
    bar_height: u32,
    caption: &str,
) -> Result<(Vec<u8>, u32), ReportError> {
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    if !crate::font::ensure_registered() {
        return Err(ReportError::Font);
    }
    let height = bar_height + SCALE_ROW;
    let mut rgb = vec![255u8; 3 * (width * height) as usize];
    rgb[..3 * (width * bar_height) as usize].copy_from_slice(&colour_bar(width, bar_height));
    {
        let area = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        let font = FontDesc::new(crate::font::FAMILY, 13.0, FontStyle::Normal);
        let y = (bar_height + 3) as i32;
        let right = width.saturating_sub(1) as i32;
        for (text, x, h) in [
            ("0", 0, HPos::Left),
            (caption, right / 2, HPos::Center),
            ("1", right, HPos::Right),
        ] {
            let style = TextStyle::from(font.clone())
                .color(&BLACK)
                .pos(Pos::new(h, VPos::Top));
            area.draw_text(text, &style, (x, y))
                .map_err(|e| ReportError::Draw(e.to_string()))?;
        }
        area.present()
            .map_err(|e| ReportError::Draw(e.to_string()))?;
    }
    Ok((rgb, height))
}

/// Places images side by side (same height) with `gap` white pixels between them.
pub fn side_by_side(images: &[(&[u8], u32, u32)], gap: u32) -> (Vec<u8>, u32, u32) {
    let h = images.iter().map(|i| i.2).max().unwrap_or(0);
    let w: u32 =
        images.iter().map(|i| i.1).sum::<u32>() + gap * images.len().saturating_sub(1) as u32;
    let mut out = vec![255u8; 3 * (w * h) as usize];
    let mut x0 = 0;
    for (img, iw, ih) in images {
        for y in 0..*ih {
            let src = &img[3 * (y * iw) as usize..3 * ((y + 1) * iw) as usize];
            let d = 3 * (y * w + x0) as usize;
            out[d..d + src.len()].copy_from_slice(src);
        }
        x0 += iw + gap;
    }
    (out, w, h)
}

/// Writes an RGB image as a PNG file (atomically).
pub fn write_rgb_png(path: &Path, rgb: &[u8], width: u32, height: u32) -> Result<(), ReportError> {
    let bytes = crate::encode_png(rgb, width, height, 1.0)?;
    squeal_io::atomic_write_bytes(path, &bytes)?;
    Ok(())
}

/// Writes RGB frames as an animated PNG (APNG, looping forever, `delay_ms` per frame) — shown
/// animated by every current browser, as its first frame by other viewers.
pub fn write_apng(
    path: &Path,
    frames: &[Vec<u8>],
    width: u32,
    height: u32,
    delay_ms: u16,
) -> Result<(), ReportError> {
    let err = |e: png::EncodingError| ReportError::Png(e.to_string());
    if frames.is_empty() {
        return Err(ReportError::InvalidFigure(
            "an animation needs frames".into(),
        ));
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_animated(frames.len() as u32, 0).map_err(err)?;
        enc.set_frame_delay(delay_ms, 1000).map_err(err)?;
        let mut writer = enc.write_header().map_err(err)?;
        for f in frames {
            writer.write_image_data(f).map_err(err)?;
        }
        writer.finish().map_err(err)?;
    }
    squeal_io::atomic_write_bytes(path, &out)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square in the x-y plane (two triangles), value 0 at x = 0 and 1 at x = 1.
    fn square() -> Surface {
        Surface {
            positions: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            values: vec![0.0, 1.0, 1.0, 0.0],
        }
    }

    fn pixel(img: &[u8], w: u32, x: u32, y: u32) -> [u8; 3] {
        let k = 3 * (y * w + x) as usize;
        [img[k], img[k + 1], img[k + 2]]
    }

    /// Seen from the top, the square fills the middle of the image; its left edge has the
    /// colour map's low end and its right edge the high end (shaded by the same factor), the
    /// corners outside it stay white.
    #[test]
    fn a_square_seen_from_above_is_coloured_left_to_right() {
        let s = square();
        let b = screen_bounds(&[&s], &View::TOP).unwrap();
        let (w, h) = (100, 100);
        let img = render(&[&s], &View::TOP, b, w, h);
        assert_eq!(pixel(&img, w, 1, 1), [255, 255, 255]);
        let (left, right) = (pixel(&img, w, 10, 50), pixel(&img, w, 89, 50));
        // Viridis runs from purple (blue > green) to yellow (green > blue).
        assert!(
            left[2] > left[1] && right[1] > right[2],
            "{left:?} {right:?}"
        );
        // Each pixel is the colour map at the interpolated value, times one shade for the
        // flat square: the left one is a low value (under 0.25), the right one a high value
        // (over 0.75), with the same shade.
        let fit = |px: [u8; 3], range: std::ops::Range<f64>| -> Option<(f64, f64)> {
            (0..=1000)
                .map(|i| range.start + (range.end - range.start) * f64::from(i) / 1000.0)
                .filter_map(|t| {
                    let c = colormap(t);
                    let shade = f64::from(px[2]) / f64::from(c[2]);
                    (0..3)
                        .all(|k| (f64::from(c[k]) * shade - f64::from(px[k])).abs() < 2.5)
                        .then_some((t, shade))
                })
                .next()
        };
        let (_, shade_left) = fit(left, 0.0..0.25).expect("left pixel off the colour map");
        let (_, shade_right) = fit(right, 0.75..1.0).expect("right pixel off the colour map");
        assert!(
            (shade_left - shade_right).abs() < 0.05,
            "{shade_left} {shade_right}"
        );
    }

    /// The nearer of two overlapping squares wins, whatever the drawing order.
    #[test]
    fn the_depth_buffer_keeps_the_nearer_surface() {
        let mut near = square();
        near.values = vec![1.0; 4];
        for p in &mut near.positions {
            p[2] = 0.1;
        }
        let far = square();
        let b = screen_bounds(&[&far], &View::TOP).unwrap();
        let a = render(&[&near, &far], &View::TOP, b, 50, 50);
        let c = render(&[&far, &near], &View::TOP, b, 50, 50);
        assert_eq!(a, c);
        let p = pixel(&a, 50, 10, 25);
        assert!(
            p[1] > p[2],
            "{p:?}: the near (yellow) square must be on top"
        );
    }

    #[test]
    fn the_colour_bar_has_its_scale_written_under_it() {
        let (img, h) = colour_bar_with_scale(300, 12, "|u| / max |u|").unwrap();
        assert_eq!(h, 12 + SCALE_ROW);
        // The bar itself is the map: dark at the left end, yellow at the right (exact pixels).
        assert_eq!(pixel(&img, 300, 0, 5), colormap(0.0));
        assert_eq!(pixel(&img, 300, 299, 5), colormap(1.0));
        // Under it, dark text on white: the "0" at the left, the caption in the middle, the
        // "1" at the right (each column range has ink, i.e. a pixel darker than mid-grey).
        let ink = |x0: u32, x1: u32| {
            (x0..x1).any(|x| (13..h).any(|y| pixel(&img, 300, x, y).iter().all(|&c| c < 128)))
        };
        assert!(ink(0, 10), "no 0 under the left end");
        assert!(ink(110, 190), "no caption");
        assert!(ink(290, 300), "no 1 under the right end");
        assert!(!ink(20, 60), "text where there should be none");
    }

    #[test]
    fn an_apng_has_its_frames() {
        let dir = std::env::temp_dir().join(format!("squeal-apng-{}", std::process::id()));
        let frames: Vec<Vec<u8>> = (0..3).map(|k| vec![80 * k as u8; 3 * 4 * 2]).collect();
        let path = dir.join("a.png");
        write_apng(&path, &frames, 4, 2, 100).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        // acTL chunk: 3 frames, 0 plays (forever).
        let at = bytes.windows(4).position(|w| w == b"acTL").unwrap();
        assert_eq!(&bytes[at + 4..at + 12], &[0, 0, 0, 3, 0, 0, 0, 0]);
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let reader = decoder.read_info().unwrap();
        assert_eq!(
            reader.info().animation_control().map(|a| a.num_frames),
            Some(3)
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
