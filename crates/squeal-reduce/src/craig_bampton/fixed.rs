//! The fixed-interface modes of a part (eq (2)'s Φ) and where their Sturm check runs.

use super::*;

/// Fixed-interface modes as found: eigenvalues, vectors, residuals, and the Sturm check made.
pub(super) struct FixedModes {
    pub(super) values: Vec<f64>,
    pub(super) vectors: Mat<f64>,
    pub(super) residuals: Vec<f64>,
    /// The guard eigenvalues above `values` (for a Sturm check made later).
    pub(super) guard_values: Vec<f64>,
    pub(super) stats: squeal_eigs::EigStats,
    /// Sturm bound `ω²` and the count of eigenvalues below it.
    pub(super) sturm: Option<(f64, usize)>,
    /// The Sturm check is still to be made ([`SturmPlacement::Deferred`]).
    pub(super) deferred: bool,
}

/// Where the Sturm check of the fixed-interface modes runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum SturmPlacement {
    /// Beside the Lanczos iteration (a second factor in memory at the same time).
    Beside,
    /// After the iteration, with the Cholesky factor still held (the eigensolver's own check,
    /// which finds missed eigenvalues by locked restarts).
    After,
    /// After the iteration, with the Cholesky factor's values freed first
    /// ([`check_deferred`]): the peak memory holds one factor.
    Deferred,
}

/// The Sturm check beside the iteration when the options allow it (`EigOptions::sturm_beside`)
/// and a second factor fits in the memory available now (Linux: `MemAvailable` of
/// `/proc/meminfo`; elsewhere it is taken to fit), else after it with the Cholesky factor
/// freed. The results do not depend on the choice (only the reported Sturm bound may).
pub(super) fn sturm_placement(
    opts: &ReduceOptions,
    factor: &squeal_eigs::FactorStats,
    modes: usize,
) -> SturmPlacement {
    if !opts.eig.sturm_beside {
        return SturmPlacement::Deferred;
    }
    // The LBL^T's values and its copy of K - b M, and the Lanczos basis (about 3 x modes).
    let need = factor.factor_bytes + 16 * factor.nnz_a + 8 * factor.n * 3 * modes;
    let available = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
        s.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<usize>().ok())
            .map(|kb| kb * 1024)
    });
    match available {
        // A quarter kept free for the other part and the allocator.
        Some(bytes) if need > bytes / 4 * 3 => SturmPlacement::Deferred,
        _ => SturmPlacement::Beside,
    }
}

/// The deferred Sturm check: frees the factor's values, counts the eigenvalues below a bound
/// placed among the modes and their guards with an LBLᵀ on the factor's analysis, and if some
/// were missed (rare), factors again and solves with the eigensolver's own check.
pub(super) fn check_deferred(
    mut modes: FixedModes,
    factor: SparseCholesky,
    k_vv: &SparseColMat<usize, f64>,
    m_vv: &SparseColMat<usize, f64>,
    constraints: &Constraints,
    spec: &PartSpec,
    opts: &ReduceOptions,
) -> Result<FixedModes, ReduceError> {
    let eigen = |source: EigError| ReduceError::Eigen {
        part: spec.name.clone(),
        source,
    };
    let analysis = factor.into_analysis();
    let t = Instant::now();
    let c = (!constraints.is_empty()).then_some(constraints);
    let all: Vec<f64> = modes
        .values
        .iter()
        .chain(&modes.guard_values)
        .copied()
        .collect();
    let (k, m) = (k_vv.as_ref(), m_vv.as_ref());
    match squeal_eigs::sturm_check_with(k, m, &all, modes.values.len(), Some(&analysis), c) {
        Ok(found) => {
            modes.sturm = Some(found);
            modes.stats.sturm = Some(found);
            modes.stats.sturm_time = t.elapsed();
            modes.deferred = false;
            Ok(modes)
        }
        Err(EigError::MissedEigenvalues { .. }) => {
            let chol = {
                let mut o = squeal_eigs::CholeskyOptions::default();
                o.par = opts.eig.par;
                o
            };
            let factor = analysis.factorize(k, &chol).map_err(eigen)?;
            let constrained = match c {
                None => None,
                Some(c) => Some(ConstrainedFactor::new(&factor, c).map_err(eigen)?),
            };
            let after = SturmPlacement::After;
            fixed_interface_modes(k_vv, m_vv, &factor, constrained.as_ref(), spec, opts, after)
        }
        Err(e) => Err(eigen(e)),
    }
}

