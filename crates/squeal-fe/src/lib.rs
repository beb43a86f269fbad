//! squeal-fe (not written yet).
