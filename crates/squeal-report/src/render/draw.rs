//! Drawing a laid-out panel: grid lines, cells, bars, series, reference lines, axes, legend
//! and point labels.

use super::*;

/// Draws one panel inside `cell`; returns its notes.
pub(super) fn draw_panel<DB: DrawingBackend>(
    p: &Painter<DB>,
    panel: &Panel,
    cell: Rect,
    name: &str,
) -> Result<Vec<String>, ReportError> {
    let z = &p.z;
    let s = p.s;
    let d = prepare_panel(panel, name)?;
    let mut legend = if panel.legend == LegendPosition::None {
        None
    } else {
        build_legend(&d, z, s)
    };
    let mut outside = match panel.legend {
        LegendPosition::Outside => true,
        LegendPosition::Auto => {
            d.grid.is_some() || legend.as_ref().is_some_and(|l| l.entries.len() > 8)
        }
        _ => false,
    };
    let legend_right = match (&legend, outside) {
        (Some(l), true) => l.w + 2.0 * z.pad,
        _ => 0.0,
    };
    let footnotes: Vec<String> = if d.footnotes.len() > MAX_FOOTNOTES {
        let mut f = d.footnotes[..MAX_FOOTNOTES - 1].to_vec();
        f.push(format!(
            "... and {} more notes",
            d.footnotes.len() - (MAX_FOOTNOTES - 1)
        ));
        f
    } else {
        d.footnotes.clone()
    };

    let mut lay = layout_panel(panel, &d, cell, legend_right, footnotes.len(), z, name)?;
    // Auto: an inside legend that would hide more than 2 % of the ink goes outside instead,
    // if the plot keeps at least 60 % of its width.
    let mut ink = ink_points(&lay.f, &d, panel, 3.0 * s);
    if let (Some(l), false, LegendPosition::Auto) = (&legend, outside, panel.legend) {
        let (_, covered) = legend_origin(l, &lay.f, &ink, panel, false, z);
        if covered as f64 > 0.02 * ink.len() as f64 {
            let wide = layout_panel(panel, &d, cell, l.w + 2.0 * z.pad, footnotes.len(), z, name);
            if let Some(wide) = wide.ok().filter(|w| w.f.r.width() >= 0.6 * lay.f.r.width()) {
                lay = wide;
                outside = true;
                ink = ink_points(&lay.f, &d, panel, 3.0 * s);
            }
        }
    }
    let PanelLayout {
        f,
        x_ticks,
        y_ticks,
        x_title,
        y_title,
        tick_h,
        xlabel_h,
        ylabel_w,
        foot_h,
    } = lay;

    draw_grid_lines(p, &f, &x_ticks, &y_ticks, panel)?;
    if let Some(g) = &d.grid {
        draw_cells(p, &f, g)?;
    }
    draw_bars(p, &f, &d, panel.y_scale)?;
    for ps in &d.series {
        draw_series(p, &f, ps)?;
    }
    let mut obstacles: Obstacles = Vec::new();
    draw_reference_lines(p, &f, panel, &mut obstacles)?;
    draw_axes(p, &f, &x_ticks, &y_ticks)?;

    // Legend: outside, a fixed corner, or the corner covering the fewest points.
    if let Some(l) = legend.take() {
        let (at, _) = legend_origin(&l, &f, &ink, panel, outside, z);
        let r = Rect {
            x0: at.0,
            y0: at.1,
            x1: at.0 + l.w,
            y1: at.1 + l.h,
        };
        draw_legend(p, &l, r)?;
        obstacles.push(r);
    }
    draw_point_labels(p, &f, panel, &ink, &mut obstacles)?;

    // Texts around the plot, centred on it and kept inside the panel.
    let cx = (f.r.x0 + f.r.x1) / 2.0;
    let room = 2.0 * (cx - cell.x0).min(cell.x1 - cx) - 2.0 * z.pad;
    let centre = (HPos::Center, VPos::Center);
    if !panel.title.is_empty() {
        let at = (cx, cell.y0 + z.pad + z.title * 0.8);
        p.text_fit((&panel.title, ""), at, z.title, room, centre, false)?;
    }
    let xt_y = f.r.y1 + z.tick_len + 3.0 * s;
    let xl_y = xt_y + tick_h + xlabel_h * 0.5;
    p.text_fit(
        (&x_title.0, &x_title.1),
        (cx, xl_y),
        z.axis,
        room,
        centre,
        false,
    )?;
    let yl_x = cell.x0 + z.pad + ylabel_w * 0.5;
    let y_room = f.r.height() + 2.0 * z.tick;
    p.text_fit(
        (&y_title.0, &y_title.1),
        (yl_x, (f.r.y0 + f.r.y1) / 2.0),
        z.axis,
        y_room,
        centre,
        true,
    )?;
    for (k, note) in footnotes.iter().enumerate() {
        let y = cell.y1 - z.pad - foot_h + (k as f64 + 0.5) * z.note * 1.3;
        let (t, size) = fit_text(note, "", z.note, cell.width() - 2.0 * z.pad);
        p.text(
            &t,
            (cell.x0 + z.pad, y),
            size,
            NOTE,
            (HPos::Left, VPos::Center),
        )?;
    }
    if d.series.is_empty() && d.grid.is_none() {
        let c = ((f.r.x0 + f.r.x1) / 2.0, (f.r.y0 + f.r.y1) / 2.0);
        p.text(
            "no data to show",
            c,
            z.axis,
            NOTE,
            (HPos::Center, VPos::Center),
        )?;
    }
    Ok(d.notes)
}

