//! Everything needed to save a body and resume it exactly, and Loop subdivision of a body.

use super::{Frozen, GasReference, SoftBody};
use crate::error::SimError;
use crate::mesh::{subdivide, TriMesh};

impl SoftBody {
    /// The last frozen positions (m) and rest lengths (m), as [`SoftBody::reset`] restores them.
    pub fn frozen_positions(&self) -> &[f64] {
        &self.frozen.x
    }
    pub fn frozen_rest_lengths(&self) -> &[f64] {
        &self.frozen.rest
    }
    pub fn frozen_gas_reference(&self) -> GasReference {
        self.frozen.gas
    }

    /// Set the gas reference (surroundings' pressure in Pa, reference volume in m³).
    pub fn set_gas_reference(&mut self, gas: GasReference) -> Result<(), SimError> {
        check_gas(&gas)?;
        self.model.gas = gas;
        Ok(())
    }

    /// Set the state [`SoftBody::reset`] returns to.
    pub fn set_frozen(&mut self, positions: &[f64], rest: &[f64], gas: GasReference) -> Result<(), SimError> {
        if positions.len() != self.state.x.len() || rest.len() != self.spring_count() {
            return Err(SimError::Length { what: "frozen state", expected: self.state.x.len() + self.spring_count(), got: positions.len() + rest.len() });
        }
        if positions.iter().chain(rest).any(|v| !v.is_finite()) {
            return Err(SimError::BadParameter { name: "frozen state", message: "must be finite".into() });
        }
        check_gas(&gas)?;
        self.frozen = Frozen { x: positions.to_vec(), rest: rest.to_vec(), bending_rest: self.frozen.bending_rest.clone(), gas, prestress: self.frozen.prestress.clone() };
        self.hinges_to_frozen();
        Ok(())
    }

    /// Set every vertex mass (kg, > 0); pins are kept.
    pub fn set_masses(&mut self, masses: &[f64]) -> Result<(), SimError> {
        if masses.len() != self.vertex_count() {
            return Err(SimError::Length { what: "masses", expected: self.vertex_count(), got: masses.len() });
        }
        if let Some(bad) = masses.iter().find(|m| !(m.is_finite() && **m > 0.0)) {
            return Err(SimError::BadParameter { name: "masses", message: format!("must be finite and > 0, got {bad}") });
        }
        for (i, &m) in masses.iter().enumerate() {
            let pinned = self.is_pinned(i);
            self.model.mass[i] = m;
            self.model.inv_mass[i] = if pinned { 0.0 } else { 1.0 / m };
        }
        Ok(())
    }

    /// The current shape as a mesh.
    pub fn to_mesh(&self) -> TriMesh {
        TriMesh { positions: self.state.x.clone(), triangles: self.triangles().to_vec() }
    }

    /// Loop subdivision of the current shape, returned as a new frozen body: every vertex keeps
    /// its mass density (new vertices take the mean of their edge's ends, then all are scaled so
    /// the total mass is unchanged), pins carry over (a new vertex is pinned if both ends are),
    /// parameters are the same.
    pub fn subdivided(&self) -> Result<SoftBody, SimError> {
        Ok(self.subdivide_parts()?.0)
    }

    /// [`SoftBody::subdivided`] (or, `keep_tension`, [`SoftBody::subdivided_keeping_tension`])
    /// and, per vertex of the new body, its one or two parents in this one ([a, a] for a vertex
    /// that was there, [a, b] for one new on the edge a–b).
    pub(crate) fn subdivided_with_parents(&self, keep_tension: bool) -> Result<(SoftBody, Vec<[u32; 2]>), SimError> {
        let (body, parents, old_to_new) = if keep_tension { self.subdivide_keeping_tension_parts()? } else { self.subdivide_parts()? };
        let mut by_new = vec![[0u32; 2]; parents.len()];
        for (k, pa) in parents.iter().enumerate() {
            by_new[old_to_new[k] as usize] = *pa;
        }
        Ok((body, by_new))
    }

