//! The SIMD kernels of the supernodal triangular solves: the dense forward and backward steps of one supernode, the updates below it and the column dot products, each over W right-hand sides at once (pulp).

use super::*;

#[inline(always)]
pub(super) fn add<const W: usize>(a: &mut [f64; W], b: &[f64; W]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x += y;
    }
}

/// Forward step of one supernode on `own` (rows `base..`), with its pattern
/// rows in `own` or as `rows` says.
#[inline(always)]
pub(super) fn forward_supernode<const W: usize>(
    sn: Supernode<'_>,
    own: &mut [[f64; W]],
    base: usize,
    rows: &mut Updates<'_, W>,
    f: &mut [[f64; W]],
    parallel: bool,
) {
    let (w, nrows) = (sn.ncols, sn.nrows());
    let f = &mut f[..nrows];
    let at = sn.start - base;
    f[..w].copy_from_slice(&own[at..at + w]);
    f[w..].fill([0.0; W]);
    for a in (0..w).step_by(PANEL) {
        let b = (a + PANEL).min(w);
        for c in a..b {
            let d = sn.l[c * nrows + c];
            let (head, tail) = f.split_at_mut(c + 1);
            let xc = &mut head[c];
            for v in xc.iter_mut() {
                *v /= d;
            }
            axpy(&mut tail[..b - c - 1], &sn.col(c, c + 1)[..b - c - 1], xc);
        }
        let (head, below) = f.split_at_mut(b);
        update_below(sn, a..b, &head[a..b], below, b, parallel);
    }
    own[at..at + w].copy_from_slice(&f[..w]);
    for (&r, v) in sn.pattern.iter().zip(&f[w..]) {
        let target = match rows {
            Updates::All => &mut own[r - base],
            Updates::Buffer {
                end,
                top_pos,
                local,
                buf,
            } => {
                if r < *end {
                    &mut own[r - base]
                } else {
                    &mut buf[local[top_pos[r] as usize] as usize]
                }
            }
        };
        add(target, v);
    }
}

/// y <- y - l x for rows y and one column l.
#[inline(always)]
pub(super) fn axpy<const W: usize>(y: &mut [[f64; W]], l: &[f64], x: &[f64; W]) {
    for (row, &li) in y.iter_mut().zip(l) {
        for (v, &xj) in row.iter_mut().zip(x) {
            *v = (-li).mul_add(xj, *v);
        }
    }
}

/// Rows `from..` of the frontal vector (`below`) minus the panel's columns
/// `cols` times the panel's solved rows `xs`, column by column.
#[inline(always)]
pub(super) fn update_below<const W: usize>(
    sn: Supernode<'_>,
    cols: Range<usize>,
    xs: &[[f64; W]],
    below: &mut [[f64; W]],
    from: usize,
    parallel: bool,
) {
    if parallel && below.len() * cols.len() >= PAR_ENTRIES {
        let arch = pulp::Arch::new();
        below
            .par_chunks_mut(ROW_CHUNK)
            .enumerate()
            .for_each(|(k, piece)| {
                arch.dispatch(BelowChunk {
                    sn,
                    cols: cols.clone(),
                    xs,
                    piece,
                    first: from + k * ROW_CHUNK,
                })
            });
    } else {
        for (k, piece) in below.chunks_mut(ROW_CHUNK).enumerate() {
            update_rows(sn, cols.clone(), xs, piece, from + k * ROW_CHUNK);
        }
    }
}

/// Rows `first..first + piece.len()` of a frontal vector minus columns
/// `cols` of the supernode times `xs`.
#[inline(always)]
pub(super) fn update_rows<const W: usize>(
    sn: Supernode<'_>,
    cols: Range<usize>,
    xs: &[[f64; W]],
    piece: &mut [[f64; W]],
    first: usize,
) {
    let len = piece.len();
    let col = |c: usize| &sn.col(c, first)[..len];
    let mut k = 0;
    while k + 4 <= xs.len() {
        let c = cols.start + k;
        let l = [col(c), col(c + 1), col(c + 2), col(c + 3)];
        axpy4(piece, l, [&xs[k], &xs[k + 1], &xs[k + 2], &xs[k + 3]]);
        k += 4;
    }
    for (x, c) in xs[k..].iter().zip(cols.start + k..) {
        axpy(piece, col(c), x);
    }
}

/// y <- y - l0 x0 - l1 x1 - l2 x2 - l3 x3, subtracted in that order (the
/// bits of four [`axpy`] calls, with one pass over y).
#[inline(always)]
pub(super) fn axpy4<const W: usize>(y: &mut [[f64; W]], l: [&[f64]; 4], x: [&[f64; W]; 4]) {
    let n = y.len();
    let (l0, l1, l2, l3) = (&l[0][..n], &l[1][..n], &l[2][..n], &l[3][..n]);
    for i in 0..n {
        let (a, b, c, d) = (-l0[i], -l1[i], -l2[i], -l3[i]);
        let row = &mut y[i];
        for j in 0..W {
            let v = a.mul_add(x[0][j], row[j]);
            let v = b.mul_add(x[1][j], v);
            let v = c.mul_add(x[2][j], v);
            row[j] = d.mul_add(x[3][j], v);
        }
    }
}

