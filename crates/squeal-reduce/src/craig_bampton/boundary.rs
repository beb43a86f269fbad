//! The boundary's rows of a part: its contact points and piston dofs as constraint rows, the footprint springs, and the projection of the boundary onto the fixed-interface modes (eq (2)).

use super::*;
use squeal_eigs::dense::cholesky_lower;

/// Boundary points and rows: contact points (3 rows each), then piston nodes (1 row each).
pub(crate) fn boundary_rows(
    mesh: &Mesh,
    dofmap: &FreeDofs,
    spec: &PartSpec,
) -> Result<(Vec<InterfacePoint>, Vec<Row>), ReduceError> {
    let part = &spec.name;
    let mut points = Vec::new();
    let mut rows = Vec::new();
    let restrained = |set: &str, node: u32, d: usize| ReduceError::BoundaryRestrained {
        part: part.clone(),
        set: set.into(),
        node: mesh.node_ids[node as usize],
        position: mesh.nodes[node as usize],
        direction: AXES[d],
    };
    // A body (a caliper, a bracket) touches no disc: its boundary is its coupling sets.
    let surfaces = match spec.role {
        PartRole::Body => Vec::new(),
        _ => spec.surfaces(),
    };
    // A node kept as a boundary point: the point and its three rows.
    let keep_node = |point: InterfacePoint,
                     node: u32,
                     set: &str,
                     points: &mut Vec<InterfacePoint>,
                     rows: &mut Vec<Row>|
     -> Result<(), ReduceError> {
        let p = points.len();
        points.push(point);
        for d in 0..3 {
            let dof = dofmap
                .free_dof(node, d)
                .ok_or_else(|| restrained(set, node, d))?;
            rows.push(Row {
                point: p,
                label: point_label(p, d),
                entries: vec![(dof, 1.0)],
                footprint: false,
            });
        }
        Ok(())
    };
    for surface in surfaces {
        match spec.interface {
            InterfaceKind::Node => {
                let nodes = contact_nodes(mesh, &surface.contact_set, &spec.axis)?;
                // Each node stands for its tributary share of the contact face, when the part has
                // one: the area its contact stiffness per unit area is multiplied by. A part has
                // none when the set is missing or names nodes with no boundary face among them (a
                // point contact whose face set is its contact set): its points carry no area, and
                // a scene's `[contact] point_area` gives them one.
                let cells = match tributary_areas(mesh, &surface.contact_face_set, &nodes) {
                    Ok(cells) => Some(cells),
                    Err(InterfaceError::MissingSet(_) | InterfaceError::NoFaces { .. }) => None,
                    Err(e) => return Err(e.into()),
                };
                for (k, node) in nodes.into_iter().enumerate() {
                    let p = points.len();
                    let cell = cells.as_ref().map(|c| c[k]);
                    points.push(InterfacePoint {
                        role: PointRole::Contact,
                        node_id: Some(mesh.node_ids[node as usize]),
                        patch: None,
                        position: mesh.nodes[node as usize],
                        area: cell.map(|c| c.0),
                        normal: cell.map(|c| c.1),
                        surface: surface.facing.clone(),
                        projected: None,
                        combines: None,
                    });
                    for d in 0..3 {
                        let dof = dofmap
                            .free_dof(node, d)
                            .ok_or_else(|| restrained(&surface.contact_set, node, d))?;
                        rows.push(Row {
                            point: p,
                            label: point_label(p, d),
                            entries: vec![(dof, 1.0)],
                            footprint: false,
                        });
                    }
                }
            }
            InterfaceKind::Nodal => match spec.role {
                // Every node of the face, its three dofs kept: the disc's face points that its
                // projected contact points combine ([`crate::interface::nodal`]; the brake
                // adds those).
                PartRole::Disc => {
                    for node in face_nodes(mesh, &surface.contact_face_set)? {
                        let point = InterfacePoint {
                            role: PointRole::Face,
                            node_id: Some(mesh.node_ids[node.node as usize]),
                            patch: None,
                            position: mesh.nodes[node.node as usize],
                            area: Some(node.area),
                            normal: Some(node.normal),
                            surface: surface.facing.clone(),
                            projected: None,
                            combines: None,
                        };
                        keep_node(
                            point,
                            node.node,
                            &surface.contact_face_set,
                            &mut points,
                            &mut rows,
                        )?;
                    }
                }
                // A pad's contact points ([`crate::interface::quad_contact`]): the face nodes
                // that carry a share of a uniform pressure (6-node triangles), kept; the
                // other nodes of its 8-node faces, kept as face points; then the Gauss points
                // of those faces, combinations of the kept nodes with no dofs of their own.
                PartRole::Pad | PartRole::Body => {
                    let contact = contact_points(mesh, &surface.contact_face_set)?;
                    let mut kept = std::collections::HashMap::new();
                    for c in contact.iter().filter(|c| c.node().is_some()) {
                        let node = c.nodes[0].0;
                        kept.insert(node, points.len());
                        let point = InterfacePoint {
                            role: PointRole::Contact,
                            node_id: Some(mesh.node_ids[node as usize]),
                            patch: None,
                            position: c.position,
                            area: Some(c.area),
                            normal: Some(c.normal),
                            surface: surface.facing.clone(),
                            projected: None,
                            combines: None,
                        };
                        keep_node(
                            point,
                            node,
                            &surface.contact_face_set,
                            &mut points,
                            &mut rows,
                        )?;
                    }
                    for node in combined_nodes(&contact) {
                        kept.insert(node, points.len());
                        let point = InterfacePoint {
                            role: PointRole::Face,
                            node_id: Some(mesh.node_ids[node as usize]),
                            patch: None,
                            position: mesh.nodes[node as usize],
                            area: None,
                            normal: None,
                            surface: surface.facing.clone(),
                            projected: None,
                            combines: None,
                        };
                        keep_node(
                            point,
                            node,
                            &surface.contact_face_set,
                            &mut points,
                            &mut rows,
                        )?;
                    }
                    for c in contact.into_iter().filter(|c| c.node().is_none()) {
                        let combines = c.nodes.iter().map(|&(n, w)| (kept[&n], w)).collect();
                        points.push(InterfacePoint {
                            role: PointRole::Contact,
                            node_id: None,
                            patch: None,
                            position: c.position,
                            area: Some(c.area),
                            normal: Some(c.normal),
                            surface: surface.facing.clone(),
                            projected: None,
                            combines: Some(combines),
                        });
                    }
                }
            },
            InterfaceKind::Patch => {
                let patches = patches(
                    mesh,
                    &surface.contact_face_set,
                    spec.grid[0],
                    spec.grid[1],
                    &spec.axis,
                )?;
                for patch in patches {
                    let p = points.len();
                    points.push(InterfacePoint {
                        role: PointRole::Contact,
                        node_id: None,
                        patch: Some(patch.number),
                        position: patch.centroid,
                        area: Some(patch.area),
                        normal: Some(patch.normal),
                        surface: surface.facing.clone(),
                        projected: None,
                        combines: None,
                    });
                    for d in 0..3 {
                        // A restrained face node would pin the patch's mean motion: refuse it,
                        // as for a restrained contact node.
                        let mut entries = Vec::with_capacity(patch.weights.len());
                        for &(node, w) in &patch.weights {
                            let dof = dofmap
                                .free_dof(node, d)
                                .ok_or_else(|| restrained(&surface.contact_face_set, node, d))?;
                            entries.push((dof, w));
                        }
                        rows.push(Row {
                            point: p,
                            label: point_label(p, d),
                            entries,
                            footprint: false,
                        });
                    }
                }
            }
        }
    }
    // A piston node's row: its dof along the piston direction (label, entries, normal).
    type PistonRow = (DofLabel, Vec<(usize, f64)>, Option<[f64; 3]>);
    let piston_row = |set: &str, node: u32, p: usize| -> Result<PistonRow, ReduceError> {
        match spec.piston_direction {
            None => {
                let d = spec.normal_direction;
                let dof = dofmap
                    .free_dof(node, d)
                    .ok_or_else(|| restrained(set, node, d))?;
                Ok((point_label(p, d), vec![(dof, 1.0)], None))
            }
            Some(n) => {
                // `r = n · u`: the node's own first axis (`piston_frames`).
                let entries = dofmap.along(node, n).ok_or_else(|| {
                    let d = (0..3)
                        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
                        .unwrap_or(2);
                    restrained(set, node, d)
                })?;
                Ok((
                    DofLabel::Along {
                        point: p,
                        direction: n,
                    },
                    entries,
                    Some(n),
                ))
            }
        }
    };
    let node_piston = |set: &str,
                       node: u32,
                       points: &mut Vec<InterfacePoint>,
                       rows: &mut Vec<Row>|
     -> Result<(), ReduceError> {
        let p = points.len();
        let (label, entries, normal) = piston_row(set, node, p)?;
        points.push(InterfacePoint {
            role: PointRole::Piston,
            node_id: Some(mesh.node_ids[node as usize]),
            patch: None,
            position: mesh.nodes[node as usize],
            area: None,
            normal,
            surface: None,
            projected: None,
            combines: None,
        });
        rows.push(Row {
            point: p,
            label,
            entries,
            footprint: false,
        });
        Ok(())
    };
    if !spec.piston_footprints.is_empty() {
        for set in &spec.piston_footprints {
            let nodes = mesh
                .node_set(set)
                .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
            match nodes {
                [] => return Err(InterfaceError::EmptySet(set.clone()).into()),
                &[node] => node_piston(set, node, &mut points, &mut rows)?,
                _ => {
                    let print = footprint(mesh, set)?;
                    let p = points.len();
                    let mut label = point_label(p, spec.normal_direction);
                    let mut entries = Vec::new();
                    for &(node, w) in &print.weights {
                        let (l, e, _) = piston_row(set, node, p)?;
                        label = l;
                        entries.extend(e.into_iter().map(|(dof, c)| (dof, c * w)));
                    }
                    let direction = match spec.piston_direction {
                        Some(n) => n,
                        None => {
                            let mut e = [0.0; 3];
                            e[spec.normal_direction.min(2)] = 1.0;
                            e
                        }
                    };
                    points.push(InterfacePoint {
                        role: PointRole::Piston,
                        node_id: None,
                        patch: None,
                        position: print.centroid,
                        area: Some(print.area),
                        normal: Some(direction),
                        surface: None,
                        projected: None,
                        combines: None,
                    });
                    rows.push(Row {
                        point: p,
                        label,
                        entries,
                        footprint: true,
                    });
                }
            }
        }
    } else if let Some(set) = &spec.piston_set {
        let nodes = mesh
            .node_set(set)
            .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
        if nodes.is_empty() {
            return Err(InterfaceError::EmptySet(set.clone()).into());
        }
        for &node in nodes {
            node_piston(set, node, &mut points, &mut rows)?;
        }
    }
    Ok((points, rows))
}

