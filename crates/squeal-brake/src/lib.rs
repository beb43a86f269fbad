//! squeal-brake (not written yet).
