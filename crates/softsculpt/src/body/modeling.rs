//! Modeling operations: reset, inflate/deflate, masses, pins, user forces (freezing: `freeze.rs`).

use super::material::{check_non_negative, check_positive};
use super::SoftBody;
use crate::error::SimError;

fn length_check(what: &'static str, expected: usize, got: usize) -> Result<(), SimError> {
    if expected != got {
        return Err(SimError::Length { what, expected, got });
    }
    Ok(())
}

fn finite(name: &'static str, values: &[f64]) -> Result<(), SimError> {
    if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
        return Err(SimError::BadParameter { name, message: format!("must be finite, got {bad}") });
    }
    Ok(())
}

impl SoftBody {
    /// The constant load kept by [`SoftBody::freeze_under_load`] (N, flat xyz).
    pub fn prestress(&self) -> &[f64] {
        &self.model.prestress
    }

    /// Set the kept load (N, flat xyz), e.g. when restoring a saved project.
    pub fn set_prestress(&mut self, prestress: &[f64], frozen: &[f64]) -> Result<(), SimError> {
        length_check("prestress", 3 * self.vertex_count(), prestress.len())?;
        length_check("frozen prestress", 3 * self.vertex_count(), frozen.len())?;
        finite("prestress", prestress)?;
        finite("frozen prestress", frozen)?;
        self.model.prestress.copy_from_slice(prestress);
        self.frozen.prestress.copy_from_slice(frozen);
        self.update_external();
        Ok(())
    }

    pub fn frozen_prestress(&self) -> &[f64] {
        &self.frozen.prestress
    }

    pub(super) fn update_external(&mut self) {
        let m = &mut self.model;
        for k in 0..m.external.len() {
            m.external[k] = m.user_force[k] + m.prestress[k];
        }
        m.external_active = m.external.iter().any(|&f| f != 0.0);
    }

    /// Reset to the last frozen shape (or the loaded one): positions, rest lengths and the gas
    /// reference; velocities zero. Masses, pins and parameters are kept.
    pub fn reset(&mut self) {
        self.state.x.copy_from_slice(&self.frozen.x);
        self.model.springs.rest.copy_from_slice(&self.frozen.rest);
        self.model.bending.rest.copy_from_slice(&self.frozen.bending_rest);
        // The hinges' rest angles too (a plastic body's flowed: `plastic.rs`, "Bending").
        self.hinges_to_frozen();
        self.model.gas = self.frozen.gas;
        self.model.prestress.copy_from_slice(&self.frozen.prestress);
        self.update_external();
        self.state.v.fill(0.0);
    }

    /// Inflate (factor > 1) or deflate (< 1) by scaling every rest length (dimensionless).
    pub fn scale_rest_lengths(&mut self, factor: f64) -> Result<(), SimError> {
        check_positive("factor", factor)?;
        for l in self.model.springs.rest.iter_mut().chain(self.model.bending.rest.iter_mut()) {
            *l *= factor;
        }
        Ok(())
    }