/// `K + Σ_f ρ_f c_fᵀ c_f` over the footprint rows `c_f` that are constraint rows (module docs),
/// or `None` when there are none. `ρ_f` is the mean of `K`'s diagonal over the row's dofs
/// over `Σ_k c_fk²`. Both triangles are stored, each column's rows ascending; an entry both in
/// `K` and added is `K`'s plus the footprints' in row order (the same bits for any thread
/// count).
pub(super) fn footprint_springs(
    k: &SparseColMat<usize, f64>,
    rows: &[Row],
    split: &Split,
) -> Option<SparseColMat<usize, f64>> {
    let n = k.ncols();
    let kr = k.as_ref();
    let diagonal = |j: usize| {
        kr.row_idx_of_col(j)
            .zip(kr.val_of_col(j))
            .find(|&(i, _)| i == j)
            .map_or(0.0, |(_, &v)| v)
    };
    let mut added: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    let mut any = false;
    for (r, kind) in rows.iter().zip(&split.kinds) {
        if !r.footprint || !matches!(kind, RowKind::Constraint(_)) {
            continue;
        }
        let norm2: f64 = r.entries.iter().map(|&(_, c)| c * c).sum();
        if norm2 <= 0.0 {
            continue;
        }
        let mean =
            r.entries.iter().map(|&(f, _)| diagonal(f)).sum::<f64>() / r.entries.len() as f64;
        let rho = mean / norm2;
        for &(j, cj) in &r.entries {
            for &(i, ci) in &r.entries {
                added[j].push((i, rho * ci * cj));
            }
        }
        any = true;
    }
    if !any {
        return None;
    }
    Some(with_added(k, added))
}

