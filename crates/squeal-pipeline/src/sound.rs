//! How loud a limit cycle is (issue 23): the brake's surface velocity at each harmonic of a
//! cycle, and its sound by [`squeal_acoustics`]: the equivalent radiated power and the
//! A-weighted level at a microphone (Rayleigh integral and monopole sum; see that crate's docs
//! for what each neglects).
//!
//! **Velocity of a harmonic.** A cycle's coefficients are the paper's eq (25) over all brake
//! dofs, `x(t) = U_0 + Σ_k U_kc cos kωt + U_ks sin kωt` (CHBM's solution, or a branch point's
//! nonlinear dofs with the linear ones recovered by eq (35),
//! [`squeal_chbm::branch::full_cycle`]). With `x = Re(X_k e^{ikωt})`, `X_k = U_kc − i U_ks`,
//! the velocity amplitude is `V_k = i kω X_k = kω (U_ks + i U_kc)`. Each part's reduced
//! velocity is put back on its mesh by its Craig–Bampton basis `[T_C T_φ]` (eq 5), only on
//! the nodes of the radiating faces: `v = T_s V_k`, `T_s` the basis' rows of those nodes
//! (restrained dofs: zero), one product for all harmonics. The mean `U_0` does not radiate.
//!
//! **Radiating faces** ([`BrakeSurface::new`]): every boundary face of the disc, and every
//! boundary face of each pad but its friction face (pressed on the disc, not in air); the
//! scene's `[sound] radiating` keeps only the parts it names. The
//! pads' back plates are kept although the piston and the caliper cover part of them.
//!
//! **Microphone** ([`default_microphone`]): SAE J2521 places its microphone near the wheel of
//! the dynamometer; the position is not given in the public summaries of the standard this
//! module's author could consult, so the default is a choice: 0.5 m from the disc's centre,
//! 45° off the disc's axis (on the side the scene's axis points to) towards the first pad's
//! centroid. On the axis itself the modes with nodal diameters radiate nothing by symmetry;
//! off it they do. The Rayleigh integral takes only the faces that face the microphone
//! ([`Facing::TowardMicrophone`]).
//! Other microphones come from the pipeline's sound options (`Pipeline::sound`, the command
//! line's `--mic x,y,z`, checked by [`check_microphones`]): `squeal chbm` gives the level at
//! each, the branch and the report at the first.

use crate::error::{PipelineError, Result};
use crate::model::{Log, Model};
use crate::parts::{SceneParts, pad_key};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
use squeal_acoustics::{
    AcousticsError, Air, Complex64, FaceRule, Facing, Harmonic, RadiatingSurface, Sound, Velocity,
};
use squeal_element::geometry::{dot, unit_or_self as unit};
use squeal_mesh::Mesh;
use squeal_mesh::select::{self, Face};
use squeal_reduce::rom::ReducedPart;
use squeal_scene::Scene;
use std::collections::HashMap;
use std::ops::Range;

/// SAE J2521's squeal threshold: a peak level of at least 70 dB(A).
pub const SQUEAL_DBA: f64 = 70.0;

/// How the sound of a cycle is estimated.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SoundOptions {
    /// The air.
    pub air: Air,
    /// Microphones (m, the meshes' frame in SI); empty: [`default_microphone`].
    pub microphones: Vec<[f64; 3]>,
    /// Faces the Rayleigh integral takes at each microphone.
    pub facing: Facing,
}

impl SoundOptions {
    /// The scene's `[sound]`: its microphones (none: the default one) and its air.
    pub fn of_scene(scene: &Scene) -> Result<Self> {
        let s = scene.sound()?;
        let mut o = Self::default();
        o.air.density = s.air_density;
        o.air.speed_of_sound = s.speed_of_sound;
        o.microphones = s.microphones;
        Ok(o)
    }
}

impl Default for SoundOptions {
    fn default() -> Self {
        Self {
            air: Air::default(),
            microphones: Vec::new(),
            facing: Facing::TowardMicrophone,
        }
    }
}

