//! The three estimates of [`crate`]'s docs at one angular frequency, A-weighting, and the
//! levels of a periodic motion given harmonic by harmonic ([`sound`]).

use crate::error::{AcousticsError, Result};
use crate::surface::{RadiatingSurface, Velocity};
use num_complex::Complex64;
use squeal_element::geometry::dot;
use std::f64::consts::PI;

/// Reference sound pressure for levels in dB (Pa), IEC 61672.
pub const P_REF: f64 = 20e-6;
/// Reference sound power for levels in dB (W).
pub const W_REF: f64 = 1e-12;

/// The air the surface radiates into.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Air {
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Speed of sound c (m/s).
    pub speed_of_sound: f64,
}

impl Default for Air {
    /// Air at about 20 °C and 1 atm: ρ = 1.2 kg/m³, c = 343 m/s.
    fn default() -> Self {
        Self {
            density: 1.2,
            speed_of_sound: 343.0,
        }
    }
}

impl Air {
    /// Both values finite and positive.
    pub fn check(&self) -> Result<()> {
        positive("air density", self.density)?;
        positive("speed of sound", self.speed_of_sound)
    }

    /// Characteristic impedance ρc (Pa s/m).
    pub fn impedance(&self) -> f64 {
        self.density * self.speed_of_sound
    }
}

fn positive(what: &'static str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(AcousticsError::Parameter { what, value })
    }
}

/// Which quadrature points the Rayleigh integral takes at a microphone.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Facing {
    /// Every point: the surface is one baffled plane (exact for a flat baffled radiator).
    #[default]
    All,
    /// Only the points whose outward normal faces the microphone (`n · (x − y) > 0`): each
    /// patch of a closed body radiates into its own half space, as if baffled by its tangent
    /// plane, and the far side of the body is hidden.
    TowardMicrophone,
}

/// Equivalent radiated power `½ ρ c ∫ |v_n|² dA` (W) of normal velocities `vn` at the
/// surface's quadrature points: the power of the surface if every patch radiated as a plane
/// wave (radiation efficiency 1).
pub fn erp(air: &Air, surface: &RadiatingSurface, vn: &[Complex64]) -> f64 {
    0.5 * air.impedance()
        * surface
            .points
            .iter()
            .zip(vn)
            .map(|(p, v)| v.norm_sqr() * p.area)
            .sum::<f64>()
}

/// The Rayleigh integral `p(x) = (i ω ρ / 2π) ∫ v_n(y) e^{−ikR}/R dA`, `R = |x − y|`,
/// `k = ω/c` (Pa, complex amplitude for time dependence `e^{iωt}`).
pub fn rayleigh(
    air: &Air,
    surface: &RadiatingSurface,
    vn: &[Complex64],
    omega: f64,
    x: [f64; 3],
    facing: Facing,
) -> Result<Complex64> {
    let k = omega / air.speed_of_sound;
    let mut s = Complex64::new(0.0, 0.0);
    for (p, v) in surface.points.iter().zip(vn) {
        let d = [
            x[0] - p.position[0],
            x[1] - p.position[1],
            x[2] - p.position[2],
        ];
        if facing == Facing::TowardMicrophone && dot(d, p.normal) <= 0.0 {
            continue;
        }
        s += v * green(k, distance(d, x)?) * p.area;
    }
    Ok(Complex64::new(0.0, omega * air.density / (2.0 * PI)) * s)
}

/// The surface as free-field point sources, one per face: volume velocity
/// `Q_f = ∫_f v_n dA` at the face's area centroid `y_f`, `p(x) = (i ω ρ / 4π) Σ_f Q_f
/// e^{−ikR_f}/R_f` (Pa).
pub fn monopoles(
    air: &Air,
    surface: &RadiatingSurface,
    vn: &[Complex64],
    omega: f64,
    x: [f64; 3],
) -> Result<Complex64> {
    let k = omega / air.speed_of_sound;
    let nq = surface.points_per_face;
    let mut s = Complex64::new(0.0, 0.0);
    for (pts, v) in surface.points.chunks(nq).zip(vn.chunks(nq)) {
        let (mut q, mut area, mut y) = (Complex64::new(0.0, 0.0), 0.0, [0.0; 3]);
        for (p, v) in pts.iter().zip(v) {
            q += v * p.area;
            area += p.area;
            for d in 0..3 {
                y[d] += p.area * p.position[d];
            }
        }
        let d = [x[0] - y[0] / area, x[1] - y[1] / area, x[2] - y[2] / area];
        s += q * green(k, distance(d, x)?);
    }
    Ok(Complex64::new(0.0, omega * air.density / (4.0 * PI)) * s)
}

/// `e^{−ikR}/R`.
fn green(k: f64, r: f64) -> Complex64 {
    let (s, c) = (k * r).sin_cos();
    Complex64::new(c, -s) / r
}

/// `|d|`, refused when zero (a microphone on the surface: the integrals are singular there).
fn distance(d: [f64; 3], x: [f64; 3]) -> Result<f64> {
    let r = dot(d, d).sqrt();
    if r > 0.0 && r.is_finite() {
        Ok(r)
    } else {
        Err(AcousticsError::MicrophoneOnSurface { at: x })
    }
}