/// `K` plus the entries `added[j]` (row, value) of each column `j`: both triangles as given,
/// each column's rows ascending; an entry both in `K` and added is `K`'s plus the added ones
/// in the order given (the same bits for any thread count).
pub(crate) fn with_added(
    k: &SparseColMat<usize, f64>,
    mut added: Vec<Vec<(usize, f64)>>,
) -> SparseColMat<usize, f64> {
    let n = k.ncols();
    let kr = k.as_ref();
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::with_capacity(kr.compute_nnz());
    let mut val = Vec::with_capacity(kr.compute_nnz());
    col_ptr.push(0);
    for (j, more) in added.iter_mut().enumerate() {
        let mut column: Vec<(usize, f64)> = kr
            .row_idx_of_col(j)
            .zip(kr.val_of_col(j))
            .map(|(i, &v)| (i, v))
            .collect();
        if !more.is_empty() {
            column.append(more);
            // Stable: K's entry first, then the footprints' in row order.
            column.sort_by_key(|e| e.0);
        }
        for (i, v) in column {
            match row_idx.last() {
                Some(&last) if last == i && row_idx.len() > col_ptr[j] => {
                    if let Some(x) = val.last_mut() {
                        *x += v;
                    }
                }
                _ => {
                    row_idx.push(i);
                    val.push(v);
                }
            }
        }
        col_ptr.push(row_idx.len());
    }
    SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
        val,
    )
}

