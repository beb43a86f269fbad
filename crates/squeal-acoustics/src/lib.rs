//! How loud a vibrating surface is: sound from the complex normal velocities of its faces.
//!
//! squeal's limit cycles give the brake's motion harmonic by harmonic; brake noise is judged
//! in sound (SAE J2521 counts a brake application as squeal when a microphone near the wheel
//! records a peak of at least 70 dB(A) between 1.25 and 16 kHz). This crate turns the surface
//! velocity at each harmonic into three estimates. Time dependence is `e^{iωt}`: a velocity
//! `v(t) = Re(V e^{iωt})` has amplitude `|V|` and rms `|V|/√2`; `k = ω/c` is the wavenumber.
//!
//! # Inputs
//! Plain data ([`RadiatingSurface::new`]): node coordinates (m), faces as lists of `N` node
//! indices (6-node triangles of tet10 boundaries today, 8-node quadrilaterals of hex20 ones
//! fit the same way) and a [`FaceRule`] (the face's shape functions at its quadrature points
//! and their weights). Per harmonic ([`Harmonic`]): the angular frequency `kω` and either the
//! normal velocity at each face node or the 3-D velocity of each node ([`Velocity`]), from
//! which `v_n = n · v` at each quadrature point with the face's own normal. The air is
//! [`Air`] (ρ = 1.2 kg/m³, c = 343 m/s by default).
//!
//! # The estimates
//! 1. **Equivalent radiated power** ([`erp`]), as commercial CAE reports it (OptiStruct's
//!    ERP): `P = ½ ρ c ∫_S |v_n|² dA` in W, and in dB re 1 pW. Every patch is taken to radiate
//!    as a plane wave, i.e. a **radiation efficiency σ = 1**. The true power is `σ` times
//!    it; σ < 1 for a source small against the wavelength: a pulsating sphere of radius a has
//!    σ = (ka)²/(1 + (ka)²) (the tests show ERP overestimating it by 1/σ ≈ 101 at ka = 0.1),
//!    and a bending plate below its coincidence frequency radiates far less than its ERP. σ
//!    can also exceed 1 slightly (a baffled piston near ka = 2: by 3%), so ERP is a measure
//!    used to rank designs and find what radiates, not a bound nor a prediction of a level.
//! 2. **The Rayleigh integral** ([`rayleigh`]): `p(x) = (i ω ρ / 2π) ∫_S v_n(y) e^{−ikR}/R dA`,
//!    `R = |x − y|`. It is exact for a flat surface set in an infinite rigid baffle (the
//!    baffled piston of the tests, near and far field alike). Applied to a brake it assumes
//!    each face radiates into the half space in front of it as if the rest of its plane were
//!    a rigid wall ([`Facing::TowardMicrophone`] keeps only the faces that see the
//!    microphone). It neglects: scattering and shadowing by the brake, wheel, knuckle and
//!    caliper; the radiation of the other side of the disc and its cancellation against
//!    this side (the acoustic short circuit around the disc's rim, strong below the
//!    frequency whose wavelength is the disc's size); the edges, where there is no baffle.
//! 3. **A monopole sum** ([`monopoles`]): each face a point source in free space with volume
//!    velocity `Q_f = ∫_f v_n dA` at its centroid, `p(x) = (i ω ρ / 4π) Σ_f Q_f e^{−ikR_f}/R_f`.
//!    It keeps the cancellation between the two sides of a body (a rigid translation of a
//!    closed surface has Σ Q_f = 0: a dipole) but neglects the body itself: sound passes
//!    through it unscattered, with no baffle. It is right for a body small against the
//!    wavelength (the pulsating sphere at ka ≪ 1) and gives half the baffled pressure of a flat
//!    plate. Lumping a face into one point also needs the face small against the wavelength
//!    and against its distance to the microphone (near field).
//!
//! The pressure estimates are linear acoustics in still, uniform air (no flow from the
//! rotating disc, no temperature field), at a microphone off the surface.
//!
//! # Levels
//! [`a_weighting_db`] is IEC 61672-1's A-weighting (eq E.6). Harmonics of a periodic signal are
//! orthogonal over the period, so the overall A-weighted level at a microphone is
//! `L_A = 10 log10(Σ_k 10^{A(f_k)/10} |p_k|² / 2 / p_ref²)` dB(A) re 20 µPa, with `|p_k|²/2`
//! the mean square of harmonic k: an **rms** level. For a steady limit cycle that is also what
//! a sound level meter's Fast (125 ms) time weighting shows at any moment, so it is the
//! cycle's **peak** level in J2521's sense (the maximum Fast level over the application) as
//! long as the cycle lasts longer than the time constant. The peak of the instantaneous
//! pressure is higher (by 3 dB for a pure tone) and is not what J2521 counts.

#![warn(missing_docs)]
// Index loops over coordinates and face nodes read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod error;
pub mod radiation;
pub mod rule;
pub mod surface;

pub use error::{AcousticsError, Result};
pub use num_complex::Complex64;
pub use radiation::{
    Air, Facing, Harmonic, HarmonicSound, P_REF, Sound, W_REF, a_weighting_db, erp, monopoles,
    power_db, rayleigh, sound, spl_db,
};
pub use rule::FaceRule;
pub use surface::{RadiatingSurface, SurfacePoint, Velocity};
