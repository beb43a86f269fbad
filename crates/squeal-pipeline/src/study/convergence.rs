//! The convergence study (`squeal study --kind convergence`, issue 20 item 4): does the Hopf
//! point μ0 stop moving when the numerical knobs the user takes for settings are refined?
//!
//! From the scene's own settings (the base), one knob at a time is refined through levels:
//! - **contact**: the patch grid (3 × 3 → 3 × 5 → 5 × 5 by default, `[sets] patch_grid`), with
//!   nodal contact (every pad face node paired with its projection on the disc face) as the
//!   limit of ever finer patches;
//! - **modes**: the fixed-interface modes kept per part, ×1, ×1.5, ×2 of the scene's count;
//! - **mesh**: the mesh level (coarse → medium → fine), found like the mesh study finds it,
//!   from the `_<level>` suffix of the scene's mesh files.
//!
//! Each level is a typed variant of the scene ([`Scene::variant`] and its setters), reduced
//! (cached in `<out>/study/convergence/`) and swept over the same friction values. Its row
//! gives μ0 and its frequency, the growth rate `Re λ` of the branch that goes unstable at a
//! chosen μ (linear between the sweep's values), and the unstable mode's identity at μ0: its
//! MAC against the previous level's, its nodal diameters (the dominant circumferential order
//! of the disc's out-of-plane motion on the braking face's mid-radius circle) and the share
//! of its kinetic energy in each part (`x^H M_p x / x^H M x`, [`energy_share`]).
//!
//! **The MAC across levels.** The reduced coordinates of two levels do not compare (other
//! modes, other interface dofs), so both shapes are recovered on the disc's contact-face nodes
//! (`u = Ψ x` with each level's Craig–Bampton basis) and compared there:
//! `MAC = |Σ_i a_i^H b_j(i)|² / (Σ_i |a_i|² Σ_i |b_j(i)|²)`, where node `i` of the previous
//! level's face is paired with the nearest node `j(i)` of this level's face (the same node on
//! the same mesh; on a finer mesh the nearest one, which on the bundled nested meshes is the
//! same point). The MAC of complex shapes is invariant to their scaling and phase.
//!
//! Each knob gets a verdict from its μ0 sequence ([`super::verdict`]): converged when the
//! estimated error of the last level's μ0 (its last change, or with three levels what the
//! observed rate says is still to come, when that is larger) is below the tolerance (0.1 % by
//! default) and the same mode goes unstable; with three levels the observed rate and the
//! extrapolated μ0 with its uncertainty. The overall verdict is converged when every knob is,
//! and names each knob that is not with its spread (`mu0 ± error`).

use super::coupled::{face_set, rings, summarize};
use super::create_dir;
use super::verdict::{self, DEFAULT_TOLERANCE, KnobVerdict};
use crate::error::{Context, PipelineError, Result};
use crate::model::{Log, Model, build};
use crate::shapes::expand_complex;
use faer::c64;
use squeal_brake::analysis::{LinearStability, stability_with};
use squeal_brake::studies::{Case, energy_share, outcome};
use squeal_scene::{CycleFriction, Interface, MESH_LEVELS, Scene};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

mod output;

/// A knob of the study.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Knob {
    Contact,
    Modes,
    Mesh,
}

impl Knob {
    /// Every knob, in the study's order.
    pub const ALL: [Knob; 3] = [Knob::Contact, Knob::Modes, Knob::Mesh];

    pub fn name(self) -> &'static str {
        match self {
            Knob::Contact => "contact",
            Knob::Modes => "modes",
            Knob::Mesh => "mesh",
        }
    }

    /// A knob by its name (`contact`, `modes`, `mesh`).
    pub fn parse(s: &str) -> std::result::Result<Knob, String> {
        Knob::ALL
            .into_iter()
            .find(|k| k.name() == s.trim())
            .ok_or_else(|| format!("\"{s}\" is not a knob: give contact, modes or mesh"))
    }
}

/// A contact discretization: a patch grid (radial × angular), node or nodal contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactLevel {
    Patches([usize; 2]),
    Node,
    Nodal,
}