    /// Loop subdivision carrying the skin's tension: as [`SoftBody::subdivided`], then every
    /// spring's rest length is its length times the stretch ratio L/l carried from the input
    /// (per input vertex the mean L/l of its springs, edge and bending apart; a new vertex takes
    /// the mean of its parents', a spring the mean of its ends'), and the gas keeps the input's
    /// reference. Not at rest: freeze it keeping the tension (`World::subdivide` does), which
    /// corrects these rest lengths to an exact equilibrium close to them.
    pub fn subdivided_keeping_tension(&self) -> Result<SoftBody, SimError> {
        Ok(self.subdivide_keeping_tension_parts()?.0)
    }

    /// [`SoftBody::subdivided_keeping_tension`] with the parents and the reordering, as
    /// `subdivide_parts` gives them.
    fn subdivide_keeping_tension_parts(&self) -> Result<(SoftBody, Vec<[u32; 2]>, Vec<u32>), SimError> {
        let (mut body, parents, old_to_new) = self.subdivide_parts()?;
        let x = self.state.x.clone();
        let nv = body.vertex_count();
        for (old, new) in [(&self.model.springs, &mut body.model.springs), (&self.model.bending, &mut body.model.bending)] {
            let mut sum = vec![0.0; self.vertex_count()];
            let mut count = vec![0.0; self.vertex_count()];
            old.lengths_into(&x, |e, l| {
                let ratio = if l > 0.0 { old.rest[e] / l } else { 1.0 };
                for v in [old.i[e] as usize, old.j[e] as usize] {
                    sum[v] += ratio;
                    count[v] += 1.0;
                }
            });
            let at = |v: usize| if count[v] > 0.0 { sum[v] / count[v] } else { 1.0 };
            let mut ratio = vec![1.0; nv];
            for (k, pa) in parents.iter().enumerate() {
                ratio[old_to_new[k] as usize] = 0.5 * (at(pa[0] as usize) + at(pa[1] as usize));
            }
            let bx = body.state.x.clone();
            let mut rest = vec![0.0; new.len()];
            new.lengths_into(&bx, |e, l| rest[e] = l * 0.5 * (ratio[new.i[e] as usize] + ratio[new.j[e] as usize]));
            new.rest = rest;
        }
        body.model.gas = self.model.gas;
        Ok((body, parents, old_to_new))
    }

    /// The subdivided, plainly frozen body; each new vertex's one or two parents; and where
    /// each vertex of the subdivision went in the body (its vertices are reordered by locality).
    fn subdivide_parts(&self) -> Result<(SoftBody, Vec<[u32; 2]>, Vec<u32>), SimError> {
        let (mesh, parents) = subdivide::loop_subdivide(&self.to_mesh());
        let (mesh, old_to_new) = crate::mesh::reorder::by_locality(&mesh);
        let total: f64 = self.model.mass.iter().sum();
        let mut body = SoftBody::new(&mesh, total, self.material.clone()).map_err(|e| SimError::BadParameter { name: "subdivide", message: e.to_string() })?;
        let mut masses = vec![0.0; mesh.vertex_count()];
        let mut pinned = vec![false; mesh.vertex_count()];
        for (k, pa) in parents.iter().enumerate() {
            let i = old_to_new[k] as usize;
            masses[i] = 0.5 * (self.model.mass[pa[0] as usize] + self.model.mass[pa[1] as usize]);
            pinned[i] = self.is_pinned(pa[0] as usize) && self.is_pinned(pa[1] as usize);
        }
        let scale = total / masses.iter().sum::<f64>();
        masses.iter_mut().for_each(|m| *m *= scale);
        body.set_masses(&masses)?;
        for (i, &p) in pinned.iter().enumerate() {
            if p {
                body.set_pinned(i, true)?;
            }
        }
        body.freeze();
        Ok((body, parents, old_to_new))
    }
}

fn check_gas(gas: &GasReference) -> Result<(), SimError> {
    if !(gas.ambient_pressure.is_finite() && gas.reference_volume.is_finite() && gas.reference_volume > 0.0) {
        return Err(SimError::BadParameter { name: "gas reference", message: format!("must be finite with a positive volume, got {gas:?}") });
    }
    Ok(())
}
