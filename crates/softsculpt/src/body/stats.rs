//! Diagnostics of a body's state: energies, momentum, centre of mass.

use super::{gas, SoftBody};

/// One line of statistics. Energies in J, momentum in kg·m/s, lengths in m, speeds in m/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
    /// The volume the pressure uses (m³).
    pub volume: f64,
    /// Gas pressure P = nRT / V (Pa).
    pub pressure: f64,
    /// Σ ½ mi |vi|² (pinned vertices do not move and contribute 0).
    pub kinetic_energy: f64,
    /// Σ ½ k (l − L)² over edge springs plus the same with k_b over bending springs, plus the
    /// hinges' Σ ½ D w (θ − θ̄)² (`hinges.rs`) (minus
    /// f_p · (x − x_frozen) after a freeze under load).
    pub elastic_energy: f64,
    /// −nRT ln(V/V0) + P_ref (V − V0), see `gas.rs`.
    pub gas_energy: f64,
    /// Σ mi g yi.
    pub gravity_energy: f64,
    /// Sum of the four energies above.
    pub total_energy: f64,
    /// Σ mi vi.
    pub momentum: [f64; 3],
    /// Σ mi xi / Σ mi.
    pub center_of_mass: [f64; 3],
    /// Largest |vi|.
    pub max_speed: f64,
    /// Newton and linear iterations of the last step (implicit integrator; zeros otherwise).
    pub solver_iterations: super::SolverIterations,
    /// Energy the plastic stage has taken out so far (J, `plastic.rs`): total_energy plus this
    /// is what the integrator alone conserves.
    pub plastic_dissipation: f64,
}

impl Stats {
    /// The row of the statistics contract (`simulate --stats`, `run`'s summary.json, the
    /// Python package's `stats()`), its keys in order: step, time (s), volume (m³), pressure
    /// (Pa), the energies (J), momentum (kg·m/s), centre of mass (m), largest speed (m/s), the
    /// last step's solver iterations and the plastic dissipation so far (J).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "step": self.step,
            "time": self.time,
            "volume": self.volume,
            "pressure": self.pressure,
            "kinetic_energy": self.kinetic_energy,
            "elastic_energy": self.elastic_energy,
            "gas_energy": self.gas_energy,
            "gravity_energy": self.gravity_energy,
            "total_energy": self.total_energy,
            "momentum": self.momentum,
            "center_of_mass": self.center_of_mass,
            "max_speed": self.max_speed,
            "solver_iterations": {"newton": self.solver_iterations.newton, "linear": self.solver_iterations.linear},
            "plastic_dissipation": self.plastic_dissipation,
        })
    }
}

impl SoftBody {
    /// The statistics of the body under `gravity` (m/s² along −y), at world step `step` and time
    /// `time` (s): see `World::stats`.
    pub(crate) fn stats_at(&self, gravity: f64, step: u64, time: f64) -> Stats {
        let (x, v, m) = (&self.state.x, &self.state.v, &self.model.mass);
        let volume = self.volume();
        let nrt = self.material.nrt();
        let mut ke = 0.0;
        let mut pe_g = 0.0;
        let mut p = [0.0; 3];
        let mut com = [0.0; 3];
        let mut total_mass = 0.0;
        let mut vmax2: f64 = 0.0;
        for i in 0..m.len() {
            let (xi, vi) = (&x[3 * i..3 * i + 3], &v[3 * i..3 * i + 3]);
            let v2 = vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2];
            ke += 0.5 * m[i] * v2;
            vmax2 = vmax2.max(v2);
            pe_g += m[i] * gravity * xi[1];
            for d in 0..3 {
                p[d] += m[i] * vi[d];
                com[d] += m[i] * xi[d];
            }
            total_mass += m[i];
        }
        // The kept load of a freeze under load is a constant force f_p: potential −f_p · (x − x_frozen).
        let mut elastic = self.model.springs.energy(self.material.stiffness, x) + self.model.bending.energy(self.material.bending_stiffness, x);
        if self.material.rigidity > 0.0 {
            elastic += self.model.hinges.energy(self.material.rigidity, x);
        }
        if self.model.prestress.iter().any(|&p| p != 0.0) {
            for k in 0..x.len() {
                elastic -= self.model.prestress[k] * (x[k] - self.frozen.x[k]);
            }
        }
        let gas_energy = gas::energy(nrt, volume, &self.model.gas);
        Stats {
            step,
            time,
            volume,
            pressure: gas::pressure(nrt, volume),
            kinetic_energy: ke,
            elastic_energy: elastic,
            gas_energy,
            gravity_energy: pe_g,
            total_energy: ke + elastic + gas_energy + pe_g,
            momentum: p,
            center_of_mass: com.map(|c| c / total_mass),
            max_speed: vmax2.sqrt(),
            solver_iterations: self.work.iterations,
            plastic_dissipation: self.model.plastic_dissipation,
        }
    }
}