/// Automatic x ticks thinned until their labels fit side by side.
pub(super) fn fit_x_ticks(panel: &Panel, xr: (f64, f64), plot_w: f64, z: &Sizes) -> AxisTicks {
    let mut count = ((plot_w / (z.tick * 4.5)) as usize).clamp(2, 12);
    loop {
        let t = axis_ticks(&panel.x_ticks, panel.x_scale, xr, count);
        let widest = t
            .major
            .iter()
            .map(|t| text_size(&t.label, z.tick).0)
            .fold(0.0, f64::max);
        let fits = (widest + z.tick) * t.major.len() as f64 <= plot_w;
        if fits || count <= 2 || !panel.x_ticks.is_empty() {
            return t;
        }
        count -= 1;
    }
}

pub(super) fn draw_grid_lines<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    xt: &AxisTicks,
    yt: &AxisTicks,
    panel: &Panel,
) -> Result<(), ReportError> {
    let w = p.s.max(1.0);
    if panel.x_scale == Scale::Log {
        for &x in &xt.minor {
            p.polyline(&[(f.px(x), f.r.y0), (f.px(x), f.r.y1)], GRID_MINOR, w)?;
        }
    }
    if panel.y_scale == Scale::Log {
        for &y in &yt.minor {
            p.polyline(&[(f.r.x0, f.py(y)), (f.r.x1, f.py(y))], GRID_MINOR, w)?;
        }
    }
    for t in &xt.major {
        p.polyline(
            &[(f.px(t.pos), f.r.y0), (f.px(t.pos), f.r.y1)],
            GRID_MAJOR,
            w,
        )?;
    }
    for t in &yt.major {
        p.polyline(
            &[(f.r.x0, f.py(t.pos)), (f.r.x1, f.py(t.pos))],
            GRID_MAJOR,
            w,
        )?;
    }
    Ok(())
}

pub(super) fn draw_cells<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    g: &PreparedGrid,
) -> Result<(), ReportError> {
    let nx = g.src.x.len();
    for (k, cell) in g.src.cells.iter().enumerate() {
        let (ix, iy) = (k % nx, k / nx);
        let r = Rect {
            x0: f.px(g.xe[ix]),
            x1: f.px(g.xe[ix + 1]),
            y0: f.py(g.ye[iy + 1]),
            y1: f.py(g.ye[iy]),
        };
        let Some(r) = r.intersect(&f.r) else { continue };
        let color = cell.map_or(MISSING_CELL, |c| g.colors[c]);
        let border =
            (r.width() > 8.0 * p.s && r.height() > 8.0 * p.s).then_some((Rgb(255, 255, 255), p.s));
        p.rect(&r, Some(color), border)?;
    }
    Ok(())
}