/// One part's share of the radiating surface.
struct SurfacePart {
    /// The part's dofs in the brake.
    range: Range<usize>,
    /// Basis rows of its surface nodes: row `3 j + d` is direction `d` of its `j`-th surface
    /// node (zero where restrained), `3 nodes × reduced size`.
    rows: Mat<f64>,
    /// Index of its first surface node in the surface's node list.
    first_node: usize,
}

/// The brake's radiating surface with what puts a cycle's reduced velocity on it.
pub struct BrakeSurface {
    /// The faces and their quadrature points (6-node triangles, degree-4 rule).
    pub surface: RadiatingSurface,
    /// Each part's name and number of radiating faces, disc first.
    pub faces_per_part: Vec<(String, usize)>,
    /// The default microphone.
    pub microphone: [f64; 3],
    /// Each surface node's part (0 the disc, then the pads) and node index in that part's mesh.
    pub mesh_nodes: Vec<(usize, u32)>,
    parts: Vec<SurfacePart>,
}

impl BrakeSurface {
    /// The radiating faces of the brake of `m` (see the module docs) on the scene's meshes
    /// (read again, in SI, with the sets the reduction used), the basis rows of their nodes,
    /// and the default microphone.
    pub fn new(scene: &Scene, m: &Model, log: Log) -> Result<Self> {
        let sp = crate::parts::load_parts(scene, log)?;
        let mut nodes: Vec<[f64; 3]> = Vec::new();
        let mut faces: Vec<u32> = Vec::new();
        let mut quads: Vec<u32> = Vec::new();
        let mut parts = Vec::new();
        let mut faces_per_part = Vec::new();
        let mut mesh_nodes = Vec::new();
        let npads = sp.pads.len();
        let mut names = vec![("disc".to_string(), m.layout.disc.clone())];
        names.extend(m.layout.pads.iter().cloned());
        if let Some(keep) = scene.sound()?.radiating {
            if let Some(b) = keep.iter().find(|k| sp.bodies.iter().any(|b| b.0 == **k)) {
                return Err(PipelineError::input(
                    "[sound] radiating",
                    format!(
                        "the further part {b} does not radiate yet (the sound model takes the disc's and the pads' surfaces): leave it out of radiating"
                    ),
                ));
            }
            names.retain(|(n, _)| keep.contains(n));
        }
        if let Some(w) = crate::parts::left_out::left_out(&m.rom, "the sound's radiating surfaces")
        {
            log(&w);
        }
        for (name, range) in names {
            let mesh = &sp
                .part(&name)
                .ok_or_else(|| PipelineError::input("the radiating surface", missing(&name)))?
                .mesh;
            let rp = m.rom.part(&name).ok_or(PipelineError::NoPart {
                part: if name == "disc" { "disc" } else { "pad" },
            })?;
            let radiating = radiating_faces(&sp, mesh, &name, npads);
            let radiating_quads = crate::sound_quads::radiating_quads(&sp, mesh, &name, npads);
            let first_node = nodes.len();
            let (local, part_faces, part_quads) =
                crate::sound_quads::renumber(&radiating, &radiating_quads, first_node);
            nodes.extend(local.iter().map(|&n| mesh.nodes[n as usize]));
            mesh_nodes.extend(local.iter().map(|&n| (parts.len(), n)));
            faces.extend(part_faces);
            quads.extend(part_quads);
            parts.push(SurfacePart {
                rows: basis_rows(rp, mesh, &local)?,
                range,
                first_node,
            });
            faces_per_part.push((name, radiating.len() + radiating_quads.len()));
        }
        let surface = if quads.is_empty() {
            RadiatingSurface::new(&nodes, &faces, &FaceRule::tri6())
        } else {
            crate::sound_quads::mixed_surface(&nodes, &faces, &quads)
        }
        .map_err(acoustic)?;
        let microphone = default_microphone(scene, &sp)?;
        Ok(Self {
            surface,
            faces_per_part,
            microphone,
            mesh_nodes,
            parts,
        })
    }

