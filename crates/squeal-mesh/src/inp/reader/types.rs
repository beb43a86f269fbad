//! Element type names (which are quadratic solids, how many nodes the others have) and `*NODE` data lines.

use super::*;

/// Whether an element type is a 10-node tetrahedron: `C3D10` and its variants (`C3D10M`,
/// `C3D10H`, `C3D10HS`, `C3D10I`, ...), which share its geometry and node order.
#[cfg(test)]
pub(super) fn is_tet10(ty: &str) -> bool {
    solid_kind(ty) == Some(ElementKind::Tet10)
}

/// The solid kind of an element type: `C3D10` and its variants (`C3D10M`, `C3D10H`,
/// `C3D10HS`, `C3D10I`, ...), `C3D20` and `C3D20R` and their variants (`C3D20H`,
/// `C3D20RH`, ...), `C3D15` and its variants but the variable-node `C3D15V`: each shares its
/// base element's geometry and node order (Abaqus's order is the canonical one).
pub(super) fn solid_kind(ty: &str) -> Option<ElementKind> {
    let variant = |base: &str| {
        ty.strip_prefix(base)
            .is_some_and(|rest| rest.chars().all(|c| c.is_ascii_alphabetic()))
    };
    if variant("C3D10") {
        Some(ElementKind::Tet10)
    } else if variant("C3D20") {
        Some(ElementKind::Hex20)
    } else if variant("C3D15") && !ty.contains('V') {
        Some(ElementKind::Wedge15)
    } else {
        None
    }
}

/// Node count of common element types squeal skips, so that their records can be delimited
/// even with a stray trailing comma; `None` for types not listed (then a record continues
/// exactly while its lines end with a comma).
pub(super) fn other_node_count(ty: &str) -> Option<usize> {
    const TABLE: &[(&str, usize)] = &[
        ("C3D20", 20),
        ("C3D15", 15),
        ("C3D8", 8),
        ("C3D6", 6),
        ("C3D4", 4),
        ("DC3D10", 10),
        ("DC3D20", 20),
        ("DC3D8", 8),
        ("DC3D4", 4),
        ("STRI65", 6),
        ("STRI3", 3),
        ("S9", 9),
        ("S8", 8),
        ("S6", 6),
        ("S4", 4),
        ("S3", 3),
        ("M3D9", 9),
        ("M3D8", 8),
        ("M3D6", 6),
        ("M3D4", 4),
        ("M3D3", 3),
        ("CPS8", 8),
        ("CPE8", 8),
        ("CAX8", 8),
        ("CPS6", 6),
        ("CPE6", 6),
        ("CAX6", 6),
        ("CPS4", 4),
        ("CPE4", 4),
        ("CAX4", 4),
        ("CPS3", 3),
        ("CPE3", 3),
        ("CAX3", 3),
        ("B31", 2),
        ("B32", 3),
        ("B33", 2),
        ("T3D2", 2),
        ("T3D3", 3),
    ];
    TABLE.iter().find_map(|&(prefix, n)| {
        let rest = ty.strip_prefix(prefix)?;
        (rest.is_empty() || rest.starts_with(|c: char| c.is_ascii_alphabetic())).then_some(n)
    })
}

/// `id, x[, y[, z]]` (blank or missing coordinates are zero; up to three more fields, the
/// normal direction Abaqus allows, are read and ignored).
pub(super) fn node_line(text: &str) -> Result<(u64, [f64; 3]), String> {
    const WHAT: [&str; 6] = ["x", "y", "z", "normal x", "normal y", "normal z"];
    let mut it = fields(text);
    let first = it
        .next()
        .ok_or("expected a node line 'id, x, y[, z]', found an empty line")?;
    let id = label(first).ok_or_else(|| {
        format!(
            "expected a node id (a non-negative integer), found '{}'",
            excerpt(first)
        )
    })?;
    let mut x = [0.0; 3];
    let mut n = 0;
    for f in it {
        let Some(what) = WHAT.get(n) else {
            return Err(format!(
                "node {id} has more than 6 numbers after its id; expected 'id, x, y[, z]' (and at most a normal)"
            ));
        };
        let v = real_or_zero(f).ok_or_else(|| {
            format!(
                "expected the {what} coordinate of node {id} as a number, found '{}'",
                excerpt(f)
            )
        })?;
        if n < 3 {
            x[n] = v;
        }
        n += 1;
    }
    if n == 0 {
        return Err(format!(
            "node {id} has no coordinates: expected 'id, x, y[, z]'"
        ));
    }
    Ok((id, x))
}
