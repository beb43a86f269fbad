//! The full finite-element brake: disc and pads on their meshes, without any reduction, joined
//! by the contact pairs of the reduced brake, as the reference the reduction is measured
//! against (issue 20, item 5; `squeal stability --full`).
//!
//! **Model.** Each part's `K` and `M` (the disc, the pads and the further parts of
//! `[parts.<name>]`) are assembled as the reduction assembles them before it reduces
//! ([`squeal_reduce::unreduced`], from the same [`BrakeInputs`]: the restraints, those in node
//! frames, the ties eliminated by the same projection, the supports' and `[[springs]]`'
//! stiffness) and stacked block-diagonally; the connectors between parts add `Cᵀ K_c C` on
//! their coupling sets' mean-motion rows and the dampers their `C_d` ([`parts`]); the ties
//! between parts (`[[ties]]` with `master_part`) are eliminated from the stacked model by the
//! reduced brake's congruence ([`ties`]). Each contact pair `p`
//! of the reduced brake gets its vectors `g_p` (along the pair normal `n_p`) and `h_p` (along
//! the sliding direction `s_p`) over the full model's dofs, with the weights the reduction
//! uses: for a patch pair the disc patch's area-weighted mean motion minus the pad patch's
//! (the patches cut again by [`squeal_reduce::interface::patches`], to the bit the same), for a
//! nodal pair the disc face's shape functions at the pad node's projection (the weights stored
//! in the reduced model) minus the pad node. The Craig–Bampton basis `B` of the parts, stacked,
//! holds these motions exactly (`g_p,reduced = Bᵀ g_p`), so the reduced brake is this model
//! projected on `B` (Rayleigh–Ritz).
//!
//! **Linearization.** About the static equilibrium at μ (eq (14), of the reduced brake: the
//! contact forces act on the interface coordinates, where the constraint modes make the static
//! response exact, so the equilibrium's contact state is the full model's too), each pair's
//! element gives `F_n,δ`, `F_t,δ` (and the rate and slip-velocity derivatives of a
//! velocity-dependent law), and eqs (18)–(20) read, over the full model's dofs,
//!
//! `K_t(μ) = K + Σ_p (F_n,δ g_p + F_t,δ h_p) g_pᵀ`,
//! `C(μ) = Σ_p (F_n,δ' g_p + F_t,δ' h_p) g_pᵀ + (F_n,v g_p + F_t,v h_p) h_pᵀ`:
//!
//! for the paper's element `F_t,δ = μ F_n,δ` (non-symmetric) and `C = 0`. The modal damping of
//! eqs (12)–(13) is defined on the reduced brake's modes and has no full-model counterpart: the
//! full model is compared with the reduced brake without it ([`onset`]). Its complex
//! eigenvalues solve `(λ² M + λ C + K_t(μ)) φ = 0` (eq (21) without the modal damping), found
//! near the band by shift-invert Arnoldi ([`squeal_eigs::quadratic`]).

pub mod onset;
pub mod parts;
pub mod run;
pub mod system;
pub mod ties;

use crate::error::{PipelineError, Result};
use crate::model::Model;
use crate::parts::SceneParts;
use faer::sparse::{SparseColMat, Triplet};
use squeal_brake::assemble::Pairing;
use squeal_brake::contact::Response;
use squeal_brake::model::SparseVec;
use squeal_fe::MaterialTable;
use squeal_reduce::brake::BrakeInputs;
use squeal_reduce::craig_bampton::PartSpec;
use squeal_reduce::interface::{Patch, patches};
use squeal_reduce::unreduced::{Coordinates, UnreducedPart, unreduced_part};
use std::collections::HashMap;

/// A real sparse matrix of the full model.
type Sparse = SparseColMat<usize, f64>;
/// One part of the full model: its matrices on its kept coordinates and its place in the
/// stacked model.
pub struct FullPart {
    /// The part's name (`disc`, a pad's or a further part's).
    pub name: String,
    /// Its `K'`, `M'` on its kept coordinates, as the reduction assembles them.
    pub unreduced: UnreducedPart,
    /// What the reduction reduces it with.
    pub spec: PartSpec,
    /// Its first dof in the full model.
    pub offset: usize,
}

