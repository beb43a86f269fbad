//! Craig–Bampton reduction (eqs 1–7 of Coudeyras, Sinou & Nacivet 2009) and reduced-model files.

pub mod rom;
