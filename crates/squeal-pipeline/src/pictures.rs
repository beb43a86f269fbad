//! Pictures of the brake for the report: mode shapes on the disc and pad meshes rendered as
//! images (surface coloured by the displacement's magnitude, deformed shape, three views), the
//! disc mode's nodal-diameter classification, and the limit cycle as an animated PNG.
//!
//! The surfaces are the meshes' boundary faces (6-node triangles split in four); the
//! displacements are the reduced vectors expanded with the Craig–Bampton bases
//! ([`crate::shapes::expand`]).

use crate::error::Result;
use crate::model::Model;
use crate::shapes::{Meshes, PartMesh, expand};
use faer::c64;
use squeal_chbm::ChbmSolution;
use squeal_mesh::Mesh;
use squeal_report::raster::{
    Surface, View, colour_bar_with_scale, render, screen_bounds, side_by_side, write_apng,
    write_rgb_png,
};
use std::path::Path;

/// The boundary of a mesh as linear triangles: every element face that no other element
/// shares ([`squeal_mesh::select::boundary_faces`] and `boundary_quads`), a 6-node triangle
/// split into four, an 8-node quadrilateral into six (four at the corners, two across the
/// midside nodes).
pub fn boundary_triangles(mesh: &Mesh) -> Vec<[u32; 3]> {
    use squeal_mesh::select::{boundary_faces, boundary_quads};
    let faces = boundary_faces(mesh);
    let mut out = Vec::with_capacity(4 * faces.len());
    for [a, b, c, ab, bc, ca] in faces {
        out.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    for [a, b, c, d, ab, bc, cd, da] in boundary_quads(mesh) {
        out.extend([
            [a, ab, da],
            [ab, b, bc],
            [bc, c, cd],
            [cd, d, da],
            [ab, bc, cd],
            [ab, cd, da],
        ]);
    }
    out
}

/// Expands a reduced brake vector onto both parts: `3 × nodes` values per part.
fn expand_parts(parts: &[PartMesh<'_>], x: &[f64]) -> Result<Vec<Vec<f64>>> {
    parts
        .iter()
        .map(|p| expand(p.part, p.mesh, p.path, &x[p.range.clone()]))
        .collect()
}

/// The largest model dimension (bounding-box diagonal over both parts, m).
/// Level with the disc, from the pads' side (the azimuth of their nodes' mean about z), so that
/// a pad under the disc is not hidden behind the hat; [`View::SIDE`] without pads.
fn side_view(parts: &[PartMesh<'_>]) -> View {
    let (mut x, mut y, mut n) = (0.0, 0.0, 0usize);
    for p in parts.iter().skip(1) {
        for q in &p.mesh.nodes {
            x += q[0];
            y += q[1];
            n += 1;
        }
    }
    if n == 0 || (x == 0.0 && y == 0.0) {
        return View::SIDE;
    }
    View {
        azimuth_deg: y.atan2(x).to_degrees(),
        elevation_deg: 0.0,
    }
}

fn model_size(parts: &[PartMesh<'_>]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in parts {
        if let Some((a, b)) = p.mesh.bounding_box() {
            for k in 0..3 {
                lo[k] = lo[k].min(a[k]);
                hi[k] = hi[k].max(b[k]);
            }
        }
    }
    ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt()
}

fn norm3(u: &[f64], i: usize) -> f64 {
    (u[3 * i].powi(2) + u[3 * i + 1].powi(2) + u[3 * i + 2].powi(2)).sqrt()
}

/// The largest displacement magnitude of each part (`u` per part, `3 × nodes`).
fn part_peaks(u: &[Vec<f64>]) -> Vec<f64> {
    u.iter()
        .map(|u| (0..u.len() / 3).map(|i| norm3(u, i)).fold(0.0, f64::max))
        .collect()
}

/// Surfaces of the parts deformed by `u` (per part, `3 × nodes`) times `scale`, coloured by
/// `|u|` over `umax[p]`, the colour scale of part `p` (its own largest in a mode picture).
fn surfaces(
    parts: &[PartMesh<'_>],
    tris: &[Vec<[u32; 3]>],
    u: &[Vec<f64>],
    scale: f64,
    umax: &[f64],
) -> Vec<Surface> {
    parts
        .iter()
        .zip(tris)
        .zip(u)
        .zip(umax)
        .map(|(((p, t), u), &umax)| Surface {
            positions: p
                .mesh
                .nodes
                .iter()
                .enumerate()
                .map(|(i, x)| {
                    [
                        x[0] + scale * u[3 * i],
                        x[1] + scale * u[3 * i + 1],
                        x[2] + scale * u[3 * i + 2],
                    ]
                })
                .collect(),
            triangles: t.clone(),
            values: (0..p.mesh.num_nodes())
                .map(|i| norm3(u, i) / umax.max(f64::MIN_POSITIVE))
                .collect(),
        })
        .collect()
}

/// How far a mode picture exaggerates the displacement: the largest becomes this fraction of
/// the model's size.
const EXAGGERATION: f64 = 0.06;

/// The nodal-diameter content of a disc mode: the share of the out-of-plane motion of the
/// braking annulus in each number of nodal diameters.
#[derive(Clone, Debug, PartialEq)]
pub struct NodalDiameters {
    /// Nodal diameters of the largest share.
    pub dominant: usize,
    /// Share of the out-of-plane motion (0..1) with `dominant` nodal diameters.
    pub share: f64,
    /// RMS in-plane over RMS out-of-plane displacement of the annulus.
    pub in_plane_ratio: f64,
}

impl NodalDiameters {
    /// "4 nodal diameters (86 % of the annulus' out-of-plane motion), out-of-plane".
    pub fn describe(&self) -> String {
        format!(
            "{} nodal diameter{} ({:.0} % of the braking annulus' out-of-plane motion), {}",
            self.dominant,
            if self.dominant == 1 { "" } else { "s" },
            100.0 * self.share,
            if self.in_plane_ratio > 1.0 {
                format!(
                    "in-plane dominated (in-plane / out-of-plane = {:.2})",
                    self.in_plane_ratio
                )
            } else {
                format!(
                    "out-of-plane (in-plane / out-of-plane = {:.2})",
                    self.in_plane_ratio
                )
            }
        )
    }
}

/// Classifies a complex disc mode (`3 × nodes` complex displacements) by nodal diameters: the
/// normal (z) displacement of the disc nodes in the outer 45 % of its radius, averaged in 72
/// angle bins, Fourier-analysed over the angle (orders 0..=12, both travelling directions of a
/// complex mode counted). The disc's axis is z through the origin, as in the bundled meshes.
pub fn nodal_diameters(mesh: &Mesh, u: &[c64]) -> Option<NodalDiameters> {
    const BINS: usize = 72;
    const ORDERS: usize = 12;
    let rmax = mesh
        .nodes
        .iter()
        .map(|p| p[0].hypot(p[1]))
        .fold(0.0, f64::max);
    let mut sum = vec![c64::new(0.0, 0.0); BINS];
    let mut n = vec![0usize; BINS];
    let (mut inplane, mut outplane) = (0.0, 0.0);
    for (i, p) in mesh.nodes.iter().enumerate() {
        let r = p[0].hypot(p[1]);
        if r < 0.55 * rmax {
            continue;
        }
        let th = p[1].atan2(p[0]).rem_euclid(std::f64::consts::TAU);
        let b = ((th / std::f64::consts::TAU * BINS as f64) as usize).min(BINS - 1);
        sum[b] += u[3 * i + 2];
        n[b] += 1;
        inplane += u[3 * i].norm_sqr() + u[3 * i + 1].norm_sqr();
        outplane += u[3 * i + 2].norm_sqr();
    }
    if n.contains(&0) || outplane <= 0.0 {
        return None;
    }
    let w: Vec<c64> = sum.iter().zip(&n).map(|(s, &k)| s / k as f64).collect();
    let mut energy = [0.0; ORDERS + 1];
    for (order, e) in energy.iter_mut().enumerate() {
        for sign in [1.0, -1.0] {
            let mut c = c64::new(0.0, 0.0);
            for (b, v) in w.iter().enumerate() {
                let th = (b as f64 + 0.5) / BINS as f64 * std::f64::consts::TAU;
                let ph = -sign * order as f64 * th;
                c += v * c64::new(ph.cos(), ph.sin());
            }
            *e += c.norm_sqr();
            if order == 0 {
                break;
            }
        }
    }
    let total: f64 = energy.iter().sum();
    let (dominant, best) = energy
        .iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(NodalDiameters {
        dominant,
        share: best / total.max(f64::MIN_POSITIVE),
        in_plane_ratio: (inplane / outplane).sqrt(),
    })
}

/// A mode's picture and classification, as written.
pub struct ModePicture {
    /// The image, relative to the report folder.
    pub file: String,
    /// Each part's name and its largest displacement over the largest of all parts: each part
    /// is coloured on its own scale (its largest is yellow), so the caption says how they
    /// compare.
    pub peaks: Vec<(String, f64)>,
    /// The disc's nodal-diameter content.
    pub nodal: Option<NodalDiameters>,
}

/// Writes `dir/<stem>.png`: the real part of the complex mode `x` (reduced brake vector,
/// phase set so that its largest component is real) on both meshes, three views side by side
/// (three-quarter view of the brake, the disc from above without the pad, the brake from the
/// side), coloured by the displacement's magnitude over the largest of its own part, with a
/// colour bar underneath. One scale for all parts would be set by the part that moves most
/// (the pad, in the bundled brake's squeal mode) and leave the other dark: the disc's pattern,
/// its nodal diameters, would not show. The shape's exaggeration is common to all parts.
pub fn write_mode_picture(
    dir: &Path,
    stem: &str,
    m: &Model,
    meshes: &Meshes,
    x: &[c64],
) -> Result<ModePicture> {
    let parts = meshes.parts(m)?;
    let x = crate::shapes::normalize_mode(x);
    let re: Vec<f64> = x.iter().map(|v| v.re).collect();
    let im: Vec<f64> = x.iter().map(|v| v.im).collect();
    let (u_re, u_im) = (expand_parts(&parts, &re)?, expand_parts(&parts, &im)?);
    let peaks = part_peaks(&u_re);
    let umax = peaks
        .iter()
        .copied()
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let scale = EXAGGERATION * model_size(&parts) / umax;
    let tris: Vec<Vec<[u32; 3]>> = parts.iter().map(|p| boundary_triangles(p.mesh)).collect();
    let s = surfaces(&parts, &tris, &u_re, scale, &peaks);
    let (w, h) = (380, 300);
    let mut images = Vec::new();
    let all: Vec<_> = s.iter().collect();
    for (view, which) in [
        (View::ISO, all.clone()),
        (View::TOP, vec![&s[0]]),
        (side_view(&parts), all),
    ] {
        let b = screen_bounds(&which, &view).unwrap_or(([0.0, 0.0], [1.0, 1.0]));
        images.push(render(&which, &view, b, w, h));
    }
    let (row, rw, rh) = side_by_side(
        &images
            .iter()
            .map(|i| (i.as_slice(), w, h))
            .collect::<Vec<_>>(),
        8,
    );
    let (bar_row, bh) = colour_bar_with_scale(rw / 3, 12, "|u| / max |u| of its part")?;
    let mut img = row;
    // The colour bar, centred under the views, after a white gap.
    let gap = vec![255u8; 3 * (rw * 6) as usize];
    img.extend_from_slice(&gap);
    let pad = (rw - rw / 3) / 2;
    for y in 0..bh {
        let mut line = vec![255u8; 3 * rw as usize];
        let src = &bar_row[3 * (y * (rw / 3)) as usize..3 * ((y + 1) * (rw / 3)) as usize];
        line[3 * pad as usize..3 * pad as usize + src.len()].copy_from_slice(src);
        img.extend_from_slice(&line);
    }
    let height = rh + 6 + bh;
    let file = format!("{stem}.png");
    write_rgb_png(&dir.join(&file), &img, rw, height)?;
    let disc_u: Vec<c64> = u_re[0]
        .iter()
        .zip(&u_im[0])
        .map(|(a, b)| c64::new(*a, *b))
        .collect();
    Ok(ModePicture {
        file,
        peaks: parts
            .iter()
            .zip(&peaks)
            .map(|(p, &m)| (p.part.info.name.clone(), m / umax))
            .collect(),
        nodal: nodal_diameters(parts[0].mesh, &disc_u),
    })
}

/// Writes `dir/<stem>.png`, an animated PNG of the limit cycle: `frames` snapshots of the
/// oscillation about the mean (the CHBM Fourier series, eq 23) on both meshes in the
/// three-quarter view, exaggerated so that the largest displacement over the cycle is a few
/// per cent of the brake's size, coloured by its magnitude over the largest. Returns the file
/// name and the exaggeration factor.
pub fn write_cycle_animation(
    dir: &Path,
    stem: &str,
    m: &Model,
    meshes: &Meshes,
    s: &ChbmSolution,
    frames: usize,
) -> Result<(String, f64)> {
    let parts = meshes.parts(m)?;
    let n = m.brake.size();
    let h = s.harmonics;
    // The Fourier coefficients on the meshes once; each frame is their combination.
    let coeff = |b: usize| -> Vec<f64> { s.coeffs[b * n..(b + 1) * n].to_vec() };
    let expanded: Vec<Vec<Vec<f64>>> = (1..=2 * h)
        .map(|b| expand_parts(&parts, &coeff(b)))
        .collect::<Result<_>>()?;
    let frame_u = |th: f64| -> Vec<Vec<f64>> {
        (0..parts.len())
            .map(|p| {
                let len = expanded[0][p].len();
                let mut u = vec![0.0; len];
                for k in 1..=h {
                    let (c, sn) = ((k as f64 * th).cos(), (k as f64 * th).sin());
                    let (uc, us) = (&expanded[2 * k - 2][p], &expanded[2 * k - 1][p]);
                    for i in 0..len {
                        u[i] += c * uc[i] + sn * us[i];
                    }
                }
                u
            })
            .collect()
    };
    let us: Vec<Vec<Vec<f64>>> = (0..frames)
        .map(|f| frame_u(std::f64::consts::TAU * f as f64 / frames as f64))
        .collect();
    let umax = us
        .iter()
        .flatten()
        .flat_map(|u| (0..u.len() / 3).map(move |i| norm3(u, i)))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let scale = EXAGGERATION * model_size(&parts) / umax;
    let tris: Vec<Vec<[u32; 3]>> = parts.iter().map(|p| boundary_triangles(p.mesh)).collect();
    let undeformed = surfaces(
        &parts,
        &tris,
        &parts
            .iter()
            .map(|p| vec![0.0; 3 * p.mesh.num_nodes()])
            .collect::<Vec<_>>(),
        0.0,
        &vec![1.0; parts.len()],
    );
    let all: Vec<&Surface> = undeformed.iter().collect();
    let b = screen_bounds(&all, &View::ISO).unwrap_or(([0.0, 0.0], [1.0, 1.0]));
    let (w, hgt) = (480, 340);
    let images: Vec<Vec<u8>> = us
        .iter()
        .map(|u| {
            let s = surfaces(&parts, &tris, u, scale, &vec![umax; parts.len()]);
            render(&s.iter().collect::<Vec<_>>(), &View::ISO, b, w, hgt)
        })
        .collect();
    let file = format!("{stem}.png");
    write_apng(&dir.join(&file), &images, w, hgt, 80)?;
    Ok((file, scale))
}

#[cfg(test)]
mod tests {
    use super::*;
    use squeal_mesh::generate::box_tet10;

    /// A box of tet10 elements: its boundary triangles cover the six faces (area 2(ab+bc+ca))
    /// and no interior face.
    #[test]
    fn the_boundary_of_a_box_is_its_six_faces() {
        let mesh = box_tet10([2.0, 1.0, 0.5], [3, 2, 2]);
        let tris = boundary_triangles(&mesh);
        let area: f64 = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.nodes[i as usize]);
                let n = [
                    (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                    (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]),
                ];
                0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
            })
            .sum();
        let exact = 2.0 * (2.0 * 1.0 + 1.0 * 0.5 + 0.5 * 2.0);
        // Straight-sided elements: the split triangles tile each face exactly (round-off).
        assert!(
            (area / exact - 1.0).abs() < 1e-12,
            "area {area}, exact {exact}"
        );
    }

    /// An annulus of nodes carrying `cos(4θ)` out of the plane is a 4-nodal-diameter mode;
    /// a travelling wave `e^{-4iθ}` too, with all its motion in that order.
    #[test]
    fn a_cos_4_theta_field_has_4_nodal_diameters() {
        let mut mesh = Mesh::default();
        for k in 0..720 {
            let th = std::f64::consts::TAU * k as f64 / 720.0;
            for r in [0.6, 0.8, 1.0] {
                mesh.nodes.push([r * th.cos(), r * th.sin(), 0.0]);
            }
        }
        let field = |f: &dyn Fn(f64) -> c64| -> Vec<c64> {
            mesh.nodes
                .iter()
                .flat_map(|p| {
                    let th = p[1].atan2(p[0]);
                    [c64::new(0.0, 0.0), c64::new(0.0, 0.0), f(th)]
                })
                .collect()
        };
        let standing = field(&|th| c64::new((4.0 * th).cos(), 0.0));
        let nd = nodal_diameters(&mesh, &standing).unwrap();
        assert_eq!(nd.dominant, 4);
        // Bin averaging over 5 degrees loses sinc(4 * 2.5 deg) of the amplitude: the share
        // of order 4 stays above 0.99.
        assert!(nd.share > 0.99, "{nd:?}");
        assert!(nd.in_plane_ratio < 1e-12);
        let travelling = field(&|th| c64::new(0.0, -4.0 * th).exp());
        let nd = nodal_diameters(&mesh, &travelling).unwrap();
        assert_eq!(nd.dominant, 4);
        assert!(nd.share > 0.99, "{nd:?}");
    }
}

#[cfg(test)]
mod colour_scales {
    use super::*;

    /// Issue 22: the peaks that set each part's colour scale are each part's own. The bundled
    /// brake's squeal mode moves the pad most; one scale for both (the old picture) put the
    /// disc's largest at a small fraction of the bar, its pattern dark.
    #[test]
    fn each_part_has_its_own_peak() {
        // Disc nodes moving 3e-3 and 4e-3 (|u| = 5e-3 for the second), pad nodes up to 1.
        let disc = vec![3e-3, 0.0, 0.0, 0.0, 3e-3, 4e-3];
        let pad = vec![0.0, 0.0, 1.0, 0.6, 0.8, 0.0];
        assert_eq!(part_peaks(&[disc, pad]), [5e-3, 1.0]);
    }
}
