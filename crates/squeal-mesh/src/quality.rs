//! Mesh quality checks, each finding reported with the file ids it concerns.
//!
//! | finding | severity |
//! |---|---|
//! | inverted element: Jacobian determinant ≤ 0 at a node or sample point | error |
//! | element referencing a node that does not exist | error |
//! | badly curved element: min/max of the Jacobian determinant below [`QualityOptions::min_jacobian_ratio`] | warning |
//! | nodes at the same coordinates (within a tolerance relative to the mesh size) | warning |
//! | nodes used by no element | warning |
//! | named node or element sets that are empty | warning |
//! | set members naming ids that do not exist | warning |
//!
//! The Jacobian determinant of a 10-node tetrahedron is a cubic polynomial; it is sampled at the
//! ten nodes, the centroid and the four points of the degree-2 Gauss rule. A straight-sided
//! element has a constant determinant (ratio 1). The other kinds are sampled at their nodes
//! (the pyramid's apex excepted) and at the points of their stiffness rule
//! ([`squeal_element::ReferenceElement::jacobian_samples`]); there a ratio below 1 also
//! comes from a non-affine shape (a hexahedron that is not a parallelepiped), not only from
//! curved edges.

use crate::model::{BlockVisitor, Dangling, Mesh};
use squeal_element::{ReferenceElement, Tet10};

/// How serious a finding is: errors make the mesh unusable for analysis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// The mesh cannot be analysed as it is (inverted elements, elements left out for a
    /// missing node). Sorts before [`Severity::Warning`].
    Error,
    /// Worth a look, but the mesh can be analysed.
    Warning,
}

/// What a finding is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FindingKind {
    /// Elements whose Jacobian determinant is ≤ 0 (or NaN) at a node or sample point (an
    /// error; ids: the elements).
    InvertedElement,
    /// Elements that name a node the file never defined and were left out of the mesh (an
    /// error; ids: the elements).
    MissingNode,
    /// Elements whose min/max Jacobian determinant ratio is below
    /// [`QualityOptions::min_jacobian_ratio`] (a warning; ids: the elements).
    CurvedElement,
    /// Pairs of nodes at the same coordinates within [`QualityOptions::duplicate_tolerance`]
    /// (a warning; ids: the two node ids of each pair, one pair after the other).
    DuplicateNodes,
    /// Nodes that no element uses (a warning; ids: the nodes).
    UnusedNodes,
    /// A named node or element set without members (a warning, one per set; no ids, the
    /// message names the set).
    EmptySet,
    /// Members of one set naming ids the file never defined (a warning, one per set; ids: the
    /// missing ids).
    DanglingSetMember,
}

/// One finding: a message and the file ids (element or node ids) it concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// Whether it makes the mesh unusable.
    pub severity: Severity,
    /// Which check found it.
    pub kind: FindingKind,
    /// One line for the user: how many, what is wrong, and an example where useful.
    pub message: String,
    /// Element ids for element findings, node ids for node findings (pairs for duplicates).
    pub ids: Vec<u64>,
}

/// Thresholds of the checks.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct QualityOptions {
    /// Elements whose min/max Jacobian determinant ratio falls below this are reported as
    /// badly curved. 0.2 flags midside nodes moved by roughly a quarter of the edge length.
    pub min_jacobian_ratio: f64,
    /// Two nodes whose coordinates all differ by at most this times the bounding-box diagonal
    /// count as duplicates.
    pub duplicate_tolerance: f64,
}

impl Default for QualityOptions {
    fn default() -> Self {
        Self {
            min_jacobian_ratio: 0.2,
            duplicate_tolerance: 1e-9,
        }
    }
}

/// All findings, plus summary figures of the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct QualityReport {
    /// Every finding, errors first.
    pub findings: Vec<Finding>,
    /// Sum of element volumes (the mesh's length unit cubed; inverted elements count
    /// negatively).
    pub volume: f64,
    /// Smallest min/max Jacobian determinant ratio over all elements (1 for straight-sided).
    pub worst_jacobian_ratio: f64,
}

impl QualityReport {
    /// The findings of [`Severity::Error`].
    pub fn errors(&self) -> impl Iterator<Item = &Finding> {
        self.findings
            .iter()
            .filter(|f| f.severity == Severity::Error)
    }

    /// The findings of [`Severity::Warning`].
    pub fn warnings(&self) -> impl Iterator<Item = &Finding> {
        self.findings
            .iter()
            .filter(|f| f.severity == Severity::Warning)
    }

    /// Whether any finding is an error (the mesh is then unusable for analysis).
    pub fn has_errors(&self) -> bool {
        self.errors().next().is_some()
    }
}

/// Min and max of the Jacobian determinant over the sample points of one tet10 element: the
/// ten nodes, the centroid and the four Gauss points of the degree-2 rule.
pub fn jacobian_range(x: &[[f64; 3]; 10]) -> (f64, f64) {
    squeal_element::reference::jacobian_range::<Tet10, 10>(x)
}

