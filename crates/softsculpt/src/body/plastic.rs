//! Plasticity ("clay"): the stage **plastic**, after a world step's integration and contacts.
//!
//! Each spring (edge and bending) has a strain ε = l / L − 1 (l its length, L its rest length,
//! m). With yield strain ε_y (`Material::yield_strain`) and flow rate φ (1/s,
//! `Material::flow_rate`), where |ε| > ε_y the rest length flows toward the rest length L* at
//! which the strain is exactly the yield strain,
//!   L* = l / (1 + ε_y)   (stretched, ε > ε_y),      L* = l / (1 − ε_y)   (compressed, ε < −ε_y),
//! by  dL/dt = φ (L* − L)  with l held at its end-of-step value. Over a step of dt the exact
//! solution is
//!   L' = L + (1 − e^(−φ dt)) (L* − L).
//! The factor lies in [0, 1) for every φ ≥ 0 and dt > 0, so L' is always between L and L*: the
//! update never overshoots the yield strain, never changes a strain's sign, keeps L > 0 and is
//! stable for any dt (an explicit L += φ dt (L* − L) overshoots once φ dt > 1 and diverges past
//! 2). Springs within the yield strain are untouched: below it the body is exactly elastic.
//! φ = 0 switches the stage off; ε_y = 0 with φ > 0 lets every strain flow (a Maxwell fluid).
//!
//! **The gas reference follows.** An inflated body at rest holds its gas with stretched
//! springs. Were only the rest lengths to flow, the springs would slacken, the gas would push
//! the skin out, the strain would flow again: the body would creep (grow) under its own gas. The
//! balance that holds the body's size is the virial identity of its internal forces: at
//! equilibrium of springs and gas, Σ_i xi · fi = 0 over springs and gas gives (Euler's theorem,
//! V homogeneous of degree 3, so Σ xi · ∂V/∂xi = 3V; a spring's pair of forces contributes
//! −k (l − L) l)
//!   Σ_springs k (l − L) l = 3 (P − P_ref) V         (V the exact volume: the force's direction)
//! A plastic step changes the left side by −Σ k l δL. Changing P_ref by
//!   δP_ref = Σ k l δL / (3 V)
//! keeps the identity, so the flow does not move the body as a whole. When every spring flows
//! by the same fraction (a uniformly stretched sphere) this is exactly the new equilibrium at the
//! same positions; otherwise it is the exact balance of the dilation mode and the rest is the
//! shape's real plastic change. In the limit ε_y = 0, φ dt → ∞ it becomes freeze's rule (every
//! L = l, P_ref = P). It applies when the gas acts (a closed mesh with nRT > 0); P_ref stays
//! ≥ 0 (the surroundings are never below vacuum).
//!
//! **The gas's share.** The identity above holds for springs and gas alone. Under a load — the
//! grab's pull, gravity and the ground, a press — the springs also carry the load:
//! Σ k (l − L) l = 3 (P − P_ref) V + (the load's virial), and a spring stretched by the pull
//! flows without the gas having anything to do with it. So P_ref follows by the gas's share
//! only: with S⁺ = Σ k (l − L) l over the stretched springs (the gas stretches the skin;
//! compressed springs hold something else) and G = 3 (P − P_ref) V the gas's part of it,
//!   δP_ref = s Σ k l δL / (3 V),   s = min(1, G / S⁺) where G > 0, else 0,
//! and P_ref never rises past P (the flow can take away the gas's whole push, as a freeze does,
//! but never turn the gas into a suction). A body held by the gas alone has G = S⁺ at
//! equilibrium (s = 1, the rule above); a frozen body (P_ref = P: the gas pushes nothing, what
//! the modeler's material switch leaves) has s = 0 until it is squeezed. Why: with the whole
//! flow credited to the gas, the modeler's clay mushroom pulled by a mirrored grab (both sides
//! of its cap) had P_ref run from 8 Pa past P to 2,420 Pa and beyond — each flow's δP_ref grows
//! as 1/V, so the sucked-in body collapsed to 0.3 % of its volume (then the step failed); with
//! the share it keeps the pulled shape at 1.78 of 2.46 m³ (an elastic body under the same pull:
//! 1.53 m³ at least), `tests/plastic.rs`.
//!
//! **Bending.** A dent pressed into a gas-filled shell is almost isometric (the cap turns
//! inside out with its edges barely stretched), so no spring passes the yield strain and the
//! gas pops the dent back out: what a potter's press changes is the shell's bending. Where the
//! hinges act (rigidity D > 0, `hinges.rs`), their rest angles flow too, past a yield angle,
//! by the same exact exponential at the same rate:
//!   r' = r − (1 − e^(−φ dt)) (r − θ_y sign r)     where |r| = |θ − θ̄| > θ_y,    θ̄' = θ − r'.
//! The yield angle comes from the same yield strain, through the thickness of the plate the
//! membrane and the hinges together are: an equilateral spring lattice of stiffness k is a
//! membrane of modulus E₂ = 2k/√3 (N/m) with Poisson's ratio ν = 1/3, and a plate of that
//! membrane modulus and flexural rigidity D = E₂ t² / 12 (1 − ν²) has thickness
//!   t = √(12 (1 − ν²) D / E₂) = √((16 √3 / 3) D / k)     (m),
//! whose surface strain at curvature κ is κ t / 2. It yields at
//!   κ_y = 2 ε_y / t     (1/m),     θ_y = κ_y Ā / |e| at each hinge (`Hinges::flow`),
//! the angle a surface of curvature κ_y makes there, so the yield is the same at any
//! resolution. (The clay preset: k 300 N/m, D 0.05 J, ε_y 0.5 %: t = 3.9 cm, κ_y = 0.26 1/m, a
//! bend to a radius of 3.9 m past the rest shape's.) Hinge forces have no virial (θ does not
//! change when the body is scaled: Σ xᵢ · ∇ᵢθ = 0), so the flow of rest angles leaves the gas
//! reference alone. A body without springs (k = 0) has no plate to yield: its hinges stay
//! elastic. A hinge with a crushed face does not flow (`Hinges::flow`).
//!
//! **Energy.** At fixed positions the stage lowers the potential energy by
//!   D = Σ ½ k [(l − L)² − (l − L')²]  +  Σ ½ D w [(θ − θ̄)² − (θ − θ̄')²]  −  δP_ref (V_g − V0)
//! (the second term: the gas energy −nRT ln(V_g/V0) + P_ref (V_g − V0) with V_g the volume the
//! gas law uses, `gas.rs`). The first term equals ∫ k (l − L) dL along the flow at fixed l: the
//! plastic work, ≥ 0 for each spring since L moves toward l. D is added to the body's
//! `plastic_dissipation` (J), so kinetic + elastic + gas + gravity energy + dissipation is what
//! the integrator alone conserves (tested in `tests/plastic.rs`).