impl ContactLevel {
    /// `3x5` (radial x angular patches), `node` or `nodal`.
    pub fn parse(s: &str) -> std::result::Result<ContactLevel, String> {
        let s = s.trim();
        match s {
            "nodal" => return Ok(ContactLevel::Nodal),
            "node" => return Ok(ContactLevel::Node),
            _ => {}
        }
        let bad = || {
            format!(
                "\"{s}\" is not a contact level: give a patch grid such as 3x5 (radial x angular), or nodal"
            )
        };
        let (r, a) = s.split_once(['x', 'X']).ok_or_else(bad)?;
        let n = |t: &str| t.trim().parse::<usize>().ok().filter(|v| *v > 0);
        Ok(ContactLevel::Patches([
            n(r).ok_or_else(bad)?,
            n(a).ok_or_else(bad)?,
        ]))
    }

    /// `3x5 patches`, `node`, `nodal`.
    pub fn label(self) -> String {
        match self {
            ContactLevel::Patches([r, a]) => format!("{r}x{a} patches"),
            ContactLevel::Node => "node".into(),
            ContactLevel::Nodal => "nodal".into(),
        }
    }

    fn key(self) -> String {
        match self {
            ContactLevel::Patches([r, a]) => format!("p{r}x{a}"),
            ContactLevel::Node => "node".into(),
            ContactLevel::Nodal => "nodal".into(),
        }
    }

    /// The scene's own contact discretization.
    fn of(scene: &Scene) -> Result<ContactLevel> {
        Ok(match scene.interface()? {
            Interface::Patch => ContactLevel::Patches(scene.patch_grid()?),
            Interface::Node => ContactLevel::Node,
            Interface::Nodal => ContactLevel::Nodal,
        })
    }

    /// The default refinements after this one: two finer grids, then nodal contact.
    fn refinements(self) -> Vec<ContactLevel> {
        match self {
            ContactLevel::Patches([r, a]) => vec![
                ContactLevel::Patches([r, a + 2]),
                ContactLevel::Patches([r + 2, a + 2]),
                ContactLevel::Nodal,
            ],
            ContactLevel::Node => vec![ContactLevel::Nodal],
            ContactLevel::Nodal => Vec::new(),
        }
    }
}

/// What the study refines and how it judges.
#[derive(Clone, Debug)]
pub struct Options {
    /// The knobs to refine, in order.
    pub knobs: Vec<Knob>,
    /// The contact levels after the scene's own (`None`: two finer grids, 3 x 3 -> 3 x 5 -> 5 x 5,
    /// then nodal contact).
    pub contacts: Option<Vec<ContactLevel>>,
    /// Factors on the scene's kept modes after ×1.
    pub mode_factors: Vec<f64>,
    /// The mesh levels, the first being the base of every knob; empty: the scene's own level,
    /// then each finer one of [`MESH_LEVELS`] whose files exist.
    pub levels: Vec<String>,
    /// The friction of the growth-rate column (`None`: the scene's `[chbm]` friction, a ratio
    /// of it taken on the base level's μ0).
    pub growth_mu: Option<f64>,
    /// Estimated relative error of the last level's μ0 below which a knob has converged
    /// ([`super::verdict`]).
    pub tolerance: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            knobs: Knob::ALL.to_vec(),
            contacts: None,
            mode_factors: vec![1.5, 2.0],
            levels: Vec::new(),
            growth_mu: None,
            tolerance: DEFAULT_TOLERANCE,
        }
    }
}

/// A point in the knobs' space: what one level computes.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    pub contact: ContactLevel,
    pub modes: usize,
    /// The mesh level, when the scene's meshes have one.
    pub level: Option<String>,
}

impl Setting {
    fn key(&self) -> String {
        format!(
            "{}{}_m{}",
            self.level
                .as_ref()
                .map_or(String::new(), |l| format!("{l}_")),
            self.contact.key(),
            self.modes
        )
    }

    /// The label of this setting in a knob's rows.
    fn label(&self, knob: Knob, base_modes: usize) -> String {
        match knob {
            Knob::Contact => self.contact.label(),
            Knob::Modes => format!(
                "{} modes (x{})",
                self.modes,
                fmt_factor(self.modes as f64 / base_modes as f64)
            ),
            Knob::Mesh => self.level.clone().unwrap_or_else(|| "scene's".into()),
        }
    }