/// Runs every check.
pub fn check(mesh: &Mesh, opts: &QualityOptions) -> QualityReport {
    let mut findings = Vec::new();
    let (volume, worst) = check_elements(mesh, opts, &mut findings);
    check_dangling(mesh, &mut findings);
    check_duplicates(mesh, opts, &mut findings);
    check_unused(mesh, &mut findings);
    check_empty_sets(mesh, &mut findings);
    findings.sort_by_key(|f| f.severity);
    QualityReport {
        findings,
        volume,
        worst_jacobian_ratio: worst,
    }
}

/// Inverted and badly curved elements, volume and worst ratio, block by block.
struct ElementCheck<'a> {
    mesh: &'a Mesh,
    opts: &'a QualityOptions,
    inverted: Vec<u64>,
    curved: Vec<u64>,
    volume: f64,
    worst: f64,
}

impl BlockVisitor for ElementCheck<'_> {
    type Error = std::convert::Infallible;

    fn block<E: ReferenceElement<N>, const N: usize>(
        &mut self,
        first: usize,
        conn: &[[u32; N]],
    ) -> Result<(), Self::Error> {
        for (i, c) in conn.iter().enumerate() {
            let x = self.mesh.coords(c);
            self.volume += E::volume(&x);
            let (lo, hi) = squeal_element::reference::jacobian_range::<E, N>(&x);
            let id = self.mesh.element_ids[first + i];
            if lo.is_nan() || lo <= 0.0 {
                self.inverted.push(id);
                self.worst = self.worst.min(0.0);
            } else {
                let ratio = lo / hi;
                self.worst = self.worst.min(ratio);
                if ratio < self.opts.min_jacobian_ratio {
                    self.curved.push(id);
                }
            }
        }
        Ok(())
    }
}

fn check_elements(mesh: &Mesh, opts: &QualityOptions, findings: &mut Vec<Finding>) -> (f64, f64) {
    let mut check = ElementCheck {
        mesh,
        opts,
        inverted: Vec::new(),
        curved: Vec::new(),
        volume: 0.0,
        worst: 1.0,
    };
    let Ok(()) = mesh.blocks.visit(&mut check);
    let ElementCheck {
        inverted,
        curved,
        volume,
        worst,
        ..
    } = check;
    if !inverted.is_empty() {
        findings.push(Finding {
            severity: Severity::Error,
            kind: FindingKind::InvertedElement,
            message: format!(
                "{} inverted element(s): Jacobian determinant <= 0 at a node or sample point",
                inverted.len()
            ),
            ids: inverted,
        });
    }
    if !curved.is_empty() {
        findings.push(Finding {
            severity: Severity::Warning,
            kind: FindingKind::CurvedElement,
            message: format!(
                "{} badly curved element(s): min/max Jacobian determinant below {}",
                curved.len(),
                opts.min_jacobian_ratio
            ),
            ids: curved,
        });
    }
    (volume, worst)
}

fn check_dangling(mesh: &Mesh, findings: &mut Vec<Finding>) {
    let mut elements = Vec::new();
    let mut missing_nodes = Vec::new();
    let mut members: Vec<(String, u64)> = Vec::new();
    for d in &mesh.dangling {
        match d {
            Dangling::ElementNode { element, node } => {
                if elements.last() != Some(element) {
                    elements.push(*element);
                }
                missing_nodes.push(*node);
            }
            Dangling::NodeSetMember { set, node } => {
                members.push((format!("node set {set}"), *node))
            }
            Dangling::ElementSetMember { set, element } => {
                members.push((format!("element set {set}"), *element))
            }
        }
    }
    if !elements.is_empty() {
        missing_nodes.sort_unstable();
        missing_nodes.dedup();
        findings.push(Finding {
            severity: Severity::Error,
            kind: FindingKind::MissingNode,
            message: format!(
                "{} element(s) reference {} node id(s) that are not defined (e.g. node {}); they were left out",
                elements.len(),
                missing_nodes.len(),
                missing_nodes[0]
            ),
            ids: elements,
        });
    }
    let mut i = 0;
    while i < members.len() {
        let set = members[i].0.clone();
        let ids: Vec<u64> = members[i..]
            .iter()
            .take_while(|(s, _)| *s == set)
            .map(|(_, id)| *id)
            .collect();
        i += ids.len();
        findings.push(Finding {
            severity: Severity::Warning,
            kind: FindingKind::DanglingSetMember,
            message: format!("{set} names {} id(s) that are not defined", ids.len()),
            ids,
        });
    }
}

