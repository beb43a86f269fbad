//! squeal-ode (not written yet).