use super::{gas, GasReference, SoftBody, Springs};

/// What the plastic stage changes: rest lengths of the edge and bending springs (m), the
/// hinges' rest angles (rad), the gas reference, the dissipation (J). What a rollback puts
/// back.
#[derive(Debug, Clone)]
pub struct PlasticState {
    rest: Vec<f64>,
    bending_rest: Vec<f64>,
    hinge_rest: Vec<f64>,
    gas: GasReference,
    dissipation: f64,
}

impl PlasticState {
    /// The rest lengths and angles it holds (the measure of its size).
    pub(crate) fn len(&self) -> usize {
        self.rest.len() + self.bending_rest.len() + self.hinge_rest.len()
    }
}

/// The yield curvature κ_y = 2 ε_y / t (1/m) of a membrane of edge stiffness `k` (N/m) with
/// hinges of rigidity `d` (J) and yield strain `y`, t = √((16 √3 / 3) D / k) the plate's
/// thickness (module documentation, "Bending"); `None` where there is no plate (k = 0 or
/// D = 0).
pub fn yield_curvature(k: f64, d: f64, y: f64) -> Option<f64> {
    let t = (16.0 * 3f64.sqrt() / 3.0 * d / k).sqrt();
    (k > 0.0 && d > 0.0 && t.is_finite()).then(|| 2.0 * y / t)
}