    /// The nodal velocity amplitude of every surface node at each harmonic 1..=`harmonics`
    /// of a cycle with coefficients `coeffs` (eq 25 over the brake's dofs) at ω.
    pub fn velocities(
        &self,
        coeffs: &[f64],
        harmonics: usize,
        omega: f64,
    ) -> Result<Vec<Vec<[Complex64; 3]>>> {
        // The brake's dofs: the last part's range ends there unless `[sound] radiating` left
        // it out, so the size comes from the coefficients, checked against every part kept.
        let n = coeffs.len() / (2 * harmonics + 1);
        let fits = self.parts.iter().all(|p| p.range.end <= n);
        if !fits || coeffs.len() != (2 * harmonics + 1) * n {
            return Err(PipelineError::input(
                "the sound of a cycle",
                format!(
                    "{} coefficients for {harmonics} harmonics of {n} dofs",
                    coeffs.len()
                ),
            ));
        }
        let nodes = self.surface.node_count;
        let zero = Complex64::new(0.0, 0.0);
        let mut out = vec![vec![[zero; 3]; nodes]; harmonics];
        for p in &self.parts {
            // Columns 2(k−1), 2(k−1)+1: Re V_k, Im V_k of the part's reduced dofs.
            let x = Mat::<f64>::from_fn(p.range.len(), 2 * harmonics, |i, c| {
                let (k, im) = (c / 2 + 1, c % 2 == 1);
                let d = p.range.start + i;
                let kw = k as f64 * omega;
                if im {
                    kw * coeffs[(2 * k - 1) * n + d]
                } else {
                    kw * coeffs[2 * k * n + d]
                }
            });
            let mut y = Mat::<f64>::zeros(p.rows.nrows(), 2 * harmonics);
            matmul(
                y.as_mut(),
                Accum::Replace,
                p.rows.as_ref(),
                x.as_ref(),
                1.0,
                Par::Seq,
            );
            for k in 0..harmonics {
                for j in 0..p.rows.nrows() / 3 {
                    out[k][p.first_node + j] = std::array::from_fn(|d| {
                        Complex64::new(y[(3 * j + d, 2 * k)], y[(3 * j + d, 2 * k + 1)])
                    });
                }
            }
        }
        Ok(out)
    }

    /// The sound of a cycle: ERP and levels at each harmonic and overall, at the options'
    /// microphones (the default one when none is given).
    pub fn cycle_sound(
        &self,
        coeffs: &[f64],
        harmonics: usize,
        omega: f64,
        opts: &SoundOptions,
    ) -> Result<Sound> {
        let v = self.velocities(coeffs, harmonics, omega)?;
        let h: Vec<Harmonic> = v
            .iter()
            .enumerate()
            .map(|(k, v)| Harmonic {
                order: k + 1,
                omega: (k + 1) as f64 * omega,
                velocity: Velocity::Nodal(v),
            })
            .collect();
        let mics = self.microphones(opts);
        squeal_acoustics::sound(&opts.air, &self.surface, &h, &mics, opts.facing).map_err(acoustic)
    }

    /// The microphones of `opts`, or the default one when none is given.
    pub fn microphones(&self, opts: &SoundOptions) -> Vec<[f64; 3]> {
        if opts.microphones.is_empty() {
            vec![self.microphone]
        } else {
            opts.microphones.clone()
        }
    }

    /// The first microphone of `opts`, or the default one.
    pub fn first_microphone(&self, opts: &SoundOptions) -> [f64; 3] {
        opts.microphones.first().copied().unwrap_or(self.microphone)
    }

    /// The corners (least, greatest) of the box that bounds the radiating surface's points.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        self.surface.points.iter().fold(
            ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
            |(lo, hi), q| {
                (
                    std::array::from_fn(|d| lo[d].min(q.position[d])),
                    std::array::from_fn(|d| hi[d].max(q.position[d])),
                )
            },
        )
    }
}