/// The full model: the parts' `K`, `M` stacked, and each pair's `g_p` and `h_p`.
pub struct FullBrake {
    /// The parts, disc first, in the reduced brake's order.
    pub parts: Vec<FullPart>,
    /// `K` of the parts, without the contact.
    pub k: SparseColMat<usize, f64>,
    /// `M`.
    pub m: SparseColMat<usize, f64>,
    /// `g_p` of each pair (along the normal), over the full model's dofs.
    pub normal: Vec<SparseVec>,
    /// `h_p` of each pair (along the sliding direction).
    pub tangent: Vec<SparseVec>,
    /// The dampers' `C_d` ([`parts`]); `None` without any.
    pub damping: Option<SparseColMat<usize, f64>>,
    /// The ties between parts, eliminated from `k`, `m`, the pairs' vectors and the damping
    /// ([`ties`]); `None` without any. With ties the parts' offsets are on the stacked dofs
    /// before the elimination ([`ties::FullTies::expand`] maps the model's dofs onto them).
    pub ties: Option<ties::FullTies>,
}

/// Components of a direction below 64 ε are dropped, as the reduced brake drops them.
const NEGLIGIBLE: f64 = 64.0 * f64::EPSILON;

/// `w` with its components below [`NEGLIGIBLE`] set to zero.
fn kept(w: [f64; 3]) -> [f64; 3] {
    w.map(|x| if x.abs() > NEGLIGIBLE { x } else { 0.0 })
}

pub(crate) fn full_error(message: impl std::fmt::Display) -> PipelineError {
    PipelineError::input("the full model", message)
}

/// A stacked block of `a` at `offset` as triplets.
pub(crate) fn push_block(
    a: &SparseColMat<usize, f64>,
    offset: usize,
    out: &mut Vec<Triplet<usize, usize, f64>>,
) {
    for j in 0..a.ncols() {
        for (i, &v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            out.push(Triplet::new(offset + i, offset + j, v));
        }
    }
}

/// The parts of the full model on `parts`' meshes with `inputs`' restraints, materials,
/// ties, supports and springs, assembled as the reduction assembles them.
fn full_parts(parts: &SceneParts, inputs: &BrakeInputs) -> Result<Vec<FullPart>> {
    let mut full = Vec::new();
    let mut offset = 0;
    for (name, input) in inputs.parts() {
        let loaded = parts::loaded(parts, name)?;
        let mesh = &loaded.mesh;
        let materials = MaterialTable::from_mesh(mesh, &input.material_overrides)
            .map_err(|e| full_error(format!("the {name}'s materials: {e}")))?;
        let spec = inputs.spec(name, input, loaded.info.clone());
        let unreduced = unreduced_part(mesh, &materials, &spec)
            .map_err(|e| full_error(format!("the {name}: {e}")))?;
        let n = unreduced.num_free();
        full.push(FullPart {
            name: name.to_string(),
            unreduced,
            spec,
            offset,
        });
        offset += n;
    }
    Ok(full)
}

/// The full model of the brake `model` (reduced from `parts` with `inputs`).
pub fn full_brake(parts: &SceneParts, inputs: &BrakeInputs, model: &Model) -> Result<FullBrake> {
    let full = full_parts(parts, inputs)?;
    let n = full.last().map_or(0, |p| p.offset + p.unreduced.num_free());
    let (mut kt, mut mt) = (Vec::new(), Vec::new());
    for p in &full {
        push_block(&p.unreduced.system.k, p.offset, &mut kt);
        push_block(&p.unreduced.system.m, p.offset, &mut mt);
    }
    parts::connector_triplets(&full, parts, inputs, model, &mut kt)?;
    let mut vectors = PairVectors::new(parts, inputs, model, &full)?;
    let (mut normal, mut tangent) = (Vec::new(), Vec::new());
    for pairing in &model.pairs {
        normal.push(vectors.vector(pairing, pairing.normal)?);
        tangent.push(vectors.vector(pairing, pairing.sliding)?);
    }
    let ties = ties::FullTies::new(parts, inputs, &full)?;
    let linked: usize = model.rom.ties.iter().map(|t| t.links.len()).sum();
    if ties.as_ref().map_or(0, |t| t.slave_nodes) != linked {
        return Err(full_error(format!(
            "the reduced model ties {linked} slave nodes between parts and the scene {}: was it reduced from another scene? Reduce again",
            ties.as_ref().map_or(0, |t| t.slave_nodes)
        )));
    }
    let (k, m) = match &ties {
        Some(t) => {
            normal = normal.iter().map(|g| t.reduce(g)).collect();
            tangent = tangent.iter().map(|h| t.reduce(h)).collect();
            (t.congruence(&kt)?, t.congruence(&mt)?)
        }
        None => {
            let sparse = |t: &[Triplet<usize, usize, f64>]| {
                SparseColMat::try_new_from_triplets(n, n, t)
                    .map_err(|e| full_error(format!("stacking the parts' matrices: {e}")))
            };
            (sparse(&kt)?, sparse(&mt)?)
        }
    };
    Ok(FullBrake {
        k,
        m,
        parts: full,
        normal,
        tangent,
        damping: None,
        ties,
    })
}

