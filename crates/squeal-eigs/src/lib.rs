//! squeal-eigs (not written yet).