fn missing(name: &str) -> String {
    format!("the scene has no part named {name}")
}

fn acoustic(e: AcousticsError) -> PipelineError {
    PipelineError::input("the sound of a cycle", e.to_string())
}

/// The disc's boundary faces; a pad's boundary faces without its friction face.
fn radiating_faces(sp: &SceneParts, mesh: &Mesh, name: &str, npads: usize) -> Vec<Face> {
    let boundary = select::boundary_faces(mesh);
    if name == "disc" {
        return boundary;
    }
    let friction = sp
        .set(&pad_key(0, name, npads))
        .map(|s| select::faces_of_set(mesh, &boundary, &s.nodes()))
        .unwrap_or_default();
    let mut skip: Vec<[u32; 3]> = friction.iter().map(sorted).collect();
    skip.sort_unstable();
    boundary
        .into_iter()
        .filter(|f| skip.binary_search(&sorted(f)).is_err())
        .collect()
}

fn sorted(f: &Face) -> [u32; 3] {
    let mut k = [f[0], f[1], f[2]];
    k.sort_unstable();
    k
}

/// The basis rows of `nodes` (mesh indices), three per node, zero where restrained.
fn basis_rows(part: &ReducedPart, mesh: &Mesh, nodes: &[u32]) -> Result<Mat<f64>> {
    let basis = part.basis.as_ref().ok_or_else(|| PipelineError::NoBasis {
        part: part.info.name.clone(),
    })?;
    let mut row_of: HashMap<(u64, u8), usize> = HashMap::with_capacity(basis.dof_node.len());
    for (r, (&n, &d)) in basis.dof_node.iter().zip(&basis.dof_dir).enumerate() {
        row_of.insert((n, d), r);
    }
    let cols = basis.values.ncols();
    let mut rows = Mat::<f64>::zeros(3 * nodes.len(), cols);
    for (j, &n) in nodes.iter().enumerate() {
        let id = mesh.node_ids[n as usize];
        for d in 0..3u8 {
            if let Some(&r) = row_of.get(&(id, d)) {
                for c in 0..cols {
                    rows[(3 * j + d as usize, c)] = basis.values[(r, c)];
                }
            }
        }
    }
    Ok(rows)
}

/// 0.5 m from the disc's centre, 45° off its axis towards the first pad (see the module
/// docs). The centre is the disc's node centroid projected onto the axis.
pub fn default_microphone(scene: &Scene, sp: &SceneParts) -> Result<[f64; 3]> {
    let axis = crate::model::scene_axis(scene)?;
    let a = unit(axis.direction);
    let centroid = |m: &Mesh| {
        let k = m.nodes.len().max(1) as f64;
        m.nodes
            .iter()
            .fold([0.0; 3], |c, x| std::array::from_fn(|d| c[d] + x[d] / k))
    };
    let cd = centroid(&sp.disc.mesh);
    let rel: [f64; 3] = std::array::from_fn(|d| cd[d] - axis.origin[d]);
    let t = dot(rel, a);
    let centre: [f64; 3] = std::array::from_fn(|d| axis.origin[d] + t * a[d]);
    let radial = sp.pads.first().map_or([0.0; 3], |(_, p)| {
        let cp = centroid(&p.mesh);
        let r: [f64; 3] = std::array::from_fn(|d| cp[d] - centre[d]);
        let along = dot(r, a);
        unit(std::array::from_fn(|d| r[d] - along * a[d]))
    });
    let dir = unit(std::array::from_fn(|d| a[d] + radial[d]));
    Ok(std::array::from_fn(|d| centre[d] + 0.5 * dir[d]))
}