/// The label of point `p`'s dof along coordinate axis `d`.
pub(super) fn point_label(p: usize, d: usize) -> DofLabel {
    DofLabel::Point {
        point: p,
        direction: d as u8,
    }
}

/// How each boundary row enters: a dof of its own (`u_m = r_b / c`) or a constraint row on the
/// interior dofs.
#[derive(Clone, Copy, Debug)]
pub(super) enum RowKind {
    /// The dof `m` and `1 / c`.
    Eliminated { dof: usize, inv: f64 },
    /// Index among the constraint rows.
    Constraint(usize),
}

/// The boundary rows split into eliminated dofs and constraints, and the interior numbering.
pub(super) struct Split {
    pub(super) kinds: Vec<RowKind>,
    /// Free dofs of the interior (all but the eliminated ones), ascending; `interior_index[f]`
    /// their position.
    pub(super) interior: Vec<usize>,
    pub(super) interior_index: Vec<Option<usize>>,
    /// Constraint rows on the interior dofs (`C_P`, interior numbering) and their entries on
    /// eliminated dofs (`C_E`: boundary row of the dof, coefficient).
    pub(super) constraint_rows: Vec<Vec<(usize, f64)>>,
    pub(super) constraint_eliminated: Vec<Vec<(usize, f64)>>,
}