/// Flow the rest lengths of `s` (stiffness `k`, N/m) by the fraction `a` of their excess strain
/// over `y`, at positions `x`. Returns (elastic energy released in J, Σ k l δL in J, the
/// stretched springs' virial Σ k (l − L) l before the flow in J).
fn flow(s: &mut Springs, k: f64, y: f64, a: f64, x: &[f64]) -> (f64, f64, f64) {
    let mut rest = std::mem::take(&mut s.rest);
    let (mut released, mut virial, mut tension) = (0.0, 0.0, 0.0);
    s.lengths_into(x, |e, l| {
        let r = rest[e];
        if !(r > 0.0 && l.is_finite()) {
            return;
        }
        if l > r {
            tension += k * (l - r) * l;
        }
        let strain = l / r - 1.0;
        let target = if strain > y {
            l / (1.0 + y)
        } else if strain < -y && y < 1.0 {
            l / (1.0 - y)
        } else {
            return;
        };
        let r2 = r + a * (target - r);
        released += 0.5 * k * ((l - r) * (l - r) - (l - r2) * (l - r2));
        virial += k * l * (r2 - r);
        rest[e] = r2;
    });
    s.rest = rest;
    (released, virial, tension)
}

impl SoftBody {
    /// Stage "plastic" over a step of `dt` seconds (see the module documentation); nothing when
    /// the flow rate is 0.
    pub(crate) fn plastic_flow(&mut self, dt: f64) {
        let p = &self.material;
        if !p.is_plastic() {
            return;
        }
        // 1 − e^(−φ dt), accurate for small φ dt.
        let a = -(-p.flow_rate * dt).exp_m1();
        let x = &self.state.x;
        let (mut released, mut virial, mut tension) = flow(&mut self.model.springs, p.stiffness, p.yield_strain, a, x);
        if p.bending_stiffness > 0.0 {
            let (r, v, t) = flow(&mut self.model.bending, p.bending_stiffness, p.yield_strain, a, x);
            released += r;
            virial += v;
            tension += t;
        }
        if let Some(kappa_y) = yield_curvature(p.stiffness, p.rigidity, p.yield_strain) {
            // No virial: the gas reference does not follow (module documentation, "Bending").
            released += self.model.hinges.flow(p.rigidity, kappa_y, a, x);
        }
        if virial != 0.0 && self.model.closed && p.nrt() > 0.0 {
            let six_v = self.model.faces.volume6(x);
            if six_v > 0.0 && six_v.is_finite() {
                let gas_volume = gas::measure(self.model.faces.triangles(), p.volume_mode, six_v, x);
                let g = &mut self.model.gas;
                let before = g.ambient_pressure;
                // The gas's share of the stretched springs' tension, in [0, 1], and P_ref never
                // past P (module documentation, "The gas's share").
                let pressure = gas::pressure(p.nrt(), gas_volume);
                let held = (pressure - before) * 0.5 * six_v;
                let share = if held > 0.0 && tension > 0.0 { (held / tension).min(1.0) } else { 0.0 };
                g.ambient_pressure = (before + share * virial / (0.5 * six_v)).min(before.max(pressure)).max(0.0);
                released -= (g.ambient_pressure - before) * (gas_volume - g.reference_volume);
            }
        }
        self.model.plastic_dissipation += released;
    }

    /// Energy (J) the plastic stage has taken out of the body since it was made (see `plastic.rs`).
    pub fn plastic_dissipation(&self) -> f64 {
        self.model.plastic_dissipation
    }

    pub(crate) fn plastic_state(&self) -> PlasticState {
        PlasticState {
            rest: self.model.springs.rest.clone(),
            bending_rest: self.model.bending.rest.clone(),
            hinge_rest: self.model.hinges.rest.clone(),
            gas: self.model.gas,
            dissipation: self.model.plastic_dissipation,
        }
    }

    pub(crate) fn set_plastic_state(&mut self, p: &PlasticState) {
        debug_assert!(p.rest.len() == self.model.springs.rest.len() && p.bending_rest.len() == self.model.bending.rest.len() && p.hinge_rest.len() == self.model.hinges.rest.len());
        self.model.springs.rest.clone_from(&p.rest);
        self.model.bending.rest.clone_from(&p.bending_rest);
        self.model.hinges.rest.clone_from(&p.hinge_rest);
        self.model.gas = p.gas;
        self.model.plastic_dissipation = p.dissipation;
    }

    /// Set the plastic dissipation counter (J), e.g. when restoring.
    pub fn set_plastic_dissipation(&mut self, joules: f64) {
        self.model.plastic_dissipation = joules;
    }
}