fn check_duplicates(mesh: &Mesh, opts: &QualityOptions, findings: &mut Vec<Finding>) {
    let Some((lo, hi)) = mesh.bounding_box() else {
        return;
    };
    let diag = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
    let tol = opts.duplicate_tolerance * diag.max(f64::MIN_POSITIVE);
    let mut order: Vec<usize> = (0..mesh.num_nodes()).collect();
    order.sort_by(|&a, &b| {
        mesh.nodes[a][0]
            .total_cmp(&mesh.nodes[b][0])
            .then(a.cmp(&b))
    });
    let mut pairs = Vec::new();
    for (k, &a) in order.iter().enumerate() {
        let pa = mesh.nodes[a];
        for &b in &order[k + 1..] {
            let pb = mesh.nodes[b];
            if pb[0] - pa[0] > tol {
                break;
            }
            if (pb[1] - pa[1]).abs() <= tol && (pb[2] - pa[2]).abs() <= tol {
                let (i, j) = (
                    mesh.node_ids[a].min(mesh.node_ids[b]),
                    mesh.node_ids[a].max(mesh.node_ids[b]),
                );
                pairs.push((i, j));
            }
        }
    }
    if !pairs.is_empty() {
        pairs.sort_unstable();
        findings.push(Finding {
            severity: Severity::Warning,
            kind: FindingKind::DuplicateNodes,
            message: format!(
                "{} pair(s) of nodes at the same coordinates (within {tol:.1e}), e.g. nodes {} and {}",
                pairs.len(),
                pairs[0].0,
                pairs[0].1
            ),
            ids: pairs.iter().flat_map(|&(i, j)| [i, j]).collect(),
        });
    }
}

fn check_unused(mesh: &Mesh, findings: &mut Vec<Finding>) {
    let used = mesh.used_nodes();
    let unused: Vec<u64> = used
        .iter()
        .enumerate()
        .filter(|(_, u)| !**u)
        .map(|(i, _)| mesh.node_ids[i])
        .collect();
    if !unused.is_empty() {
        findings.push(Finding {
            severity: Severity::Warning,
            kind: FindingKind::UnusedNodes,
            message: format!(
                "{} node(s) used by no element (they get no degrees of freedom)",
                unused.len()
            ),
            ids: unused,
        });
    }
}

fn check_empty_sets(mesh: &Mesh, findings: &mut Vec<Finding>) {
    for (name, set) in &mesh.node_sets {
        if set.is_empty() {
            findings.push(Finding {
                severity: Severity::Warning,
                kind: FindingKind::EmptySet,
                message: format!("node set {name} is empty"),
                ids: Vec::new(),
            });
        }
    }
    for (name, set) in &mesh.element_sets {
        if set.is_empty() {
            findings.push(Finding {
                severity: Severity::Warning,
                kind: FindingKind::EmptySet,
                message: format!("element set {name} is empty"),
                ids: Vec::new(),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builder::MeshBuilder;
    use crate::generate::box_tet10;

    #[test]
    fn clean_box_has_no_findings_and_exact_volume() {
        let m = box_tet10([1.0, 2.0, 3.0], [2, 2, 2]);
        let r = check(&m, &QualityOptions::default());
        assert!(r.findings.is_empty(), "{:?}", r.findings);
        // Straight-sided elements: the volume is exact to round-off, the ratio exactly 1.
        assert!((r.volume - 6.0).abs() < 1e-13);
        assert!((r.worst_jacobian_ratio - 1.0).abs() < 1e-12);
    }

    #[test]
    fn detects_inverted_curved_duplicate_unused_missing_and_empty() {
        let mut m = box_tet10([1.0, 1.0, 1.0], [1, 1, 1]);
        // Invert element 0 by swapping two vertices (and their edges) of its connectivity.
        let c = m.blocks.tet10[0];
        m.blocks.tet10[0] = [c[0], c[2], c[1], c[3], c[6], c[5], c[4], c[7], c[9], c[8]];
        // Curve element 1: move a midside node from 1/2 to 3/10 of its edge (1/4 would make det J vanish at the vertex; along the edge det J then ranges 0.2..2.0).
        let e1 = m.blocks.tet10[1];
        let (mid, v) = (e1[4] as usize, e1[0] as usize);
        for d in 0..3 {
            m.nodes[mid][d] += (m.nodes[v][d] - m.nodes[mid][d]) * 0.4;
        }
        // An unused node duplicating node 0's position, and an empty set.
        m.nodes.push(m.nodes[0]);
        m.node_ids.push(9999);
        m.node_sets.insert("NOTHING".into(), vec![]);
        let r = check(&m, &QualityOptions::default());
        let kinds: Vec<FindingKind> = r.findings.iter().map(|f| f.kind).collect();
        assert!(kinds.contains(&FindingKind::InvertedElement));
        assert!(kinds.contains(&FindingKind::CurvedElement));
        assert!(kinds.contains(&FindingKind::DuplicateNodes));
        assert!(kinds.contains(&FindingKind::UnusedNodes));
        assert!(kinds.contains(&FindingKind::EmptySet));
        let inv = r
            .findings
            .iter()
            .find(|f| f.kind == FindingKind::InvertedElement)
            .unwrap();
        assert_eq!(inv.ids, vec![m.element_ids[0]]);
        assert_eq!(inv.severity, Severity::Error);
        let dup = r
            .findings
            .iter()
            .find(|f| f.kind == FindingKind::DuplicateNodes)
            .unwrap();
        assert_eq!(dup.ids, vec![m.node_ids[0], 9999]);

        let mut b = MeshBuilder::new();
        b.add_element(5, [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]).unwrap();
        let r = check(&b.finish(), &QualityOptions::default());
        assert_eq!(r.findings[0].kind, FindingKind::MissingNode);
        assert_eq!(r.findings[0].ids, vec![5]);
        assert!(r.has_errors());
    }
}