impl Split {
    pub(super) fn new(rows: &[Row], n_free: usize, part: &str) -> Result<Self, ReduceError> {
        let mut owner: Vec<Option<usize>> = vec![None; n_free];
        let mut kinds = Vec::with_capacity(rows.len());
        let mut n_constraints = 0;
        for (b, r) in rows.iter().enumerate() {
            let single = match r.entries.as_slice() {
                &[(dof, c)] if c != 0.0 => Some((dof, c)),
                _ => None,
            };
            kinds.push(match single {
                Some((dof, c)) => {
                    // Two rows on one dof are the same coordinate twice.
                    if owner[dof].replace(b).is_some() {
                        return Err(ReduceError::NoMaster {
                            part: part.into(),
                            point: r.point,
                            direction: match r.label {
                                DofLabel::Point { direction, .. } => {
                                    AXES[direction.min(2) as usize]
                                }
                                _ => 'n',
                            },
                        });
                    }
                    RowKind::Eliminated { dof, inv: 1.0 / c }
                }
                None => {
                    n_constraints += 1;
                    RowKind::Constraint(n_constraints - 1)
                }
            });
        }
        let interior: Vec<usize> = (0..n_free).filter(|&f| owner[f].is_none()).collect();
        let mut interior_index = vec![None; n_free];
        for (i, &f) in interior.iter().enumerate() {
            interior_index[f] = Some(i);
        }
        let mut constraint_rows = Vec::with_capacity(n_constraints);
        let mut constraint_eliminated = Vec::with_capacity(n_constraints);
        for (r, kind) in rows.iter().zip(&kinds) {
            if let RowKind::Constraint(_) = kind {
                let (mut on_interior, mut on_eliminated) = (Vec::new(), Vec::new());
                for &(f, w) in &r.entries {
                    match (interior_index[f], owner[f]) {
                        (Some(i), _) => on_interior.push((i, w)),
                        (None, Some(b)) => on_eliminated.push((b, w)),
                        (None, None) => {}
                    }
                }
                constraint_rows.push(on_interior);
                constraint_eliminated.push(on_eliminated);
            }
        }
        Ok(Self {
            kinds,
            interior,
            interior_index,
            constraint_rows,
            constraint_eliminated,
        })
    }

    /// The constraint rows `C_P` on the interior dofs.
    pub(super) fn constraints(&self) -> Result<Constraints, EigError> {
        Constraints::new(self.interior.len(), self.constraint_rows.clone())
    }

    /// The dof of an eliminated boundary row and `1 / c` (the blocked constraint modes read
    /// [`RowKind`] directly; the unblocked reference in their test uses this).
    #[cfg(test)]
    pub(super) fn eliminated_dof(&self, b: usize) -> Option<(usize, f64)> {
        match self.kinds[b] {
            RowKind::Eliminated { dof, inv } => Some((dof, inv)),
            RowKind::Constraint(_) => None,
        }
    }

    /// Eq (3): the interior part of the constraint modes, one column per boundary row (see the
    /// module documentation), from the factor of `K_vv` and, if there are constraint rows, its
    /// constrained form, all at once: the reference of the blocked
    /// [`Split::constraint_modes_into`] in its test.
    #[cfg(test)]
    pub(super) fn constraint_modes(
        &self,
        k: &SparseColMat<usize, f64>,
        factor: &SparseCholesky,
        constrained: Option<&ConstrainedFactor<'_>>,
    ) -> Result<Mat<f64>, EigError> {
        let eliminated: Vec<(usize, usize, f64)> = (0..self.kinds.len())
            .filter_map(|b| self.eliminated_dof(b).map(|(m, inv)| (b, m, inv)))
            .collect();
        // y = -K_vv⁻¹ K_vm / c for every eliminated dof.
        let mut y = Mat::<f64>::zeros(self.interior.len(), eliminated.len());
        let kr = k.as_ref();
        for (e, &(_, m, inv)) in eliminated.iter().enumerate() {
            for (r, &v) in kr.row_idx_of_col(m).zip(kr.val_of_col(m)) {
                if let Some(i) = self.interior_index[r] {
                    y[(i, e)] -= v * inv;
                }
            }
        }
        factor.solve_in_place(y.as_mut())?;
        let mut out = Mat::<f64>::zeros(self.interior.len(), self.kinds.len());
        let (y, x) = match constrained {
            None => (y, None),
            Some(c) => {
                // P y - X S⁻¹ C_E e_m / c, and X S⁻¹ for the constraint rows.
                let mut y = y;
                c.project(y.as_mut());
                let column = |b: usize| eliminated.iter().position(|&(row, _, _)| row == b);
                let g = Mat::from_fn(self.constraint_rows.len(), eliminated.len(), |p, e| {
                    self.constraint_eliminated[p]
                        .iter()
                        .filter(|&&(b, _)| column(b) == Some(e))
                        .map(|&(_, w)| w * eliminated[e].2)
                        .sum()
                });
                let y = &y - c.correction(g.as_ref())?;
                let q = self.constraint_rows.len();
                (y, Some(c.correction(Mat::<f64>::identity(q, q).as_ref())?))
            }
        };
        let mut next_eliminated = 0;
        for (b, kind) in self.kinds.iter().enumerate() {
            match (kind, &x) {
                (RowKind::Eliminated { .. }, _) => {
                    out.col_mut(b).copy_from(y.col(next_eliminated));
                    next_eliminated += 1;
                }
                (RowKind::Constraint(p), Some(x)) => out.col_mut(b).copy_from(x.col(*p)),
                (RowKind::Constraint(_), None) => {}
            }
        }
        Ok(out)
    }

