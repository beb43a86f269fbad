//! Pixel geometry: clipping polylines to the plot rectangle (Liang-Barsky) and cutting them
//! into dashes.

/// A point in pixels (x to the right, y down).
pub(crate) type Px = (f64, f64);

/// An axis-aligned rectangle in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }

    pub fn contains(&self, p: Px) -> bool {
        p.0 >= self.x0 - 0.5 && p.0 <= self.x1 + 0.5 && p.1 >= self.y0 - 0.5 && p.1 <= self.y1 + 0.5
    }

    pub fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    pub fn inside(&self, o: &Rect) -> bool {
        self.x0 >= o.x0 && self.x1 <= o.x1 && self.y0 >= o.y0 && self.y1 <= o.y1
    }

    /// The overlap of two rectangles, if it has an area.
    pub fn intersect(&self, o: &Rect) -> Option<Rect> {
        let r = Rect {
            x0: self.x0.max(o.x0),
            y0: self.y0.max(o.y0),
            x1: self.x1.min(o.x1),
            y1: self.y1.min(o.y1),
        };
        (r.x1 > r.x0 && r.y1 > r.y0).then_some(r)
    }
}

/// The part of segment `a`-`b` inside `r` (Liang & Barsky 1984, parametric clipping), or `None`.
pub(crate) fn clip_segment(a: Px, b: Px, r: &Rect) -> Option<(Px, Px)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    if !(dx.is_finite() && dy.is_finite()) {
        return None;
    }
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - r.x0),
        (dx, r.x1 - a.0),
        (-dy, a.1 - r.y0),
        (dy, r.y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    let p = (a.0 + t0 * dx, a.1 + t0 * dy);
    let q = (a.0 + t1 * dx, a.1 + t1 * dy);
    (t0 <= t1).then_some((p, q))
}