/// Eqs (4)–(5): the fixed-interface modes of `K_vv φ = ω² M_vv φ` with the factor of `K_vv`,
/// mass-normalized. A fixed number (`spec.modes`), or with `opts.modes_below_hz` all those
/// below that frequency (counted by a Sturm count; at most `spec.modes`, else an error).
pub(super) fn fixed_interface_modes(
    k_vv: &SparseColMat<usize, f64>,
    m_vv: &SparseColMat<usize, f64>,
    factor: &SparseCholesky,
    constrained: Option<&ConstrainedFactor<'_>>,
    spec: &PartSpec,
    opts: &ReduceOptions,
    sturm: SturmPlacement,
) -> Result<FixedModes, ReduceError> {
    let part = &spec.name;
    let eigen = |source: EigError| ReduceError::Eigen {
        part: part.clone(),
        source,
    };
    let n = k_vv.nrows();
    let mut eig_opts = {
        let mut o = opts.eig;
        o.shift = 0.0;
        o.sturm_beside = sturm == SturmPlacement::Beside;
        o
    };
    let deferred = sturm == SturmPlacement::Deferred && opts.eig.sturm_check;
    if deferred {
        eig_opts.sturm_check = false;
    }
    let mut below = None;
    let nm = match opts.modes_below_hz {
        None => spec.modes,
        Some(f) => {
            if !(f.is_finite() && f > 0.0) {
                return Err(ReduceError::Invalid {
                    part: part.clone(),
                    what: format!("the mode cut-off frequency {f} Hz is not a positive number"),
                });
            }
            let bound = omega2(f);
            let (k, m) = (k_vv.as_ref(), m_vv.as_ref());
            let count = match constrained {
                None => squeal_eigs::count_below(k, m, bound),
                Some(c) => squeal_eigs::count_below_constrained(k, m, c.constraints(), bound),
            }
            .map_err(eigen)?;
            if count > spec.modes {
                return Err(ReduceError::TooManyModes {
                    part: part.clone(),
                    below_hz: f,
                    count,
                    limit: spec.modes,
                });
            }
            // The count is itself the Sturm check: the solver's own one is not needed
            // unless the solve misses a mode below the bound.
            eig_opts.sturm_check = false;
            below = Some((bound, count));
            count
        }
    };
    if nm == 0 {
        return Ok(FixedModes {
            values: Vec::new(),
            vectors: Mat::zeros(n, 0),
            residuals: Vec::new(),
            guard_values: Vec::new(),
            stats: Default::default(),
            sturm: below,
            deferred: false,
        });
    }
    let dim = n - constrained.map_or(0, |c| c.constraints().len());
    if nm >= dim {
        return Err(ReduceError::Invalid {
            part: part.clone(),
            what: format!("{nm} fixed-interface modes asked for, the interior has {dim} free dofs"),
        });
    }
    let solve = |eig_opts: &EigOptions| {
        let (k, m) = (k_vv.as_ref(), m_vv.as_ref());
        match constrained {
            None => lowest_modes_with_factor(k, m, factor, nm, eig_opts),
            Some(c) => lowest_modes_constrained(k, m, c, nm, eig_opts),
        }
        .map_err(eigen)
    };
    let modes = solve(&eig_opts)?;
    let modes = match below {
        Some((bound, _)) if modes.values.iter().any(|&v| v >= bound) => {
            // A mode below the bound was missed: solve again with the solver's Sturm check,
            // which finds missed copies of multiple eigenvalues by locked restarts.
            eig_opts.sturm_check = true;
            solve(&eig_opts)?
        }
        _ => modes,
    };
    Ok(FixedModes {
        sturm: below.or(modes.stats.sturm),
        // The count below the cut-off is itself the Sturm check.
        deferred: deferred && below.is_none(),
        values: modes.values,
        vectors: modes.vectors,
        residuals: modes.residuals,
        guard_values: modes.guard_values,
        stats: modes.stats,
    })
}

/// A zeroed dense matrix, or an error naming the part when the memory is not there.
pub(super) fn try_zeros(rows: usize, cols: usize, part: &str) -> Result<Mat<f64>, ReduceError> {
    let too_big = || ReduceError::Invalid {
        part: part.into(),
        what: format!("cannot allocate the {rows} x {cols} reduction basis"),
    };
    let count = rows.checked_mul(cols).ok_or_else(too_big)?;
    let mut probe: Vec<f64> = Vec::new();
    probe.try_reserve_exact(count).map_err(|_| too_big())?;
    drop(probe);
    Ok(Mat::zeros(rows, cols))
}
