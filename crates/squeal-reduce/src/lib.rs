//! squeal-reduce (not written yet).
