//! Typed errors of the finite-element stage.

/// Why a material's constants cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MaterialError {
    #[error("a constant is not a finite number")]
    NotFinite,
    #[error("density {0} kg/m^3 is not positive")]
    NonPositiveDensity(f64),
    #[error("the material axis has zero length")]
    ZeroAxis,
    #[error(
        "the elasticity matrix is not positive definite (isotropic: need E > 0 and -1 < nu < 0.5; \
         engineering constants: need E_i, G_ij > 0 and nu_ij^2 < E_i/E_j, \
         1 - nu12 nu21 - nu23 nu32 - nu13 nu31 - 2 nu21 nu32 nu13 > 0)"
    )]
    NotPositiveDefinite,
}

/// Why an element matrix cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ElementError {
    #[error(
        "Jacobian determinant {det:.3e} is not positive at quadrature point {point} \
         (inverted element, or midside nodes curved too far)"
    )]
    NonPositiveJacobian { point: usize, det: f64 },
}

/// An error of the finite-element stage. Elements and nodes are named by their ids in the
/// mesh file.
///
/// Each message is complete in `Display`: a variant that wraps a [`MaterialError`] or an
/// [`ElementError`] prints it after its own context and does not also return it as
/// `source()`, so an error chain printed with `{:#}` (anyhow) shows every piece once.
#[derive(Debug, thiserror::Error)]
pub enum FeError {
    #[error(
        "element {element} has no material ({others} more elements have none): \
         give its element set a *SOLID SECTION or a material override"
    )]
    NoMaterial { element: u64, others: usize },
    #[error("material '{material}' (section of element set '{element_set}') is not defined")]
    UnknownMaterial {
        material: String,
        element_set: String,
    },
    #[error("material '{material}' has no {missing}")]
    IncompleteMaterial {
        material: String,
        missing: &'static str,
    },
    #[error("material '{material}': {error}")]
    InvalidMaterial {
        material: String,
        error: MaterialError,
    },
    #[error("no element set named '{0}'")]
    UnknownElementSet(String),
    #[error("no node set named '{0}'")]
    UnknownNodeSet(String),
    #[error(
        "a restraint direction of node index {node} has zero length or is not finite (or the node is on the rotation axis, where radial and tangential are undefined)"
    )]
    BadDirection { node: u32 },
    #[error("the rotation axis has zero length or is not finite, or its point is not finite")]
    BadAxis,
    #[error("restraint names node index {index}, but the mesh has {num_nodes} nodes")]
    NodeOutOfRange { index: u32, num_nodes: usize },
    #[error("element {element} uses node index {node}, but the mesh has {num_nodes} nodes")]
    BadConnectivity {
        element: u64,
        node: u32,
        num_nodes: usize,
    },
    #[error("the mesh has {nodes} nodes; at most {max} are supported")]
    TooManyNodes { nodes: usize, max: usize },
    #[error("the material table covers {table} elements, the mesh has {mesh}")]
    TableMismatch { table: usize, mesh: usize },
    #[error("element {element} refers to material entry {index}, but the table has {entries}")]
    MaterialIndex {
        element: u64,
        index: u32,
        entries: usize,
    },
    #[error("the dof map was built for {map} nodes, the mesh has {mesh}")]
    DofMapMismatch { map: usize, mesh: usize },
    #[error("element {element}: {error}")]
    Element { element: u64, error: ElementError },
    #[error(transparent)]
    Quadrature(#[from] squeal_element::QuadratureError),
    #[error(transparent)]
    Io(#[from] squeal_io::IoError),
}

impl FeError {
    /// Wraps an [`ElementError`] of the element with file id `element`.
    pub(crate) fn in_element(element: u64) -> impl Fn(ElementError) -> Self + Copy {
        move |error| FeError::Element { element, error }
    }
}