pub(super) fn draw_bars<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    d: &PanelData,
    y_scale: Scale,
) -> Result<(), ReportError> {
    if d.bar_count == 0 {
        return Ok(());
    }
    let width = d.bar_slot * 0.8 / d.bar_count as f64;
    let base = match y_scale {
        Scale::Linear => f.py(0.0_f64.clamp(f.yr.0, f.yr.1)),
        Scale::Log => f.r.y1,
    };
    for (j, ps) in d
        .series
        .iter()
        .filter(|ps| ps.src.kind == SeriesKind::Bars)
        .enumerate()
    {
        let offset = (j as f64 - (d.bar_count as f64 - 1.0) / 2.0) * width;
        for &(x, y) in ps.pts.iter().flatten() {
            let (xa, xb) = (
                f.px(x + offset - width / 2.0),
                f.px(x + offset + width / 2.0),
            );
            let yv = f.py(y);
            let r = Rect {
                x0: xa,
                x1: xb,
                y0: yv.min(base),
                y1: yv.max(base),
            };
            if let Some(r) = r.intersect(&f.r) {
                p.rect(&r, Some(ps.color), None)?;
            }
        }
    }
    Ok(())
}

/// Pixel polylines of a series: split at skipped points, long time histories reduced to four
/// points per pixel column ([`m4_decimate`]), clipped to the plot rectangle.
pub(super) fn series_pieces(f: &Frame, ps: &Prepared) -> Vec<Vec<Px>> {
    let mut pieces = Vec::new();
    let mut run: Vec<Px> = Vec::new();
    for q in &ps.pts {
        match q {
            Some(q) => run.push(f.map(*q)),
            None if !run.is_empty() => pieces.push(std::mem::take(&mut run)),
            None => {}
        }
    }
    if !run.is_empty() {
        pieces.push(run);
    }
    let columns = f.r.width().max(1.0);
    for piece in &mut pieces {
        let monotone = piece.windows(2).all(|w| w[1].0 >= w[0].0);
        if piece.len() as f64 > 4.0 * columns && monotone {
            *piece = m4_decimate(piece);
        }
    }
    pieces
        .iter()
        .flat_map(|piece| clip_polyline(piece, &f.r))
        .collect()
}

pub(super) fn draw_series<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    ps: &Prepared,
) -> Result<(), ReportError> {
    let kind = ps.src.kind;
    if matches!(kind, SeriesKind::Line | SeriesKind::LineMarkers) {
        let width = ps.src.line_width.clamp(0.5, 20.0) * p.s;
        for piece in series_pieces(f, ps) {
            p.dashed(&piece, ps.color, width, ps.src.dash)?;
        }
    }
    if matches!(kind, SeriesKind::Markers | SeriesKind::LineMarkers) {
        let valid: Vec<(f64, f64)> = ps.pts.iter().flatten().copied().collect();
        let n = valid.len();
        let step_through = kind == SeriesKind::LineMarkers && n > MAX_LINE_MARKERS;
        let picks: Vec<usize> = if step_through {
            (0..20).map(|i| i * (n - 1) / 19).collect()
        } else {
            (0..n).collect()
        };
        for i in picks {
            let at = f.map(valid[i]);
            if f.r.contains(at) {
                p.marker(at, ps.marker, ps.color)?;
            }
        }
    }
    Ok(())
}