    /// `X_II`: `x` itself when no dof is eliminated (no copy of a large matrix), else
    /// [`Split::extract_interior`].
    pub(super) fn interior_of<'x>(
        &self,
        x: &'x SparseColMat<usize, f64>,
    ) -> Cow<'x, SparseColMat<usize, f64>> {
        if self.interior.len() == x.ncols() {
            Cow::Borrowed(x)
        } else {
            Cow::Owned(self.extract_interior(x))
        }
    }

    /// `X_II` as a sparse matrix (rows and columns of the interior dofs).
    pub(super) fn extract_interior(
        &self,
        x: &SparseColMat<usize, f64>,
    ) -> SparseColMat<usize, f64> {
        let n = self.interior.len();
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut val = Vec::new();
        col_ptr.push(0);
        let xr = x.as_ref();
        for &f in &self.interior {
            for (r, &v) in xr.row_idx_of_col(f).zip(xr.val_of_col(f)) {
                if let Some(i) = self.interior_index[r] {
                    row_idx.push(i);
                    val.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        SparseColMat::new(
            SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
            val,
        )
    }

    /// Writes an interior vector into the interior dofs of `out` (a full free-dof vector whose
    /// eliminated dofs are left as they are).
    pub(super) fn expand_into(&self, v: faer::ColRef<'_, f64>, mut out: faer::ColMut<'_, f64>) {
        for (i, &f) in self.interior.iter().enumerate() {
            out[f] = v[i];
        }
    }
}

/// Rows per block in the sums of [`project`]: fixed, so that the bits of the result do not
/// depend on the thread count.
pub(super) const ROW_BLOCK: usize = 4096;

/// Eqs (6)–(7): `K̂ = Bᵀ K B` and `M̂ = Bᵀ M B` for sparse symmetric `K`, `M` (both
/// triangles stored) and dense `B`, symmetrized. Blocks of rows run in parallel: in each, a
/// row `i` of `X B` sums the stored entries of column `i` of `X` (its row `i`) in stored
/// order, and the block adds `B_blockᵀ (X B)_block`; the blocks' sums are added in order.
/// The result is the same bits for any number of threads. The reference of the blocked
/// [`super::blocked::project_blocked`] in its test (that one holds no row-major copy of `B`).
#[cfg(test)]
pub(super) fn project_pair(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    basis: &Mat<f64>,
) -> (Mat<f64>, Mat<f64>) {
    let (rows, n) = (basis.nrows(), basis.ncols());
    // Row-major copy of B: a row of X B is then a sum of contiguous rows of B.
    let mut b_rows = vec![0.0; rows * n];
    for j in 0..n {
        for (i, &v) in basis.col(j).iter().enumerate() {
            b_rows[i * n + j] = v;
        }
    }
    let starts: Vec<usize> = (0..rows).step_by(ROW_BLOCK).collect();
    let project = |x: &SparseColMat<usize, f64>| {
        let xr = x.as_ref();
        let partials: Vec<Mat<f64>> = starts
            .par_iter()
            .map(|&r0| {
                let len = ROW_BLOCK.min(rows - r0);
                let mut xb = vec![0.0; len * n];
                for (i, out) in (r0..r0 + len).zip(xb.chunks_exact_mut(n.max(1))) {
                    for (r, &v) in xr.row_idx_of_col(i).zip(xr.val_of_col(i)) {
                        for (o, b) in out.iter_mut().zip(&b_rows[r * n..(r + 1) * n]) {
                            *o += v * b;
                        }
                    }
                }
                let block = MatRef::from_row_major_slice(&b_rows[r0 * n..(r0 + len) * n], len, n);
                let xb = MatRef::from_row_major_slice(&xb, len, n);
                let mut p = Mat::<f64>::zeros(n, n);
                faer::linalg::matmul::matmul(
                    p.as_mut(),
                    Accum::Replace,
                    block.transpose(),
                    xb,
                    1.0,
                    Par::Seq,
                );
                p
            })
            .collect();
        let mut p = Mat::<f64>::zeros(n, n);
        for part in &partials {
            p += part;
        }
        Mat::from_fn(n, n, |i, j| 0.5 * (p[(i, j)] + p[(j, i)]))
    };
    (project(k), project(m))
}

pub(super) fn max_deviation_from_identity(m: &Mat<f64>, from: usize) -> f64 {
    let n = m.nrows();
    let mut worst: f64 = 0.0;
    for i in from..n {
        for j in from..n {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((m[(i, j)] - target).abs());
        }
    }
    worst
}

/// Re-orthonormalizes the modal columns in the mass metric: with `Φᵀ M Φ = L Lᵀ`,
/// `Φ ← Φ L⁻ᵀ`, and `K̂ ← Sᵀ K̂ S`, `M̂ ← Sᵀ M̂ S` with `S = diag(I, L⁻ᵀ)` (the projection
/// of eqs 6–7 on the new basis, done on the small matrices).
pub(super) fn orthonormalize_modes(
    basis: &mut Mat<f64>,
    k_hat: &mut Mat<f64>,
    m_hat: &mut Mat<f64>,
    nb: usize,
    part: &str,
) -> Result<(), ReduceError> {
    let n = basis.ncols();
    let nm = n - nb;
    let mnn = Mat::from_fn(nm, nm, |i, j| m_hat[(nb + i, nb + j)]);
    let l = cholesky_lower(&mnn).ok_or_else(|| ReduceError::Invalid {
        part: part.into(),
        what: "the modal block of the reduced mass is not positive definite".into(),
    })?;
    // L⁻¹ by forward substitution on the identity; S = diag(I, L⁻ᵀ).
    let mut linv = Mat::<f64>::zeros(nm, nm);
    for c in 0..nm {
        for i in c..nm {
            let mut s = if i == c { 1.0 } else { 0.0 };
            for k in c..i {
                s -= l[(i, k)] * linv[(k, c)];
            }
            linv[(i, c)] = s / l[(i, i)];
        }
    }
    let s = Mat::from_fn(n, n, |i, j| match (i < nb, j < nb) {
        (true, true) if i == j => 1.0,
        (false, false) => linv[(j - nb, i - nb)],
        _ => 0.0,
    });
    // Φ L⁻ᵀ, row by row, blocks of rows in parallel.
    let mut blocks = Vec::new();
    let mut rest = basis.subcols_mut(nb, nm);
    while rest.nrows() > 0 {
        let len = ROW_BLOCK.min(rest.nrows());
        let (top, bottom) = rest.split_at_row_mut(len);
        blocks.push(top);
        rest = bottom;
    }
    blocks.into_par_iter().for_each(|mut phi| {
        let mut row = vec![0.0; nm];
        for r in 0..phi.nrows() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (j..nm).map(|k| phi[(r, k)] * linv[(k, j)]).sum();
            }
            for (j, &x) in row.iter().enumerate() {
                phi[(r, j)] = x;
            }
        }
    });
    let congruence = |a: &Mat<f64>| {
        let mut t = Mat::<f64>::zeros(n, n);
        faer::linalg::matmul::matmul(t.as_mut(), Accum::Replace, a, &s, 1.0, Par::Seq);
        let mut out = Mat::<f64>::zeros(n, n);
        faer::linalg::matmul::matmul(
            out.as_mut(),
            Accum::Replace,
            s.transpose(),
            &t,
            1.0,
            Par::Seq,
        );
        Mat::from_fn(n, n, |i, j| 0.5 * (out[(i, j)] + out[(j, i)]))
    };
    *k_hat = congruence(k_hat);
    *m_hat = congruence(m_hat);
    Ok(())
}