/// One parallel chunk of [`update_below`].
pub(super) struct BelowChunk<'a, 'b, const W: usize> {
    pub(super) sn: Supernode<'a>,
    pub(super) cols: Range<usize>,
    pub(super) xs: &'b [[f64; W]],
    pub(super) piece: &'b mut [[f64; W]],
    pub(super) first: usize,
}

impl<const W: usize> pulp::WithSimd for BelowChunk<'_, '_, W> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        update_rows(self.sn, self.cols, self.xs, self.piece, self.first);
    }
}

/// Dot products of columns `cols` of a supernode (rows `from..`) with `x`,
/// four columns per pass over x.
#[inline(always)]
pub(super) fn column_dots<const W: usize>(
    sn: Supernode<'_>,
    cols: Range<usize>,
    from: usize,
    x: &[[f64; W]],
) -> Vec<[f64; W]> {
    let mut out = Vec::with_capacity(cols.len());
    let mut c = cols.start;
    while c + 4 <= cols.end {
        let l = [
            sn.col(c, from),
            sn.col(c + 1, from),
            sn.col(c + 2, from),
            sn.col(c + 3, from),
        ];
        out.extend(dot4(l, x));
        c += 4;
    }
    for c in c..cols.end {
        out.push(dot(sn.col(c, from), x));
    }
    out
}

/// One parallel piece of [`column_dots`].
pub(super) struct ColumnDots<'a, 'b, const W: usize> {
    pub(super) sn: Supernode<'a>,
    pub(super) cols: Range<usize>,
    pub(super) from: usize,
    pub(super) x: &'b [[f64; W]],
}

impl<const W: usize> pulp::WithSimd for ColumnDots<'_, '_, W> {
    type Output = Vec<[f64; W]>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Vec<[f64; W]> {
        column_dots(self.sn, self.cols, self.from, self.x)
    }
}

/// Backward step of one supernode on `own` (rows `base..`).
#[inline(always)]
pub(super) fn backward_supernode<const W: usize>(
    sn: Supernode<'_>,
    own: &mut [[f64; W]],
    base: usize,
    rows: &Reads<'_, W>,
    f: &mut [[f64; W]],
    parallel: bool,
) {
    let (w, nrows) = (sn.ncols, sn.nrows());
    let f = &mut f[..nrows];
    let at = sn.start - base;
    f[..w].copy_from_slice(&own[at..at + w]);
    for (&r, v) in sn.pattern.iter().zip(&mut f[w..]) {
        *v = match rows {
            Reads::All => own[r - base],
            Reads::Top { end, top_pos, top } => {
                if r < *end {
                    own[r - base]
                } else {
                    top[top_pos[r] as usize]
                }
            }
        };
    }
    let panels: Vec<usize> = (0..w).step_by(PANEL).collect();
    for &a in panels.iter().rev() {
        let b = (a + PANEL).min(w);
        let (head, below) = f.split_at_mut(b);
        let panel = &mut head[a..b];
        if parallel && below.len() * (b - a) >= PAR_ENTRIES {
            let arch = pulp::Arch::new();
            let below = &*below;
            let s: Vec<Vec<[f64; W]>> = (a..b)
                .step_by(4)
                .collect::<Vec<_>>()
                .into_par_iter()
                .map(|c| {
                    arch.dispatch(ColumnDots {
                        sn,
                        cols: c..(c + 4).min(b),
                        from: b,
                        x: below,
                    })
                })
                .collect();
            for (x, s) in panel.iter_mut().zip(s.iter().flatten()) {
                sub(x, s);
            }
        } else {
            let s = column_dots(sn, a..b, b, below);
            for (x, s) in panel.iter_mut().zip(&s) {
                sub(x, s);
            }
        }
        for c in (a..b).rev() {
            let (left, right) = head.split_at_mut(c + 1);
            let s = dot(&sn.col(c, c + 1)[..b - c - 1], &right[..b - c - 1]);
            let x = &mut left[c];
            sub(x, &s);
            let d = sn.l[c * nrows + c];
            for v in x.iter_mut() {
                *v /= d;
            }
        }
    }
    own[at..at + w].copy_from_slice(&f[..w]);
}

#[inline(always)]
pub(super) fn sub<const W: usize>(a: &mut [f64; W], b: &[f64; W]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x -= y;
    }
}

/// [`dot`] of four columns at once (independent sums, each in row order:
/// the same bits).
#[inline(always)]
pub(super) fn dot4<const W: usize>(l: [&[f64]; 4], x: &[[f64; W]]) -> [[f64; W]; 4] {
    let n = x.len();
    let (l0, l1, l2, l3) = (&l[0][..n], &l[1][..n], &l[2][..n], &l[3][..n]);
    let mut acc = [[0.0; W]; 4];
    for i in 0..n {
        let row = &x[i];
        let li = [l0[i], l1[i], l2[i], l3[i]];
        for k in 0..4 {
            for j in 0..W {
                acc[k][j] = li[k].mul_add(row[j], acc[k][j]);
            }
        }
    }
    acc
}

/// Sum over rows of l_i x_i (x rows of W values), in row order.
#[inline(always)]
pub(super) fn dot<const W: usize>(l: &[f64], x: &[[f64; W]]) -> [f64; W] {
    let mut acc = [0.0; W];
    for (&li, row) in l.iter().zip(x) {
        for (a, &v) in acc.iter_mut().zip(row) {
            *a = li.mul_add(v, *a);
        }
    }
    acc
}
