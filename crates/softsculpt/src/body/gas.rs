//! Gas: the ideal-gas pressure P = nRT / V and its reference state.
//!
//! The force on vertex i is (P − P_ref) ∂V/∂xi (the faces stage gives ∂V/∂xi). P_ref is the
//! pressure of the surroundings: 0 (vacuum) until the first freeze. Freezing sets P_ref to the
//! current P, so that with springs at rest and gas at the surroundings' pressure nothing moves:
//! the frozen shape is an exact equilibrium. Adding gas (or heat) afterwards raises P above
//! P_ref and inflates; removing it deflates. Since P_ref is *set*, never added to, toggling or
//! freezing repeatedly cannot make the body grow (godot#123661).
//!
//! Potential energy of the gas (J), with V0 the volume at the last freeze (or at creation):
//!   E_gas = −nRT ln(V / V0) + P_ref (V − V0)
//! whose gradient −(nRT/V − P_ref) ∂V/∂x is the force above (exact volume mode). Before any
//! freeze P_ref = 0 and this is the textbook −nRT ln(V/V0).

use super::material::VolumeMode;
use std::f64::consts::PI;

/// State of the gas that is not a user parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GasReference {
    /// Pressure of the surroundings P_ref (Pa), set by freeze.
    pub ambient_pressure: f64,
    /// Volume V0 (m³) at which the gas energy is zero.
    pub reference_volume: f64,
}

/// The volume the gas law uses (m³): the exact one from the faces stage (`six_v` = 6V), or one
/// of the paper's bounding volumes computed from the positions `x` (flat xyz).
pub fn measure(mode: VolumeMode, six_v: f64, x: &[f64]) -> f64 {
    match mode {
        VolumeMode::Exact => six_v / 6.0,
        VolumeMode::Box => {
            let (lo, hi) = crate::mesh::bounds(x);
            (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
        }
        VolumeMode::Sphere => {
            let n = (x.len() / 3).max(1) as f64;
            let mut c = [0.0; 3];
            for p in x.chunks_exact(3) {
                c[0] += p[0];
                c[1] += p[1];
                c[2] += p[2];
            }
            let c = [c[0] / n, c[1] / n, c[2] / n];
            let mut r2: f64 = 0.0;
            for p in x.chunks_exact(3) {
                r2 = r2.max((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2));
            }
            4.0 / 3.0 * PI * r2.sqrt().powi(3)
        }
    }
}

/// Gas pressure P = nRT / V (Pa); 0 without gas.
pub fn pressure(nrt: f64, volume: f64) -> f64 {
    if nrt == 0.0 {
        0.0
    } else {
        nrt / volume
    }
}

/// Potential energy of the gas (J), see the module comment.
pub fn energy(nrt: f64, volume: f64, r: &GasReference) -> f64 {
    let log_term = if nrt == 0.0 { 0.0 } else { -nrt * (volume / r.reference_volume).ln() };
    log_term + r.ambient_pressure * (volume - r.reference_volume)
}