    /// The scene of this setting: a typed variant, its reduced model kept in `dir`.
    fn scene(&self, scene: &Scene, dir: &Path) -> Result<Scene> {
        let mut v = scene.variant()?;
        if let Some(l) = &self.level {
            v.set_mesh_level(l)?;
        }
        match self.contact {
            ContactLevel::Patches(g) => {
                v.set_interface(Interface::Patch);
                v.set_patch_grid(g)?;
            }
            ContactLevel::Node => v.set_interface(Interface::Node),
            ContactLevel::Nodal => v.set_interface(Interface::Nodal),
        }
        v.set_modes(self.modes);
        v.set_rom(&dir.join(format!("brake_{}.rom", self.key())));
        Ok(v)
    }
}

fn fmt_factor(f: f64) -> String {
    let s = format!("{f:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The levels of each knob (the base first), and the distinct settings to compute.
#[derive(Clone, Debug)]
pub struct Plan {
    pub base: Setting,
    pub knobs: Vec<(Knob, Vec<Setting>)>,
}

impl Plan {
    /// Every distinct setting, the base first.
    pub fn settings(&self) -> Vec<Setting> {
        let mut all = vec![self.base.clone()];
        for (_, levels) in &self.knobs {
            for s in levels {
                if !all.contains(s) {
                    all.push(s.clone());
                }
            }
        }
        all
    }
}

/// The mesh levels of the study: `levels`, or the scene's own and the finer ones on disk.
fn mesh_levels(scene: &Scene, levels: &[String]) -> Result<Vec<Option<String>>> {
    if !levels.is_empty() {
        for l in levels {
            // Every level's files must exist before the first, slow, reduction.
            scene.variant()?.set_mesh_level(l)?;
        }
        return Ok(levels.iter().cloned().map(Some).collect());
    }
    let Some(own) = scene.mesh_level()? else {
        return Ok(vec![None]);
    };
    let mut out = vec![Some(own.clone())];
    if let Some(i) = MESH_LEVELS.iter().position(|l| *l == own) {
        for l in &MESH_LEVELS[i + 1..] {
            let files = scene.level_mesh_files(l)?;
            if files.iter().all(|p| p.is_file()) {
                out.push(Some(l.to_string()));
            }
        }
    }
    Ok(out)
}

/// The study's plan: the base (the scene's settings at the first mesh level) and each knob's
/// levels.
pub fn plan(scene: &Scene, opts: &Options) -> Result<Plan> {
    if opts.knobs.is_empty() {
        return Err(PipelineError::input(
            "--knobs",
            "give at least one knob (contact, modes, mesh)",
        ));
    }
    if !(opts.tolerance > 0.0 && opts.tolerance < 1.0) {
        return Err(PipelineError::input(
            "--tolerance",
            format!(
                "{} is not a relative tolerance: give one between 0 and 1 (e.g. 0.01 for 1 %)",
                opts.tolerance
            ),
        ));
    }
    let levels = mesh_levels(scene, &opts.levels)?;
    let modes = scene.modes_per_part();
    let base = Setting {
        contact: ContactLevel::of(scene)?,
        modes,
        level: levels[0].clone(),
    };
    let mut knobs = Vec::new();
    for &knob in &opts.knobs {
        let mut list = vec![base.clone()];
        let mut add = |s: Setting| {
            if !list.contains(&s) {
                list.push(s);
            }
        };
        match knob {
            Knob::Contact => {
                let contacts = opts
                    .contacts
                    .clone()
                    .unwrap_or_else(|| base.contact.refinements());
                for c in contacts {
                    add(Setting {
                        contact: c,
                        ..base.clone()
                    });
                }
            }
            Knob::Modes => {
                for &f in &opts.mode_factors {
                    if !(f.is_finite() && f > 0.0) {
                        return Err(PipelineError::input(
                            "--mode-factors",
                            format!(
                                "{f} is not a factor on the kept modes: give positive numbers such as 1.5,2"
                            ),
                        ));
                    }
                    add(Setting {
                        modes: ((modes as f64) * f).round().max(1.0) as usize,
                        ..base.clone()
                    });
                }
            }
            Knob::Mesh => {
                for l in &levels[1..] {
                    add(Setting {
                        level: l.clone(),
                        ..base.clone()
                    });
                }
            }
        }
        knobs.push((knob, list));
    }
    Ok(Plan { base, knobs })
}

/// The unstable mode of a level at μ0, recovered on the meshes.
#[derive(Clone, Debug)]
pub struct Shape {
    /// The disc's contact-face nodes: position and (complex) displacement.
    pub face: Vec<([f64; 3], [c64; 3])>,
    /// Dominant circumferential order on the braking face (`None` when the face has too few
    /// nodes on its mid-radius circle to say).
    pub nodal_diameters: Option<usize>,
    /// Share of the kinetic energy in each part (disc, then the pads).
    pub energy: Vec<(String, f64)>,
}

/// What one level gives.
#[derive(Clone, Debug)]
pub struct LevelResult {
    pub setting: Setting,
    /// Reduced dofs of the brake.
    pub dofs: usize,
    /// Mesh nodes of all parts.
    pub nodes: usize,
    /// ContactLevel pairs.
    pub pairs: usize,
    pub mu0: Option<f64>,
    pub frequency_hz: Option<f64>,
    /// The unstable branch's `(μ, Re λ)` over the sweep.
    pub branch: Vec<(f64, f64)>,
    pub shape: Option<Shape>,
    /// Why there is no μ0: no Hopf point in the band (a result), or a failure.
    pub note: Option<String>,
}

impl LevelResult {
    /// `Re λ` of the unstable branch at `mu`, linear between the sweep's values (`None`
    /// outside them or without a branch).
    pub fn growth_at(&self, mu: f64) -> Option<f64> {
        let b = &self.branch;
        b.windows(2)
            .find(|w| w[0].0 <= mu && mu <= w[1].0)
            .map(|w| {
                if w[1].0 == w[0].0 {
                    w[0].1
                } else {
                    w[0].1 + (w[1].1 - w[0].1) * (mu - w[0].0) / (w[1].0 - w[0].0)
                }
            })
    }
}

/// MAC of two shapes on the disc's contact face, each node of `a` paired with the nearest node
/// of `b`; `None` when either has no face nodes or no motion there.
pub fn face_mac(a: &Shape, b: &Shape) -> Option<f64> {
    if a.face.is_empty() || b.face.is_empty() {
        return None;
    }
    let d2 = |p: [f64; 3], q: [f64; 3]| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>();
    let (mut cross, mut na, mut nb) = (c64::new(0.0, 0.0), 0.0, 0.0);
    for (p, u) in &a.face {
        let (_, v) = b
            .face
            .iter()
            .min_by(|x, y| d2(*p, x.0).total_cmp(&d2(*p, y.0)))?;
        for k in 0..3 {
            cross += u[k].conj() * v[k];
            na += u[k].norm_sqr();
            nb += v[k].norm_sqr();
        }
    }
    (na > 0.0 && nb > 0.0).then(|| cross.norm_sqr() / (na * nb))
}

/// The unstable mode at μ0 of a swept model, on the meshes.
fn unstable_shape(s: &Model, st: &LinearStability, log: Log) -> Result<Option<Shape>> {
    let Some(h) = &st.sweep.hopf else {
        return Ok(None);
    };
    let x = h.point.spectrum.shape(&st.reference.basis, h.index);
    let disc = s.read_mesh(&s.disc_mesh, log)?;
    let dp = s
        .rom
        .part("disc")
        .ok_or(PipelineError::NoPart { part: "disc" })?;
    let ud = expand_complex(dp, &disc, &s.disc_mesh, &x[s.layout.disc.clone()])?;
    let face = face_set(dp, &disc)?
        .iter()
        .map(|&i| {
            let i = i as usize;
            (disc.nodes[i], [ud[3 * i], ud[3 * i + 1], ud[3 * i + 2]])
        })
        .collect();
    let mut energy = vec![(
        "disc".to_string(),
        energy_share(&s.brake.m, &x, s.layout.disc.clone()),
    )];
    for (name, range) in &s.layout.pads {
        energy.push((name.clone(), energy_share(&s.brake.m, &x, range.clone())));
    }
    let nodal_diameters = match s.pad_meshes.first() {
        Some((_, p)) => {
            let pad = s.read_mesh(p, log)?;
            // A face too sparse for the circle leaves the column empty, not the study failed.
            match rings(&s.rom, &disc, &pad) {
                Ok(r) => {
                    Some(summarize(s, (&disc, &pad), &r, &x, h.frequency_hz)?.nodal_diameters())
                }
                Err(e) => {
                    log(&format!("  nodal diameters not measured: {e}"));
                    None
                }
            }
        }
        None => None,
    };
    Ok(Some(Shape {
        face,
        nodal_diameters,
        energy,
    }))
}

/// Reduces and sweeps one level.
fn compute_level(
    scene: &Scene,
    setting: &Setting,
    dir: &Path,
    mus: &[f64],
    log: Log,
) -> Result<LevelResult> {
    let v = setting.scene(scene, dir)?;
    let s = build(&v, dir, log).with_context(|| format!("level {}", setting.key()))?;
    let mut r = LevelResult {
        setting: setting.clone(),
        dofs: s.rom.size(),
        nodes: s.rom.parts.iter().map(|p| p.info.mesh.nodes).sum(),
        pairs: s.brake.pairs.len(),
        mu0: None,
        frequency_hz: None,
        branch: Vec::new(),
        shape: None,
        note: None,
    };
    // A line per tenth of each sweep (a nodal level's sweeps take minutes).
    let tenth = AtomicUsize::new(usize::MAX);
    let tell = |done: usize, total: usize| {
        let t = done * 10 / total.max(1);
        if tenth.swap(t, Ordering::Relaxed) != t {
            log(&format!("  sweep: {done}/{total} friction values"));
        }
    };
    let st = match stability_with(&s.brake, &s.damping, mus, &s.sweep, &tell)
        .with_context(|| format!("level {}", setting.key()))
    {
        Ok(st) => st,
        Err(e) => {
            let none = super::no_hopf_point(&e);
            r.note = Some(if none {
                format!("no Hopf point in the band ({e})")
            } else {
                format!("the analysis failed: {e}")
            });
            return Ok(r);
        }
    };
    let o = outcome(&Case::default(), &st);
    r.mu0 = o.mu0;
    r.frequency_hz = o.frequency_hz;
    if let Some(u) = &o.unstable {
        r.branch =
            u.mu.iter()
                .zip(&u.values)
                .map(|(m, v)| (*m, v.re))
                .collect();
    }
    if r.mu0.is_none() {
        r.note = Some("no Hopf point in the band".into());
    }
    r.shape = unstable_shape(&s, &st, log)?;
    Ok(r)
}

/// One knob's levels and verdict.
#[derive(Clone, Debug)]
pub struct KnobResult {
    pub knob: Knob,
    /// Indices into [`Study::levels`], the base first.
    pub levels: Vec<usize>,
    /// MAC of each level's unstable mode against the previous level's (`None` for the first).
    pub mac: Vec<Option<f64>>,
    pub verdict: KnobVerdict,
}

/// The whole study.
#[derive(Clone, Debug)]
pub struct Study {
    pub levels: Vec<LevelResult>,
    pub knobs: Vec<KnobResult>,
    pub base_modes: usize,
    /// The friction of the growth-rate column.
    pub growth_mu: Option<f64>,
    pub tolerance: f64,
    pub overall: (verdict::Status, String),
}

/// The friction of the growth column: the option, else the scene's limit-cycle friction.
fn growth_mu(scene: &Scene, opts: &Options, base_mu0: Option<f64>) -> Result<Option<f64>> {
    if let Some(m) = opts.growth_mu {
        return Ok(Some(m));
    }
    Ok(match scene.cycle()?.at {
        CycleFriction::Mu(m) => Some(m),
        CycleFriction::Ratio(r) => base_mu0.map(|m| r * m),
    })
}

/// Judges the computed levels knob by knob.
pub fn judge(
    plan: &Plan,
    levels: Vec<LevelResult>,
    growth_mu: Option<f64>,
    tolerance: f64,
) -> Study {
    let mut knobs = Vec::new();
    for (knob, settings) in &plan.knobs {
        let idx: Vec<usize> = settings
            .iter()
            .filter_map(|s| levels.iter().position(|l| l.setting == *s))
            .collect();
        let mac: Vec<Option<f64>> = idx
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let prev = idx.get(k.wrapping_sub(1))?;
                face_mac(levels[*prev].shape.as_ref()?, levels[i].shape.as_ref()?)
            })
            .collect();
        let mu0: Vec<Option<f64>> = idx.iter().map(|&i| levels[i].mu0).collect();
        let verdict = verdict::verdict(&mu0, mac.last().copied().flatten(), tolerance);
        knobs.push(KnobResult {
            knob: *knob,
            levels: idx,
            mac,
            verdict,
        });
    }
    let named: Vec<(&str, &KnobVerdict)> =
        knobs.iter().map(|k| (k.knob.name(), &k.verdict)).collect();
    let overall = verdict::overall(&named);
    Study {
        base_modes: plan.base.modes,
        levels,
        knobs,
        growth_mu,
        tolerance,
        overall,
    }
}