/// One line on a cycle's sound, as `squeal chbm` prints it.
pub fn sound_text(s: &Sound, surface: &BrakeSurface, mic: [f64; 3]) -> String {
    let lr = s.rayleigh_dba.first().copied().unwrap_or(f64::NAN);
    let lm = s.monopole_dba.first().copied().unwrap_or(f64::NAN);
    let per: Vec<String> = s
        .harmonics
        .iter()
        .map(|h| format!("H{} {:.1} dB", h.order, squeal_acoustics::power_db(h.erp_w)))
        .collect();
    format!(
        "  sound: {lr:.1} dB(A) at the microphone ({:.3}, {:.3}, {:.3}) m by the Rayleigh integral ({lm:.1} dB(A) by the monopole sum){}; ERP {:.1} dB re 1 pW ({:.1} dB(A); {}) over {} faces\n",
        mic[0],
        mic[1],
        mic[2],
        if lr >= SQUEAL_DBA {
            ", squeal by SAE J2521's 70 dB(A)"
        } else {
            ", below SAE J2521's 70 dB(A)"
        },
        s.erp_db,
        s.erp_dba,
        per.join(", "),
        surface.surface.face_count()
    )
}

/// The A-weighted level (Rayleigh integral, dB(A)) at the first microphone of `opts` (the
/// default one when none is given) of every cycle of a branch: each cycle's coefficients of
/// all dofs recovered by eq (35) at its own μ ([`squeal_chbm::branch::full_cycle`] on
/// `samples` AFT samples), then [`BrakeSurface::cycle_sound`].
pub fn branch_levels(
    surface: &BrakeSurface,
    m: &Model,
    st: &squeal_brake::analysis::LinearStability,
    a: &crate::branch::BranchAnalysis,
    samples: Option<usize>,
    opts: &SoundOptions,
) -> Result<Vec<f64>> {
    let mb = squeal_brake::modal_brake::ModalBrake::new(&m.brake, &st.reference, a.mu0());
    let opts = SoundOptions {
        microphones: vec![surface.first_microphone(opts)],
        ..opts.clone()
    };
    a.branch
        .points
        .iter()
        .map(|p| {
            let c = squeal_chbm::branch::full_cycle(&mb, p, samples)?;
            let s = surface.cycle_sound(&c, p.harmonics, p.omega, &opts)?;
            Ok(s.rayleigh_dba[0])
        })
        .collect()
}

/// Where the branch's stable cycles reach SAE J2521's 70 dB(A) at the microphone: one line.
pub fn squeal_level_text(a: &crate::branch::BranchAnalysis, levels: &[f64]) -> String {
    use squeal_chbm::floquet::CycleStability as Stability;
    let at = a.microphone.map_or(String::new(), |m| {
        format!(" ({:.3}, {:.3}, {:.3}) m", m[0], m[1], m[2])
    });
    let loud: Vec<f64> = a
        .branch
        .points
        .iter()
        .zip(levels)
        .enumerate()
        .filter(|(i, (_, l))| **l >= SQUEAL_DBA && a.stability(*i) == Some(Stability::Stable))
        .map(|(_, (p, _))| p.parameter)
        .collect();
    let top = levels
        .iter()
        .enumerate()
        .max_by(|x, y| x.1.total_cmp(y.1))
        .map(|(i, l)| (a.branch.points[i].parameter, *l));
    let range = match (
        loud.iter().copied().reduce(f64::min),
        loud.iter().copied().reduce(f64::max),
    ) {
        (Some(lo), Some(hi)) => format!(
            "above {SQUEAL_DBA} dB(A) from mu = {lo:.6} to {hi:.6} (stable cycles of the computed branch)"
        ),
        _ => format!("no stable cycle of the computed branch reaches {SQUEAL_DBA} dB(A)"),
    };
    let top = top.map_or(String::new(), |(mu, l)| {
        format!("; loudest {l:.1} dB(A) at mu = {mu:.6}")
    });
    format!(
        "sound at the microphone{at} (Rayleigh integral, SAE J2521 squeal from {SQUEAL_DBA} dB(A)): {range}{top}\n"
    )
}