/// Adds `a bᵀ` scaled by `f` (sparse outer product) to `out`.
fn push_outer(a: &SparseVec, b: &SparseVec, f: f64, out: &mut Vec<Triplet<usize, usize, f64>>) {
    if f == 0.0 {
        return;
    }
    for &(j, bj) in b {
        for &(i, ai) in a {
            out.push(Triplet::new(i, j, f * (ai * bj)));
        }
    }
}

impl FullBrake {
    /// The model with the scene's dampers in its damping (module [`parts`]); `parts` the
    /// scene's parts it was built from.
    pub fn with_dampers(mut self, scene: &squeal_scene::Scene, parts: &SceneParts) -> Result<Self> {
        let stacked = parts::damping(scene, &self.parts, parts)?;
        self.damping = match (stacked, &self.ties) {
            (Some(d), Some(t)) => {
                let mut triplets = Vec::new();
                push_block(&d, 0, &mut triplets);
                Some(t.congruence(&triplets)?)
            }
            (d, _) => d,
        };
        Ok(self)
    }

    /// Number of dofs.
    pub fn size(&self) -> usize {
        self.k.nrows()
    }

    /// `K + Σ_p (a_p g_p + b_p h_p) g_pᵀ`: the tangent stiffness with normal stiffnesses `a`
    /// and friction stiffnesses `b` (one of each per pair).
    pub fn stiffness(&self, a: &[f64], b: &[f64]) -> Result<SparseColMat<usize, f64>> {
        let mut t = Vec::new();
        push_block(&self.k, 0, &mut t);
        for (p, (g, h)) in self.normal.iter().zip(&self.tangent).enumerate() {
            push_outer(g, g, a.get(p).copied().unwrap_or(0.0), &mut t);
            push_outer(h, g, b.get(p).copied().unwrap_or(0.0), &mut t);
        }
        let n = self.size();
        SparseColMat::try_new_from_triplets(n, n, &t)
            .map_err(|e| full_error(format!("the tangent stiffness: {e}")))
    }

    /// `K_t(μ)` and `C(μ) + C_d` (module docs, [`parts`]) from each pair's element response at
    /// the state; `None` when no element depends on the velocities and there is no damper.
    pub fn linearized(&self, responses: &[Response]) -> Result<(Sparse, Option<Sparse>)> {
        if responses.len() != self.normal.len() {
            return Err(full_error(format!(
                "{} element responses for {} pairs",
                responses.len(),
                self.normal.len()
            )));
        }
        let a: Vec<f64> = responses.iter().map(|r| r.normal_derivatives[0]).collect();
        let b: Vec<f64> = responses
            .iter()
            .map(|r| r.tangential_derivatives[0])
            .collect();
        let k = self.stiffness(&a, &b)?;
        if !responses.iter().any(|r| r.has_velocity_terms()) {
            return Ok((k, self.damping.clone()));
        }
        let mut t = Vec::new();
        if let Some(d) = &self.damping {
            push_block(d, 0, &mut t);
        }
        for (r, (g, h)) in responses.iter().zip(self.normal.iter().zip(&self.tangent)) {
            let [_, n_r, n_v] = r.normal_derivatives;
            let [_, t_r, t_v] = r.tangential_derivatives;
            push_outer(g, g, n_r, &mut t);
            push_outer(h, g, t_r, &mut t);
            push_outer(g, h, n_v, &mut t);
            push_outer(h, h, t_v, &mut t);
        }
        let n = self.size();
        let c = SparseColMat::try_new_from_triplets(n, n, &t)
            .map_err(|e| full_error(format!("the contact damping: {e}")))?;
        Ok((k, Some(c)))
    }
}

