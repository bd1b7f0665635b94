//! Bodies that start overlapping: contacts between them are off until they part.
//!
//! A file often holds its parts as pieces that overlap or touch where they join (a robot's
//! links, a teddy's limbs sewn into its body). Each piece becomes a body; were the contact stage
//! to keep each body out of the others, it would push the pieces apart at once — measured on
//! urdf_000 (5 overlapping pieces): they flew apart and jittered at 2–6 m/s for good. Merging
//! them into one surface is a mesh boolean that a file's pieces rarely allow (open seams,
//! coincident faces), so SoftSculpt does what assembled models in rigid-body engines do (Box2D's
//! `collideConnected = false` on a joint, Bullet's collision filter pairs): **the pairs of bodies
//! that overlap or touch when the model is made take no contact with each other** — neither
//! vertex against face nor edge against edge — **until they part**: once their bounding boxes,
//! grown by the contact stage's query radius (the largest triangle radius plus the contact
//! thickness), no longer overlap, the pair is dropped from the set and they collide as any two
//! bodies do from then on. Each body still meets the ground, the obstacles and every other body.
//!
//! "Overlap or touch" is the contact stage's own test: some vertex of one body within the
//! contact thickness in front of a face of the other, or behind it by less than the largest
//! triangle radius (where the surfaces cross) — what the stage would respond to.
//!
//! The set is state (it changes as pairs part, and what it holds changes the next step): the
//! snapshot keeps it (version 7), a rollback or rewind puts it back with the clock.

use super::World;
use crate::vec3::get;

/// Pairs of bodies `[a, b]`, a < b, whose contacts with each other are off until they part.
pub(crate) type Overlaps = Vec<[u32; 2]>;

impl World {
    /// Turn contacts off between every pair of bodies that overlap or touch now (the module
    /// documentation), until they part; returns the pairs, lower index first. For a model made
    /// of pieces that were meant to be together (an import's pieces).
    pub fn let_overlapping_bodies_be(&mut self) -> Vec<[usize; 2]> {
        let found = self.touching_pairs();
        for &[a, b] in &found {
            let pair = [a as u32, b as u32];
            if !self.overlaps.contains(&pair) {
                self.overlaps.push(pair);
            }
        }
        self.overlaps.sort_unstable();
        found
    }

    /// The pairs of bodies whose contacts are off until they part, lower index first.
    pub fn overlapping_bodies(&self) -> Vec<[usize; 2]> {
        self.overlaps.iter().map(|p| p.map(|i| i as usize)).collect()
    }

    /// Whether contacts between bodies `a` and `b` (a ≠ b) are off.
    pub(super) fn overlooked(&self, a: usize, b: usize) -> bool {
        !self.overlaps.is_empty() && self.overlaps.contains(&[a.min(b) as u32, a.max(b) as u32])
    }

    /// Drop the pairs that have parted: their `boxes` (each body's bounding box grown by the
    /// query radius) no longer overlap.
    pub(super) fn part_overlaps(&mut self, boxes: &[([f64; 3], [f64; 3])]) {
        self.overlaps.retain(|&[a, b]| {
            let (p, q) = (boxes[a as usize], boxes[b as usize]);
            (0..3).all(|d| p.0[d] <= q.1[d] && q.0[d] <= p.1[d])
        });
    }

    /// Pairs of distinct bodies in contact now by the contact stage's own test (a vertex of one
    /// within the thickness in front of a face of the other, or behind it by less than the
    /// largest triangle radius), lower index first.
    fn touching_pairs(&mut self) -> Vec<[usize; 2]> {
        let mut found: Vec<[usize; 2]> = Vec::new();
        let reach = self.gather_triangles();
        let radius = reach + self.settings.contact.thickness;
        if !(radius.is_finite() && radius > 0.0) || self.bodies.len() < 2 {
            return found;
        }
        self.clear_near();
        let zones = self.contact_zones(radius);
        if !self.hash_triangles_in(&zones, radius) {
            return found;
        }
        for bi in 0..self.bodies.len() {
            for vi in 0..self.bodies[bi].vertex_count() {
                let p = get(self.bodies[bi].positions(), vi);
                if !super::contacts::in_zones(&zones[bi], p, 0.0) {
                    continue;
                }
                if let Some(ob) = self.deepest_contact(bi, vi, p, radius, reach).map(|c| c.ob).filter(|&ob| ob != bi) {
                    let pair = [bi.min(ob), bi.max(ob)];
                    if !found.contains(&pair) {
                        found.push(pair);
                    }
                }
            }
        }
        found.sort_unstable();
        found
    }
}