/// The A-weighting of IEC 61672-1:2013 (eq E.6), in dB at frequency `f` (Hz):
/// `A(f) = 20 log10(f4² f⁴ / ((f² + f1²) √(f² + f2²) √(f² + f3²) (f² + f4²))) − A1000`
/// with f1 = 20.598997, f2 = 107.65265, f3 = 737.86223, f4 = 12194.217 Hz and
/// A1000 = −2.000 dB (the normalization that makes A(1 kHz) ≈ 0).
pub fn a_weighting_db(f: f64) -> f64 {
    const F1: f64 = 20.598_997;
    const F2: f64 = 107.652_65;
    const F3: f64 = 737.862_23;
    const F4: f64 = 12_194.217;
    const A1000: f64 = -2.000;
    let f2 = f * f;
    let r = F4 * F4 * f2 * f2
        / ((f2 + F1 * F1) * (f2 + F2 * F2).sqrt() * (f2 + F3 * F3).sqrt() * (f2 + F4 * F4));
    20.0 * r.log10() - A1000
}

/// Sound pressure level (dB re 20 µPa) of an rms pressure (Pa).
pub fn spl_db(p_rms: f64) -> f64 {
    20.0 * (p_rms / P_REF).log10()
}

/// Sound power level (dB re 1 pW) of a power (W).
pub fn power_db(w: f64) -> f64 {
    10.0 * (w / W_REF).log10()
}

/// One harmonic of a periodic motion: angular frequency `k ω` and the surface's velocity
/// amplitude there (`v(t) = Re(V e^{i k ω t})`).
#[derive(Clone, Copy, Debug)]
pub struct Harmonic<'a> {
    /// The harmonic's order k (for the report).
    pub order: usize,
    /// Its angular frequency k ω (rad/s).
    pub omega: f64,
    /// The velocity amplitude.
    pub velocity: Velocity<'a>,
}

/// The estimates at one harmonic.
#[derive(Clone, Debug, PartialEq)]
pub struct HarmonicSound {
    /// The harmonic's order.
    pub order: usize,
    /// Its frequency (Hz).
    pub frequency_hz: f64,
    /// Equivalent radiated power (W).
    pub erp_w: f64,
    /// The Rayleigh-integral pressure amplitude at each microphone (Pa, complex; rms is
    /// `|p| / √2`).
    pub rayleigh: Vec<Complex64>,
    /// The monopole-sum pressure amplitude at each microphone (Pa, complex).
    pub monopole: Vec<Complex64>,
}

/// The sound of a periodic motion: each harmonic, and the overall levels (the harmonics'
/// mean squares add: they are orthogonal over a period).
#[derive(Clone, Debug, PartialEq)]
pub struct Sound {
    /// Each harmonic given.
    pub harmonics: Vec<HarmonicSound>,
    /// Total ERP (W) and its level (dB re 1 pW).
    pub erp_w: f64,
    /// `10 log10(erp_w / 1 pW)`.
    pub erp_db: f64,
    /// The ERP level A-weighted harmonic by harmonic (dB(A) re 1 pW).
    pub erp_dba: f64,
    /// Overall A-weighted level at each microphone by the Rayleigh integral (dB(A) re 20 µPa,
    /// rms over a period).
    pub rayleigh_dba: Vec<f64>,
    /// The same by the monopole sum.
    pub monopole_dba: Vec<f64>,
}

/// ERP, Rayleigh and monopole pressures of every harmonic at every microphone, and the
/// overall levels. A harmonic of zero frequency (the mean) is refused: it does not radiate.
pub fn sound(
    air: &Air,
    surface: &RadiatingSurface,
    harmonics: &[Harmonic],
    microphones: &[[f64; 3]],
    facing: Facing,
) -> Result<Sound> {
    air.check()?;
    let mut out = Vec::with_capacity(harmonics.len());
    for h in harmonics {
        positive("harmonic angular frequency", h.omega)?;
        let vn = surface.normal_velocity(h.velocity)?;
        let mut rayleigh_p = Vec::with_capacity(microphones.len());
        let mut monopole_p = Vec::with_capacity(microphones.len());
        for &x in microphones {
            rayleigh_p.push(rayleigh(air, surface, &vn, h.omega, x, facing)?);
            monopole_p.push(monopoles(air, surface, &vn, h.omega, x)?);
        }
        out.push(HarmonicSound {
            order: h.order,
            frequency_hz: h.omega / (2.0 * PI),
            erp_w: erp(air, surface, &vn),
            rayleigh: rayleigh_p,
            monopole: monopole_p,
        });
    }
    let erp_w: f64 = out.iter().map(|h| h.erp_w).sum();
    let erp_a: f64 = out
        .iter()
        .map(|h| h.erp_w * 10f64.powf(a_weighting_db(h.frequency_hz) / 10.0))
        .sum();
    let level = |pick: &dyn Fn(&HarmonicSound) -> Complex64| {
        let ms: f64 = out
            .iter()
            .map(|h| 0.5 * pick(h).norm_sqr() * 10f64.powf(a_weighting_db(h.frequency_hz) / 10.0))
            .sum();
        spl_db(ms.sqrt())
    };
    let rayleigh_dba = (0..microphones.len())
        .map(|m| level(&|h| h.rayleigh[m]))
        .collect();
    let monopole_dba = (0..microphones.len())
        .map(|m| level(&|h| h.monopole[m]))
        .collect();
    Ok(Sound {
        harmonics: out,
        erp_w,
        erp_db: power_db(erp_w),
        erp_dba: power_db(erp_a),
        rayleigh_dba,
        monopole_dba,
    })
}
