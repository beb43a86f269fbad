//! faer's sparse errors in words.
//!
//! faer's error types print through their `Debug` form (`Generic(OutOfMemory)`,
//! `SymbolicSingular { index: 12 }`), which is not what a message to a user should carry.
//! These functions say the same thing in a sentence, with what to do where there is something.

use faer::sparse::linalg::LuError;
use faer::sparse::{CreationError, FaerError};

/// A sparse algorithm's generic failure.
pub fn describe_faer(e: FaerError) -> String {
    match e {
        FaerError::OutOfMemory => {
            "out of memory (the factor or its workspace did not fit: free memory, or use a \
             coarser mesh or fewer kept dofs)"
                .to_string()
        }
        FaerError::IndexOverflow => {
            "an index overflowed the sparse format (the matrix or its factor has too many \
             entries)"
                .to_string()
        }
        _ => "a sparse algorithm failed without a reason faer names".to_string(),
    }
}

/// A sparse matrix that could not be built from triplets.
pub fn describe_creation(e: CreationError) -> String {
    match e {
        CreationError::Generic(g) => describe_faer(g),
        CreationError::OutOfBounds { row, col } => {
            format!("entry ({row}, {col}) lies outside the matrix")
        }
    }
}

/// A sparse LU factorization's failure.
pub fn describe_lu(e: LuError) -> String {
    match e {
        LuError::SymbolicSingular { index } => format!(
            "the matrix is structurally singular (no pivot at elimination step {index}): a dof \
             has no stiffness, mass or damping entry"
        ),
        LuError::Generic(g) => describe_faer(g),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No message carries faer's Debug form (a variant name or braces).
    #[test]
    fn messages_are_sentences() {
        let all = [
            describe_faer(FaerError::OutOfMemory),
            describe_faer(FaerError::IndexOverflow),
            describe_creation(CreationError::OutOfBounds { row: 3, col: 7 }),
            describe_creation(CreationError::Generic(FaerError::OutOfMemory)),
            describe_lu(LuError::SymbolicSingular { index: 12 }),
            describe_lu(LuError::Generic(FaerError::IndexOverflow)),
        ];
        for m in &all {
            assert!(
                !m.contains('{') && !m.contains("Generic") && !m.contains("OutOf"),
                "{m}"
            );
        }
        assert!(all[2].contains("(3, 7)"));
        assert!(all[4].contains("step 12"));
    }
}