/// Runs the convergence study of a scene over the friction values `mus` and writes its table
/// (`convergence.csv`, `.md`), `convergence.json` and figure to `<out>/study`.
pub fn run(scene: &Scene, out: &Path, mus: &[f64], opts: &Options, log: Log) -> Result<Study> {
    let plan = plan(scene, opts)?;
    let dir = out.join("study");
    let rdir = dir.join("convergence");
    create_dir(&rdir)?;
    let settings = plan.settings();
    log(&format!(
        "convergence study: {} levels ({}), each reduced and swept over {} friction values",
        settings.len(),
        plan.knobs
            .iter()
            .map(|(k, l)| format!("{} {}", k.name(), l.len()))
            .collect::<Vec<_>>()
            .join(", "),
        mus.len()
    ));
    let mut levels = Vec::new();
    for (i, s) in settings.iter().enumerate() {
        let t = Instant::now();
        log(&format!(
            "level {}/{}: {} ...",
            i + 1,
            settings.len(),
            s.key()
        ));
        let r = compute_level(scene, s, &rdir, mus, log)?;
        log(&format!(
            "level {}/{}: {} dofs, {} contact pairs, mu0 = {} at {} Hz ({:.1} s)",
            i + 1,
            settings.len(),
            r.dofs,
            r.pairs,
            r.mu0.map_or("none".into(), |m| format!("{m:.6}")),
            r.frequency_hz.map_or("-".into(), |f| format!("{f:.1}")),
            t.elapsed().as_secs_f64()
        ));
        levels.push(r);
    }
    let gmu = growth_mu(scene, opts, levels.first().and_then(|l| l.mu0))?;
    let study = judge(&plan, levels, gmu, opts.tolerance);
    output::write(&study, &dir, log)?;
    Ok(study)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_levels_parse_and_refine() {
        assert_eq!(
            ContactLevel::parse("3x5"),
            Ok(ContactLevel::Patches([3, 5]))
        );
        assert_eq!(ContactLevel::parse(" nodal "), Ok(ContactLevel::Nodal));
        assert!(ContactLevel::parse("3x0").is_err() && ContactLevel::parse("five").is_err());
        assert_eq!(
            ContactLevel::Patches([3, 3]).refinements(),
            vec![
                ContactLevel::Patches([3, 5]),
                ContactLevel::Patches([5, 5]),
                ContactLevel::Nodal
            ]
        );
        assert_eq!(fmt_factor(1.5), "1.5");
        assert_eq!(fmt_factor(2.0), "2");
    }

    fn shape(face: Vec<([f64; 3], [c64; 3])>) -> Shape {
        Shape {
            face,
            nodal_diameters: None,
            energy: Vec::new(),
        }
    }

    #[test]
    fn the_face_mac_ignores_scale_and_phase_and_sees_another_shape() {
        let z = c64::new(0.0, 0.0);
        let p = |x: f64| [x, 0.0, 0.0];
        let w = |v: f64| [z, z, c64::new(v, 0.0)];
        let a = shape(vec![(p(0.0), w(1.0)), (p(1.0), w(2.0)), (p(2.0), w(-1.0))]);
        // Same shape times 3i on a finer face (extra node between): MAC 1 to round-off.
        let s = c64::new(0.0, 3.0);
        let b = shape(vec![
            (p(0.0), [z, z, s]),
            (p(0.5), [z, z, s * 5.0]),
            (p(1.0), [z, z, s * 2.0]),
            (p(2.0), [z, z, -s]),
        ]);
        assert!((face_mac(&a, &b).unwrap() - 1.0).abs() < 1e-14);
        // An orthogonal shape on the same nodes: MAC 0.
        let c = shape(vec![(p(0.0), w(1.0)), (p(1.0), w(0.0)), (p(2.0), w(1.0))]);
        assert!(face_mac(&a, &c).unwrap().abs() < 1e-14);
        assert_eq!(face_mac(&a, &shape(Vec::new())), None);
    }
}