    /// Inflate or deflate locally: `factors` holds one scale per vertex (dimensionless, > 0);
    /// each spring's rest length is multiplied by the mean of its two ends' factors, after a
    /// field sharper than the mesh can show is spread to about 2.6 edges' radius, keeping the
    /// growth's area-weighted sum (`growth.rs`).
    pub fn scale_rest_lengths_by_vertex(&mut self, factors: &[f64]) -> Result<(), SimError> {
        length_check("factors", self.vertex_count(), factors.len())?;
        if let Some(bad) = factors.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
            return Err(SimError::BadParameter { name: "factors", message: format!("must be finite and > 0, got {bad}") });
        }
        let mut f = factors.to_vec();
        let s = &self.model.springs;
        super::growth::spread(&mut f, self.model.faces.triangles(), (&s.i, &s.j), &self.state.x);
        for s in [&mut self.model.springs, &mut self.model.bending] {
            for e in 0..s.rest.len() {
                s.rest[e] *= 0.5 * (f[s.i[e] as usize] + f[s.j[e] as usize]);
            }
        }
        Ok(())
    }

    /// Set every bending spring's rest length (m), now and in the frozen state.
    pub fn set_bending_rest_lengths(&mut self, rest: &[f64], frozen: &[f64]) -> Result<(), SimError> {
        length_check("bending rest lengths", self.model.bending.len(), rest.len())?;
        length_check("frozen bending rest lengths", self.model.bending.len(), frozen.len())?;
        if let Some(bad) = rest.iter().chain(frozen).find(|l| !(l.is_finite() && **l >= 0.0)) {
            return Err(SimError::BadParameter { name: "bending rest lengths", message: format!("must be finite and ≥ 0, got {bad}") });
        }
        self.model.bending.rest.copy_from_slice(rest);
        self.frozen.bending_rest.copy_from_slice(frozen);
        Ok(())
    }

    /// Frozen rest lengths of the bending springs (m).
    pub fn frozen_bending_rest_lengths(&self) -> &[f64] {
        &self.frozen.bending_rest
    }

    /// Set every rest length (m).
    pub fn set_rest_lengths(&mut self, rest: &[f64]) -> Result<(), SimError> {
        length_check("rest lengths", self.spring_count(), rest.len())?;
        if let Some(bad) = rest.iter().find(|l| !(l.is_finite() && **l >= 0.0)) {
            return Err(SimError::BadParameter { name: "rest lengths", message: format!("must be finite and ≥ 0, got {bad}") });
        }
        self.model.springs.rest.copy_from_slice(rest);
        Ok(())
    }

    /// Split a total mass (kg) equally over the vertices (pins are kept).
    pub fn set_total_mass(&mut self, total: f64) -> Result<(), SimError> {
        check_positive("mass", total)?;
        let m = total / self.vertex_count() as f64;
        for (mass, inv) in self.model.mass.iter_mut().zip(&mut self.model.inv_mass) {
            *mass = m;
            if *inv != 0.0 {
                *inv = 1.0 / m; // pinned vertices (inv = 0) stay pinned
            }
        }
        Ok(())
    }

    /// Set the mass of vertex i (kg, > 0). Heavier vertices move less: this localises deformation.
    pub fn set_vertex_mass(&mut self, i: usize, mass: f64) -> Result<(), SimError> {
        check_positive("vertex mass", mass)?;
        self.vertex_index(i)?;
        let pinned = self.is_pinned(i);
        self.model.mass[i] = mass;
        self.model.inv_mass[i] = if pinned { 0.0 } else { 1.0 / mass };
        Ok(())
    }

    /// Pin (infinite mass: never moves) or unpin vertex i.
    pub fn set_pinned(&mut self, i: usize, pinned: bool) -> Result<(), SimError> {
        self.vertex_index(i)?;
        self.model.inv_mass[i] = if pinned { 0.0 } else { 1.0 / self.model.mass[i] };
        if pinned {
            self.state.v[3 * i..3 * i + 3].fill(0.0);
        }
        Ok(())
    }

    /// External force on every vertex (N, flat xyz), applied until changed. Zeros switch it off.
    pub fn set_user_forces(&mut self, forces: &[f64]) -> Result<(), SimError> {
        length_check("user forces", 3 * self.vertex_count(), forces.len())?;
        finite("user forces", forces)?;
        self.model.user_force.copy_from_slice(forces);
        self.update_external();
        Ok(())
    }

    /// External pressure on every face (Pa, along the inward normal), applied until changed.
    pub fn set_face_pressures(&mut self, pressures: &[f64]) -> Result<(), SimError> {
        length_check("face pressures", self.face_count(), pressures.len())?;
        finite("face pressures", pressures)?;
        self.model.face_pressure.copy_from_slice(pressures);
        self.model.face_pressure_active = pressures.iter().any(|&p| p != 0.0);
        Ok(())
    }

    /// Give every vertex the velocity `v` (m/s).
    pub fn set_uniform_velocity(&mut self, v: [f64; 3]) -> Result<(), SimError> {
        finite("velocity", &v)?;
        for (i, u) in self.state.v.chunks_exact_mut(3).enumerate() {
            if self.model.inv_mass[i] != 0.0 {
                u.copy_from_slice(&v);
            }
        }
        Ok(())
    }

    /// Replace positions and velocities (flat xyz), e.g. to roll back to a snapshot.
    pub fn set_state(&mut self, x: &[f64], v: &[f64]) -> Result<(), SimError> {
        length_check("positions", self.state.x.len(), x.len())?;
        length_check("velocities", self.state.v.len(), v.len())?;
        finite("positions", x)?;
        finite("velocities", v)?;
        self.state.x.copy_from_slice(x);
        self.state.v.copy_from_slice(v);
        Ok(())
    }

    /// Set the gas by n (mol) and T (K).
    pub fn set_gas(&mut self, amount: f64, temperature: f64) -> Result<(), SimError> {
        check_non_negative("gas", amount)?;
        check_positive("temperature", temperature)?;
        if amount > 0.0 && !self.model.closed {
            return Err(SimError::BadParameter {
                name: "gas",
                message: "gas pressure needs a closed surface; this mesh is open or non-manifold".into(),
            });
        }
        self.material.gas_amount = amount;
        self.material.temperature = temperature;
        Ok(())
    }

    /// Move vertex i by `dx` (m) and change its velocity by `dv` (m/s): for contact responses
    /// computed outside the body (see `world.rs`). Pinned vertices do not move.
    pub(crate) fn nudge(&mut self, i: usize, dx: [f64; 3], dv: [f64; 3]) {
        if self.model.inv_mass[i] == 0.0 {
            return;
        }
        for d in 0..3 {
            self.state.x[3 * i + d] += dx[d];
            self.state.v[3 * i + d] += dv[d];
        }
    }

    fn vertex_index(&self, i: usize) -> Result<(), SimError> {
        if i >= self.vertex_count() {
            return Err(SimError::BadParameter {
                name: "vertex",
                message: format!("index {i} out of range (the body has {} vertices)", self.vertex_count()),
            });
        }
        Ok(())
    }
}