/// What it takes to write a pair's vectors over the full model's dofs: node lookups and the
/// patches of each contact face (cut once).
struct PairVectors<'a> {
    parts: &'a SceneParts,
    inputs: &'a BrakeInputs,
    model: &'a Model,
    full: &'a [FullPart],
    /// Each part's kept coordinates, in `full`'s order.
    coordinates: Vec<Coordinates<'a>>,
    /// Node id → node index, by part.
    nodes: HashMap<&'a str, HashMap<u64, u32>>,
    /// Patches by (part, face set).
    patches: HashMap<(String, String), Vec<Patch>>,
}

impl<'a> PairVectors<'a> {
    fn new(
        parts: &'a SceneParts,
        inputs: &'a BrakeInputs,
        model: &'a Model,
        full: &'a [FullPart],
    ) -> Result<Self> {
        let nodes = parts
            .all()
            .into_iter()
            .map(|(name, p)| {
                let ids = p.mesh.node_ids.iter().enumerate();
                (name, ids.map(|(i, &id)| (id, i as u32)).collect())
            })
            .collect();
        Ok(Self {
            parts,
            inputs,
            model,
            full,
            coordinates: full.iter().map(|p| p.unreduced.coordinates()).collect(),
            nodes,
            patches: HashMap::new(),
        })
    }

    /// The motion `w · u` of node index `node` of part `name` (`w` a unit vector) on the full
    /// model's coordinates, scaled by `scale`: the reduction's row of a contact point.
    fn along(&self, name: &str, node: u32, w: [f64; 3], scale: f64) -> Result<SparseVec> {
        let k = self
            .full
            .iter()
            .position(|p| p.name == name)
            .ok_or_else(|| full_error(format!("no part {name}")))?;
        let row = self.coordinates[k].along(node, w).ok_or_else(|| {
            full_error(format!(
                "a contact node of the {name} (index {node}) is held or tied along the pair's direction: contact nodes must be free"
            ))
        })?;
        let offset = self.full[k].offset;
        Ok(row
            .into_iter()
            .map(|(i, v)| (offset + i, scale * v))
            .collect())
    }

    /// The node index of node `id` of part `name`.
    fn node(&self, name: &str, id: u64) -> Result<u32> {
        let mesh = self
            .parts
            .part(name)
            .map(|p| std::path::PathBuf::from(&p.info.path))
            .unwrap_or_default();
        self.nodes
            .get(name)
            .and_then(|m| m.get(&id))
            .copied()
            .ok_or(PipelineError::ForeignNode {
                part: name.to_string(),
                node: id,
                mesh,
            })
    }

    /// The pair's vector along `w` (`g_p` for the normal, `h_p` for the sliding direction).
    fn vector(&mut self, pairing: &Pairing, w: [f64; 3]) -> Result<SparseVec> {
        let disc = self
            .model
            .rom
            .part("disc")
            .ok_or(PipelineError::NoPart { part: "disc" })?;
        let dp = disc
            .info
            .points
            .get(pairing.disc_point)
            .ok_or_else(|| full_error("a pair's disc point is not in the reduced model"))?;
        if dp.projected.is_some() {
            self.nodal(pairing, w)
        } else {
            self.patch(pairing, w)
        }
    }

