//! squeal-hbm (not written yet).