pub(super) fn draw_reference_lines<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    panel: &Panel,
    obstacles: &mut Obstacles,
) -> Result<(), ReportError> {
    let z = &p.z;
    let w = 1.4 * p.s;
    for a in &panel.annotations {
        match a {
            Annotation::VLine { x, label, dash } => {
                let Some(x) = to_axis(panel.x_scale, *x).filter(|x| *x >= f.xr.0 && *x <= f.xr.1)
                else {
                    continue;
                };
                let px = f.px(x);
                p.dashed(&[(px, f.r.y0), (px, f.r.y1)], REFERENCE, w, *dash)?;
                let at = (px + 4.0 * p.s, f.r.y0 + 4.0 * p.s);
                let (tw, th) = text_size(label, z.annot);
                let fits = at.0 + tw <= f.r.x1;
                let (x0, anchor) = if fits {
                    (at.0, HPos::Left)
                } else {
                    (px - 4.0 * p.s, HPos::Right)
                };
                p.text(
                    label,
                    (x0, at.1 + th / 2.0),
                    z.annot,
                    REFERENCE,
                    (anchor, VPos::Center),
                )?;
                let bx = if fits { x0 } else { x0 - tw };
                obstacles.push(Rect {
                    x0: bx,
                    y0: at.1,
                    x1: bx + tw,
                    y1: at.1 + th,
                });
            }
            Annotation::HLine { y, label, dash } => {
                let Some(y) = to_axis(panel.y_scale, *y).filter(|y| *y >= f.yr.0 && *y <= f.yr.1)
                else {
                    continue;
                };
                let py = f.py(y);
                p.dashed(&[(f.r.x0, py), (f.r.x1, py)], REFERENCE, w, *dash)?;
                let (tw, th) = text_size(label, z.annot);
                let above = py - th - 3.0 * p.s >= f.r.y0;
                let cy = if above {
                    py - 3.0 * p.s - th / 2.0
                } else {
                    py + 3.0 * p.s + th / 2.0
                };
                let x1 = f.r.x1 - 4.0 * p.s;
                p.text(
                    label,
                    (x1, cy),
                    z.annot,
                    REFERENCE,
                    (HPos::Right, VPos::Center),
                )?;
                obstacles.push(Rect {
                    x0: x1 - tw,
                    y0: cy - th / 2.0,
                    x1,
                    y1: cy + th / 2.0,
                });
            }
            Annotation::Label { .. } => {}
        }
    }
    Ok(())
}

pub(super) fn draw_axes<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    xt: &AxisTicks,
    yt: &AxisTicks,
) -> Result<(), ReportError> {
    let z = &p.z;
    let w = p.s.max(1.0);
    p.rect(&f.r, None, Some((FRAME, w)))?;
    for t in &xt.major {
        let x = f.px(t.pos);
        p.polyline(&[(x, f.r.y1), (x, f.r.y1 + z.tick_len)], FRAME, w)?;
        p.text(
            &t.label,
            (x, f.r.y1 + z.tick_len + 3.0 * p.s),
            z.tick,
            TEXT,
            (HPos::Center, VPos::Top),
        )?;
    }
    for &x in &xt.minor {
        let x = f.px(x);
        p.polyline(&[(x, f.r.y1), (x, f.r.y1 + z.tick_len * 0.6)], FRAME, w)?;
    }
    for t in &yt.major {
        let y = f.py(t.pos);
        p.polyline(&[(f.r.x0 - z.tick_len, y), (f.r.x0, y)], FRAME, w)?;
        p.text(
            &t.label,
            (f.r.x0 - z.tick_len - 4.0 * p.s, y),
            z.tick,
            TEXT,
            (HPos::Right, VPos::Center),
        )?;
    }
    for &y in &yt.minor {
        let y = f.py(y);
        p.polyline(&[(f.r.x0 - z.tick_len * 0.6, y), (f.r.x0, y)], FRAME, w)?;
    }
    Ok(())
}