    /// A nodal pair: `+w` on the disc face nodes weighted by the shape functions at the
    /// projected point, `-w` on the pad node (or on a Gauss point's face nodes, weighted by
    /// the shape functions there).
    fn nodal(&self, pairing: &Pairing, w: [f64; 3]) -> Result<SparseVec> {
        let rom = &self.model.rom;
        let disc = rom
            .part("disc")
            .ok_or(PipelineError::NoPart { part: "disc" })?;
        let pad = rom
            .part(&pairing.pad)
            .ok_or_else(|| full_error(format!("no pad {} in the reduced model", pairing.pad)))?;
        let point_node = |points: &[squeal_reduce::rom::InterfacePoint], k: usize, part: &str| {
            points
                .get(k)
                .and_then(|p| p.node_id)
                .ok_or_else(|| full_error(format!("a contact point of the {part} has no node")))
        };
        let dp = &disc.info.points[pairing.disc_point];
        let proj = dp
            .projected
            .as_ref()
            .ok_or_else(|| full_error("a nodal pair without its projection"))?;
        // The pad's side: its node, or a Gauss point's combination of its face's nodes.
        let pp = pad
            .info
            .points
            .get(pairing.pad_point)
            .ok_or_else(|| full_error(format!("no pad point of {} for a pair", pairing.pad)))?;
        let pad_weights = match &pp.combines {
            Some(c) => c.clone(),
            None => vec![(pairing.pad_point, 1.0)],
        };
        let w = kept(w);
        let mut g = Vec::new();
        for &(k, wk) in &proj.weights {
            let node = self.node("disc", point_node(&disc.info.points, k, "disc")?)?;
            g.extend(self.along("disc", node, w, wk)?);
        }
        for (k, wk) in pad_weights {
            let id = point_node(&pad.info.points, k, &pairing.pad)?;
            let node = self.node(&pairing.pad, id)?;
            g.extend(self.along(&pairing.pad, node, w, -wk)?);
        }
        Ok(g)
    }

    /// The patch `number` of `face_set` on part `part`, cut as the reduction cuts it.
    fn cut(&mut self, part: &str, face_set: &str, number: Option<usize>) -> Result<Patch> {
        let key = (part.to_string(), face_set.to_string());
        if !self.patches.contains_key(&key) {
            let mesh = &self
                .parts
                .part(part)
                .ok_or_else(|| full_error(format!("no mesh for the part {part}")))?
                .mesh;
            let [radial, angular] = self.inputs.grid;
            let cut = patches(mesh, face_set, radial, angular, &self.inputs.axis)
                .map_err(|e| full_error(format!("cutting {face_set} of the {part}: {e}")))?;
            self.patches.insert(key.clone(), cut);
        }
        self.patches[&key]
            .iter()
            .find(|p| Some(p.number) == number)
            .cloned()
            .ok_or_else(|| full_error(format!("no patch of {face_set} on the {part} for a pair")))
    }

    /// A patch pair: `+w` on the disc patch's weighted nodes, `-w` on the pad patch's.
    fn patch(&mut self, pairing: &Pairing, w: [f64; 3]) -> Result<SparseVec> {
        let rom = &self.model.rom;
        let disc = rom
            .part("disc")
            .ok_or(PipelineError::NoPart { part: "disc" })?;
        let dp = &disc.info.points[pairing.disc_point];
        let surfaces = self.inputs.disc.surfaces();
        let surface = surfaces
            .iter()
            .find(|s| s.facing == dp.surface)
            .ok_or_else(|| full_error("a disc point on no contact surface"))?;
        let disc_patch = self.cut("disc", &surface.contact_face_set, dp.patch)?;
        let pad_input = self
            .inputs
            .pads
            .iter()
            .find(|p| p.name == pairing.pad)
            .ok_or_else(|| full_error(format!("no pad {} in the inputs", pairing.pad)))?;
        let pp = rom
            .part(&pairing.pad)
            .and_then(|p| p.info.points.get(pairing.pad_point))
            .ok_or_else(|| full_error(format!("no pad point of {} for a pair", pairing.pad)))?;
        let face = pad_input.part.contact_face_set.clone();
        let pad_patch = self.cut(&pairing.pad, &face, pp.patch)?;
        if disc_patch.centroid != dp.position || pad_patch.centroid != pp.position {
            return Err(full_error(
                "the patches cut again do not match the reduced model's: was it reduced from \
                 other meshes or another patch grid?",
            ));
        }
        let w = kept(w);
        let mut g = Vec::new();
        for (part, weights, sign) in [
            ("disc", &disc_patch.weights, 1.0),
            (pairing.pad.as_str(), &pad_patch.weights, -1.0),
        ] {
            for &(node, wn) in weights {
                g.extend(self.along(part, node, w, sign * wn)?);
            }
        }
        Ok(g)
    }
}
