//! squeal-report (not written yet).