/// Pixels covered by the panel's data and reference lines, sampled every few pixels: what a
/// legend or a label should not hide.
pub(super) fn ink_points(f: &Frame, d: &PanelData, panel: &Panel, spacing: f64) -> Vec<Px> {
    let mut ink = Vec::new();
    let mut sample = |pts: &[Px]| {
        for w in pts.windows(2) {
            let n = ((w[1].0 - w[0].0).hypot(w[1].1 - w[0].1) / spacing)
                .ceil()
                .min(10_000.0) as usize;
            for k in 0..n.max(1) {
                let t = k as f64 / n.max(1) as f64;
                ink.push((
                    w[0].0 + t * (w[1].0 - w[0].0),
                    w[0].1 + t * (w[1].1 - w[0].1),
                ));
            }
        }
        ink.extend(pts.last());
    };
    for ps in &d.series {
        match ps.src.kind {
            SeriesKind::Line | SeriesKind::LineMarkers => {
                for piece in series_pieces(f, ps) {
                    sample(&piece);
                }
            }
            SeriesKind::Markers => {
                for &q in ps.pts.iter().flatten() {
                    sample(&[f.map(q)]);
                }
            }
            SeriesKind::Bars => {
                for &q in ps.pts.iter().flatten() {
                    let top = f.map(q);
                    sample(&[top, (top.0, f.r.y1)]);
                }
            }
        }
    }
    for a in &panel.annotations {
        match a {
            Annotation::VLine { x, .. } => {
                if let Some(x) = to_axis(panel.x_scale, *x) {
                    sample(&[(f.px(x), f.r.y0), (f.px(x), f.r.y1)]);
                }
            }
            Annotation::HLine { y, .. } => {
                if let Some(y) = to_axis(panel.y_scale, *y) {
                    sample(&[(f.r.x0, f.py(y)), (f.r.x1, f.py(y))]);
                }
            }
            Annotation::Label { at, .. } => {
                if let Some(q) = to_axis(panel.x_scale, at.0).zip(to_axis(panel.y_scale, at.1)) {
                    sample(&[f.map(q)]);
                }
            }
        }
    }
    ink.retain(|&q| f.r.contains(q));
    ink
}

/// Top-left corner of the legend box, and how many ink samples it hides.
pub(super) fn legend_origin(
    l: &Legend,
    f: &Frame,
    ink: &[Px],
    panel: &Panel,
    outside: bool,
    z: &Sizes,
) -> (Px, usize) {
    let inset = z.pad;
    let corner = |pos: LegendPosition| -> Px {
        let left = f.r.x0 + inset;
        let right = f.r.x1 - inset - l.w;
        let top = f.r.y0 + inset;
        let bottom = f.r.y1 - inset - l.h;
        match pos {
            LegendPosition::UpperLeft => (left, top),
            LegendPosition::LowerRight => (right, bottom),
            LegendPosition::LowerLeft => (left, bottom),
            _ => (right, top),
        }
    };
    let hidden = |at: Px| {
        let r = Rect {
            x0: at.0 - inset,
            y0: at.1 - inset,
            x1: at.0 + l.w + inset,
            y1: at.1 + l.h + inset,
        };
        ink.iter().filter(|&&q| r.contains(q)).count()
    };
    if outside {
        return ((f.r.x1 + 2.0 * z.pad, f.r.y0), 0);
    }
    if panel.legend != LegendPosition::Auto {
        let at = corner(panel.legend);
        return (at, hidden(at));
    }
    // Auto: the first corner (UR, UL, LR, LL) hiding the least ink.
    let candidates = [
        LegendPosition::UpperRight,
        LegendPosition::UpperLeft,
        LegendPosition::LowerRight,
        LegendPosition::LowerLeft,
    ];
    let mut best = (corner(LegendPosition::UpperRight), usize::MAX);
    for c in candidates {
        let at = corner(c);
        let covered = hidden(at);
        if covered < best.1 {
            best = (at, covered);
        }
    }
    best
}