/// The lines `squeal chbm` prints on a CHBM solution's sound, one per microphone of `opts`
/// (the default one when none is given), or why it was not computed.
pub fn solution_sound_text(
    scene: &Scene,
    m: &Model,
    sol: &squeal_chbm::ChbmSolution,
    opts: &SoundOptions,
    log: Log,
) -> String {
    let text = BrakeSurface::new(scene, m, log).and_then(|s| {
        let mut out = String::new();
        for mic in s.microphones(opts) {
            let one = SoundOptions {
                microphones: vec![mic],
                ..opts.clone()
            };
            let snd = s.cycle_sound(&sol.coeffs, sol.harmonics, sol.omega, &one)?;
            out += &sound_text(&snd, &s, mic);
        }
        Ok(out)
    });
    text.unwrap_or_else(|e| format!("  sound: not computed: {e}\n"))
}

/// [`branch_levels`] on the scene's radiating surface, with the microphone they are taken
/// at; empty (with the reason logged) when they cannot be computed, e.g. a reduced model kept
/// without its bases.
pub fn branch_levels_or_log(
    scene: &Scene,
    m: &Model,
    st: &squeal_brake::analysis::LinearStability,
    a: &crate::branch::BranchAnalysis,
    samples: Option<usize>,
    opts: &SoundOptions,
    log: Log,
) -> (Vec<f64>, Option<[f64; 3]>) {
    BrakeSurface::new(scene, m, log)
        .and_then(|s| {
            let levels = branch_levels(&s, m, st, a, samples, opts)?;
            Ok((levels, Some(s.first_microphone(opts))))
        })
        .unwrap_or_else(|e| {
            log(&format!("sound of the branch's cycles not computed: {e}"));
            (Vec::new(), None)
        })
}

/// Checks microphones given on the command line against the brake of `m` before any long
/// computation: each must lie in the air around the brake, outside the box that bounds its
/// radiating surface (inside it the Rayleigh integral over the faces that face it and the
/// monopole sum have no meaning).
pub fn check_microphones(scene: &Scene, m: &Model, mics: &[[f64; 3]], log: Log) -> Result<()> {
    if mics.is_empty() {
        return Ok(());
    }
    let s = BrakeSurface::new(scene, m, log)?;
    let (lo, hi) = s.bounds();
    for (k, mic) in mics.iter().enumerate() {
        if (0..3).all(|d| lo[d] <= mic[d] && mic[d] <= hi[d]) {
            return Err(PipelineError::input(
                "--mic",
                format!(
                    "microphone {} at ({}, {}, {}) m is inside the brake's bounds x {:.3}..{:.3}, y {:.3}..{:.3}, z {:.3}..{:.3} m (the meshes' frame in metres): place it in the air around the brake, e.g. the default ({:.3}, {:.3}, {:.3}) m, 0.5 m from the disc's centre",
                    k + 1,
                    mic[0],
                    mic[1],
                    mic[2],
                    lo[0],
                    hi[0],
                    lo[1],
                    hi[1],
                    lo[2],
                    hi[2],
                    s.microphone[0],
                    s.microphone[1],
                    s.microphone[2]
                ),
            ));
        }
    }
    Ok(())
}

/// A microphone position from the command line: `x,y,z` in metres (three finite numbers).
pub fn parse_microphone(text: &str) -> std::result::Result<[f64; 3], String> {
    let usage = "give the microphone's position as three numbers in metres separated by commas, x,y,z, in the meshes' frame (e.g. --mic 0.35,0,0.35); repeat --mic for more microphones";
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("'{text}' has {} value(s): {usage}", parts.len()));
    }
    let mut out = [0.0; 3];
    for (d, p) in parts.iter().enumerate() {
        out[d] = match p.parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => return Err(format!("'{p}' in '{text}' is not a finite number: {usage}")),
        };
    }
    Ok(out)
}