/// Clips a polyline to `r`; the visible parts come back as separate polylines.
pub(crate) fn clip_polyline(pts: &[Px], r: &Rect) -> Vec<Vec<Px>> {
    let mut out: Vec<Vec<Px>> = Vec::new();
    let mut current: Vec<Px> = Vec::new();
    if pts.len() == 1 && r.contains(pts[0]) {
        return vec![pts.to_vec()];
    }
    for w in pts.windows(2) {
        match clip_segment(w[0], w[1], r) {
            Some((p, q)) => {
                let joined = current
                    .last()
                    .is_some_and(|l| (l.0 - p.0).abs() < 1e-9 && (l.1 - p.1).abs() < 1e-9);
                if !joined && !current.is_empty() {
                    out.push(std::mem::take(&mut current));
                }
                if current.is_empty() {
                    current.push(p);
                }
                current.push(q);
            }
            None => {
                if !current.is_empty() {
                    out.push(std::mem::take(&mut current));
                }
            }
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// Cuts a polyline into the "on" pieces of `pattern` (alternating on/off lengths in pixels,
/// starting with "on"); the pattern runs on across vertices. An empty pattern is a solid line.
pub(crate) fn dash_polyline(pts: &[Px], pattern: &[f64]) -> Vec<Vec<Px>> {
    if pattern.is_empty() || pattern.iter().any(|&l| l.is_nan() || l <= 0.0) {
        return vec![pts.to_vec()];
    }
    // An odd pattern repeated once is even, so on and off keep alternating.
    let pattern: Vec<f64> = if pattern.len() % 2 == 1 {
        pattern.repeat(2)
    } else {
        pattern.to_vec()
    };
    let mut out = Vec::new();
    let (mut k, mut left) = (0usize, pattern[0]);
    let mut current: Vec<Px> = pts.first().map(|&p| vec![p]).unwrap_or_default();
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let mut t = 0.0;
        while len - t > left {
            t += left;
            let p = (a.0 + (b.0 - a.0) * t / len, a.1 + (b.1 - a.1) * t / len);
            if k % 2 == 0 {
                current.push(p);
                out.push(std::mem::take(&mut current));
            } else {
                current = vec![p];
            }
            k = (k + 1) % pattern.len();
            left = pattern[k];
        }
        left -= len - t;
        if k % 2 == 0 {
            current.push(b);
        }
    }
    if k % 2 == 0 && current.len() > 1 {
        out.push(current);
    }
    out
}

/// M4 aggregation (Jugel et al., "M4: a visualization-oriented time series data aggregation",
/// PVLDB 7(10), 2014): of a polyline whose x never decreases, keeps per pixel column only the
/// first, lowest, highest and last point, in their original order. A line drawn through them
/// covers the same pixels of each column as the full polyline, so a 100 000-sample time
/// history is drawn from at most four points per column.
pub(crate) fn m4_decimate(pts: &[Px]) -> Vec<Px> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < pts.len() {
        let col = pts[start].0.floor();
        let mut end = start;
        while end < pts.len() && pts[end].0.floor() == col {
            end += 1;
        }
        let run = &pts[start..end];
        let lowest = (0..run.len()).fold(0, |b, i| if run[i].1 < run[b].1 { i } else { b });
        let highest = (0..run.len()).fold(0, |b, i| if run[i].1 > run[b].1 { i } else { b });
        let mut keep = [0, lowest, highest, run.len() - 1];
        keep.sort_unstable();
        for (k, &i) in keep.iter().enumerate() {
            if k == 0 || i != keep[k - 1] {
                out.push(run[i]);
            }
        }
        start = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: Rect = Rect {
        x0: 0.0,
        y0: 0.0,
        x1: 10.0,
        y1: 10.0,
    };

    // Intersections of straight lines with the box edges are exact in binary here (halves),
    // so the comparisons allow only rounding (1e-12).
    #[test]
    fn clipping_a_diagonal() {
        let (p, q) = clip_segment((-5.0, 5.0), (5.0, 15.0), &R).unwrap();
        assert!(
            (p.0 - 0.0).abs() < 1e-12 && (p.1 - 10.0).abs() < 1e-12,
            "{p:?}"
        );
        assert!(
            (q.0 - 0.0).abs() < 1e-12 && (q.1 - 10.0).abs() < 1e-12,
            "{q:?}"
        );
        let (p, q) = clip_segment((-5.0, 2.5), (15.0, 7.5), &R).unwrap();
        assert!((p.1 - 3.75).abs() < 1e-12 && (q.1 - 6.25).abs() < 1e-12);
        assert!(clip_segment((-1.0, -1.0), (-1.0, 20.0), &R).is_none());
    }

    #[test]
    fn polyline_leaving_and_reentering_splits_in_two() {
        let parts = clip_polyline(&[(1.0, 5.0), (20.0, 5.0), (20.0, 6.0), (1.0, 6.0)], &R);
        assert_eq!(parts.len(), 2);
        assert_eq!(parts[0], vec![(1.0, 5.0), (10.0, 5.0)]);
        assert_eq!(parts[1], vec![(10.0, 6.0), (1.0, 6.0)]);
    }

    #[test]
    fn m4_keeps_every_column_extent() {
        // A fast oscillation, 50 samples per pixel column over 40 columns.
        let pts: Vec<Px> = (0..2000)
            .map(|i| {
                (
                    i as f64 / 50.0,
                    (i as f64 * 0.7).sin() * 10.0 + i as f64 * 0.01,
                )
            })
            .collect();
        let kept = m4_decimate(&pts);
        assert!(kept.len() <= 4 * 40, "{}", kept.len());
        // Per column, the kept points span exactly the same y range and start and end at the
        // same points as the original (they are a subset, so the comparison is exact).
        let extent = |v: &[Px], col: f64| {
            let c: Vec<&Px> = v.iter().filter(|p| p.0.floor() == col).collect();
            let lo = c.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
            let hi = c.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
            (lo, hi, *c[0], *c[c.len() - 1])
        };
        for col in 0..40 {
            assert_eq!(
                extent(&pts, col as f64),
                extent(&kept, col as f64),
                "column {col}"
            );
        }
    }

    #[test]
    fn dashes_cover_the_on_fraction() {
        // A 100 px line with a 6-on/4-off pattern: 10 dashes of 6 px = 60 px of ink exactly.
        let dashes = dash_polyline(&[(0.0, 0.0), (40.0, 0.0), (40.0, 60.0)], &[6.0, 4.0]);
        let ink: f64 = dashes
            .iter()
            .map(|d| {
                d.windows(2)
                    .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
                    .sum::<f64>()
            })
            .sum();
        assert_eq!(dashes.len(), 10);
        assert!((ink - 60.0).abs() < 1e-9, "{ink}");
    }
}