pub(super) fn draw_legend<DB: DrawingBackend>(
    p: &Painter<DB>,
    l: &Legend,
    r: Rect,
) -> Result<(), ReportError> {
    let z = &p.z;
    let s = p.s;
    p.rect(
        &r,
        Some(Rgb(255, 255, 255)),
        Some((Rgb(190, 190, 190), s.max(1.0))),
    )?;
    for (k, (name, sample)) in l.entries.iter().enumerate() {
        let cy = r.y0 + z.pad + (k as f64 + 0.5) * l.row;
        let (sx0, sx1) = (r.x0 + z.pad, r.x0 + z.pad + 30.0 * s);
        match sample {
            Sample::Line {
                color,
                dash,
                width,
                marker,
            } => {
                if *width > 0.0 {
                    p.dashed(&[(sx0, cy), (sx1, cy)], *color, width * s, *dash)?;
                }
                if let Some(m) = marker {
                    p.marker(((sx0 + sx1) / 2.0, cy), *m, *color)?;
                }
            }
            Sample::Block(color) => {
                let h = l.row * 0.32;
                p.rect(
                    &Rect {
                        x0: sx0 + 4.0 * s,
                        x1: sx1 - 4.0 * s,
                        y0: cy - h,
                        y1: cy + h,
                    },
                    Some(*color),
                    None,
                )?;
            }
        }
        p.text(
            name,
            (sx1 + 6.0 * s, cy),
            z.legend,
            TEXT,
            (HPos::Left, VPos::Center),
        )?;
    }
    Ok(())
}

pub(super) fn draw_point_labels<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    panel: &Panel,
    ink: &[Px],
    obstacles: &mut Obstacles,
) -> Result<(), ReportError> {
    let z = &p.z;
    let gap = 5.0 * p.s;
    let labelled: Vec<(Px, &str)> = panel
        .annotations
        .iter()
        .filter_map(|a| match a {
            Annotation::Label { at, text } => to_axis(panel.x_scale, at.0)
                .zip(to_axis(panel.y_scale, at.1))
                .map(|q| f.map(q))
                .filter(|&q| f.r.contains(q))
                .map(|q| (q, text.as_str())),
            _ => None,
        })
        .collect();
    // The labelled points themselves are obstacles for every label.
    let r = z.marker + p.s;
    obstacles.extend(labelled.iter().map(|&(q, _)| Rect {
        x0: q.0 - r,
        y0: q.1 - r,
        x1: q.0 + r,
        y1: q.1 + r,
    }));
    for &(q, text) in &labelled {
        let (tw, th) = text_size(text, z.annot);
        // Right-above, right-below, left-above, left-below, right, left, above, below.
        let spots = [
            (q.0 + gap, q.1 - gap - th),
            (q.0 + gap, q.1 + gap),
            (q.0 - gap - tw, q.1 - gap - th),
            (q.0 - gap - tw, q.1 + gap),
            (q.0 + gap + 2.0 * p.s, q.1 - th / 2.0),
            (q.0 - gap - 2.0 * p.s - tw, q.1 - th / 2.0),
            (q.0 - tw / 2.0, q.1 - gap - th - 2.0 * p.s),
            (q.0 - tw / 2.0, q.1 + gap + 2.0 * p.s),
        ];
        // Cost: outside the plot or on another label is worst, then ink hidden; the first
        // spot wins ties.
        let cost = |b: &Rect| -> usize {
            let outside = if b.inside(&f.r) { 0 } else { 1_000_000 };
            let blocked = obstacles.iter().filter(|o| o.overlaps(b)).count() * 10_000;
            outside + blocked + ink.iter().filter(|&&i| b.contains(i)).count()
        };
        let mut best = (
            usize::MAX,
            Rect {
                x0: 0.0,
                y0: 0.0,
                x1: 0.0,
                y1: 0.0,
            },
        );
        for &(x, y) in &spots {
            let b = Rect {
                x0: x,
                y0: y,
                x1: x + tw,
                y1: y + th,
            };
            let c = cost(&b);
            if c < best.0 {
                best = (c, b);
            }
        }
        let chosen = best.1;
        p.text(
            text,
            (chosen.x0, (chosen.y0 + chosen.y1) / 2.0),
            z.annot,
            TEXT,
            (HPos::Left, VPos::Center),
        )?;
        obstacles.push(chosen);
    }
    Ok(())
}
