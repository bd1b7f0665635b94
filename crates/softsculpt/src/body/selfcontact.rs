//! Self-contacts inside the implicit solve: one-sided penalty springs between a vertex and a
//! face of the same body, found by the world's contact broad and narrow phase at the start of
//! the step (`world/contacts.rs`, [`crate::world::World`]'s stage 1) and coupled into the
//! backward-Euler system (`implicit/system/`) like every other force.
//!
//! **Energy.** A vertex–face contact pairs vertex p with face (a, b, c) at barycentric weights
//! w (Σ w = 1) of the closest point q found at the start of the step, with n the unit vector
//! from q to p then (the face's normal where p is over the face). Both w and n are held for the
//! step (the contact's frame), so the gap
//!
//!   d(x) = n · (x_p − Σ_k w_k x_k) = uᵀ x,   u = (n, −w_a n, −w_b n, −w_c n)          (m)
//!
//! is linear in the positions. An edge–edge contact (edges a0 a1 and b0 b1, closest points at
//! parameters s and t, n from the second to the first) is the same with
//! u = ((1 − s) n, s n, −(1 − t) n, −t n). In general u = (g_k n), Σ g_k = 0, and
//! the energy
//!
//!   E_c = ½ k_c (h − d)²  for d < h,   0 otherwise                                      (J)
//!
//! (h the contact thickness) is C¹ and convex. Its force f = −∇E = k_c (h − d) u: +k_c (h − d) n
//! on the vertex, −w_k k_c (h − d) n on the face's corners (g_k k_c (h − d) n on vertex k).
//! Σ f = k_c (h − d) n Σ g = 0: the contact terms conserve momentum exactly. Its Hessian
//! k_c u uᵀ (where d < h) is rank one and positive semi-definite as it stands (no projection needed, the frame being fixed), so the
//! conjugate gradient's matrix stays positive definite; in Newton's matrix it is
//! dt² k_c u uᵀ (`System::product`), its diagonal blocks dt² k_c g_k² n nᵀ in the
//! preconditioner's blocks. The force and the active set (d < h) are evaluated exactly at every
//! Newton iterate; at d = h the force is 0 and the line search sees a C¹ energy.
//!
//! **Stiffness.** Along u the pair is one degree of freedom with effective mass
//! μ = 1 / Σ g_k² / m_k (pinned vertices: 1/m = 0). One backward-Euler step of that
//! degree of freedom under the spring and a load F (gap d, approach speed −v) gives
//!
//!   h − d⁺ = (h − d − dt v − dt² F / μ) / (1 + κ),     κ = dt² k_c / μ,
//!
//! i.e. the penetration the pair would reach in free flight, divided by 1 + κ. So with
//! k_c = κ μ / dt²:
//! - **a crossing is stopped within the step** when the free flight would have gone less than
//!   κ h behind the face: with κ = [`KAPPA`] = 100, h = 5 mm and dt = 1/60 s, any approach
//!   under 30 m/s;
//! - **a steady load F sinks the contact by F dt² / (κ μ)**. Here the loads that matter are
//!   not the body's weight (g dt² / κ = 0.03 mm) but its own springs pressing a crumpled skin
//!   together: ~k L, a spring compressed by its length (100 N/m × 6.5 cm = 6.5 N on the
//!   modeler's mushroom), against k_c = κ μ / dt² ≈ 750 N/m (vertex over a face's middle:
//!   μ = m_i / (1 + 3 (1/3)²) = 0.75 m_i ≈ 2 g): 1.3 mm per newton, under the thickness for
//!   loads up to ~4 N. Measured on the crushed
//!   mushroom (`tests/self_contact.rs`): κ = 16 left 144 edges through faces, 100 left 14 (all
//!   between faces within two rings of each other, a crumpled sliver), 400 and 1,600 left 6
//!   and 2 at 25 % more linear iterations;
//! - **the conditioning barely changes**: the contact adds κ μ ≈ 75 m_i to a vertex's
//!   diagonal, where the body's springs already add dt² Σk ≈ 60–120 m_i (k = k_b = 100 N/m,
//!   m_i = 2.8 g, six edges and six bending springs per vertex), so the largest eigenvalue of
//!   M⁻¹A grows by under 2× and the conjugate gradient's iterations by ~30 % (measured, last
//!   step of 10 s of the crushed mushroom: 35 without self-collision, 45 at κ = 16, 46 at
//!   κ = 100, 58 at κ = 400).
//!
//! Backward Euler damps the contact's own oscillation (ω dt = √κ = 10: amplitude × 1/√(1 + κ)
//! ≈ 0.1 per step), so a resting contact is still within a few steps: no contact damping is
//! added, and no friction (the skins' own damping stops sliding).

/// κ = dt² k_c / μ: how many times its own free-flight penetration a contact is stiff enough to
/// stop within one step (see the module documentation).
pub(crate) const KAPPA: f64 = 100.0;

/// One self-contact for the step: four vertices and signed weights g (Σ g = 0) so that the gap
/// is d = n · Σ g_k x_k. Vertex–face: (p, a, b, c) with g = (1, −w_a, −w_b, −w_c), w the
/// barycentric weights of the closest point on the face. Edge–edge: (a0, a1, b0, b1) with
/// g = (1 − s, s, −(1 − t), −t), s and t the closest points' parameters on the two edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SelfContact {
    pub idx: [u32; 4],
    pub g: [f64; 4],
    /// Unit normal from the second side to the first at the step's start.
    pub n: [f64; 3],
    /// Stiffness k_c = κ μ / dt² (N/m).
    pub k: f64,
}

/// The self-contacts of one step (set by the world before the body's implicit step, cleared
/// after): the list and the thickness h (m) they keep.
#[derive(Debug, Clone, Default)]
pub(crate) struct SelfContacts {
    pub list: Vec<SelfContact>,
    pub thickness: f64,
}

impl SelfContacts {
    pub fn active(&self) -> bool {
        !self.list.is_empty()
    }
}

/// The gap d = n · Σ g_k x_k of contact `c` in positions `x` (m), or the same combination of
/// any per-vertex vector (velocities: the normal relative velocity).
#[inline(always)]
pub(crate) fn along(c: &SelfContact, x: &[f64]) -> f64 {
    let mut d = 0.0;
    for q in 0..3 {
        let rel: f64 = (0..4).map(|k| c.g[k] * x[3 * c.idx[k] as usize + q]).sum();
        d += c.n[q] * rel;
    }
    d
}

/// The contact terms of one Newton evaluation, allocated once per body (per-vertex arrays on
/// the first step with contacts) and reused.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactTerms {
    /// Per contact: dt² k_c where the contact is active at the current iterate, else 0 (kg).
    pub kk: Vec<f64>,
    /// Per vertex: the contact force (N, xyz) and the sum of its magnitudes' |components| (the
    /// residual's rounding level); zero outside a Newton evaluation.
    pub f: Vec<[f64; 4]>,
    /// Per vertex: the contacts' part of its diagonal block (kg; xx, yy, zz, xy, xz, yz); zero
    /// outside a Newton evaluation.
    pub blk: Vec<[f64; 6]>,
}

impl ContactTerms {
    /// Forces and diagonal blocks of the contacts at positions `xt` into `f` and `blk`
    /// (scattered in list order, on the calling thread: the same bits for any thread count),
    /// and each contact's dt² k_c or 0 into `kk`. Call [`ContactTerms::clear`] after the
    /// vertex pass has read them.
    pub fn eval(&mut self, sc: &SelfContacts, n: usize, dt: f64, xt: &[f64]) {
        if self.f.len() != n {
            self.f = vec![[0.0; 4]; n];
            self.blk = vec![[0.0; 6]; n];
        }
        self.kk.clear();
        for c in &sc.list {
            let d = along(c, xt);
            if d >= sc.thickness {
                self.kk.push(0.0);
                continue;
            }
            let fs = c.k * (sc.thickness - d);
            let kk = dt * dt * c.k;
            self.kk.push(kk);
            let nn = [c.n[0] * c.n[0], c.n[1] * c.n[1], c.n[2] * c.n[2], c.n[0] * c.n[1], c.n[0] * c.n[2], c.n[1] * c.n[2]];
            for (&i, &s) in c.idx.iter().zip(&c.g) {
                let (f, b) = (&mut self.f[i as usize], &mut self.blk[i as usize]);
                for q in 0..3 {
                    f[q] += s * fs * c.n[q];
                    f[3] += (s * fs * c.n[q]).abs();
                }
                for q in 0..6 {
                    b[q] += s * s * kk * nn[q];
                }
            }
        }
    }

    /// Zero the per-vertex entries `eval` wrote.
    pub fn clear(&mut self, sc: &SelfContacts) {
        for c in &sc.list {
            for i in c.idx {
                self.f[i as usize] = [0.0; 4];
                self.blk[i as usize] = [0.0; 6];
            }
        }
    }

    /// out += A_c p (or −= when `SUB`), A_c = Σ dt² k_c u uᵀ over the active contacts, on the
    /// rows of free vertices (`inv_mass` ≠ 0; p is 0 on pinned ones); returns p · A_c p. In list
    /// order on the calling thread.
    pub fn product<const SUB: bool>(&self, sc: &SelfContacts, inv_mass: &[f64], p: &[f64], out: &mut [f64]) -> f64 {
        let mut pq = 0.0;
        for (c, &kk) in sc.list.iter().zip(&self.kk) {
            if kk == 0.0 {
                continue;
            }
            let up = along(c, p);
            let s = kk * up;
            pq += s * up;
            let s = if SUB { -s } else { s };
            for (&i, &wt) in c.idx.iter().zip(&c.g) {
                let i = i as usize;
                if inv_mass[i] != 0.0 {
                    for q in 0..3 {
                        out[3 * i + q] += wt * s * c.n[q];
                    }
                }
            }
        }
        pq
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eight vertices at pseudo-random positions (m) and a vertex–face and an edge–edge contact
    /// among them, both within the thickness.
    fn setup() -> (SelfContacts, Vec<f64>) {
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let x: Vec<f64> = (0..24).map(|_| 0.01 * rnd()).collect();
        let unit = |v: [f64; 3]| {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / l, v[1] / l, v[2] / l]
        };
        let list = vec![
            SelfContact { idx: [0, 1, 2, 3], g: [1.0, -0.2, -0.5, -0.3], n: unit([0.3, 1.0, -0.2]), k: 700.0 },
            SelfContact { idx: [4, 5, 6, 7], g: [0.6, 0.4, -0.7, -0.3], n: unit([-0.5, 0.2, 1.0]), k: 900.0 },
        ];
        (SelfContacts { list, thickness: 0.05 }, x)
    }

    /// The contact forces sum to zero (Σ g = 0: momentum is conserved; rounding: a few ulps of
    /// the forces, 1e-12 relative), they are minus the gradient of E = Σ ½ k_c (h − d)² (central
    /// differences with step 1e-7 m: the energy is quadratic between kinks, so the difference
    /// is exact up to rounding of E / step ≈ 1e-16 × 1 J / 1e-7 m = 1e-9 N), and the matrix
    /// dt² Σ k_c u uᵀ is symmetric and gives no force to a uniform translation (every
    /// vertex free for that check).
    #[test]
    fn contact_terms_conserve_momentum_and_are_the_energy_derivatives() {
        let (sc, x) = setup();
        let n = 8;
        let dt = 1.0 / 60.0;
        let mut ct = ContactTerms::default();
        ct.eval(&sc, n, dt, &x);
        assert!(ct.kk.iter().all(|&k| k > 0.0), "both contacts within the thickness");
        let (mut sum, mut mag) = ([0.0; 3], 0.0);
        for f in &ct.f {
            for q in 0..3 {
                sum[q] += f[q];
                mag += f[q].abs();
            }
        }
        assert!(sum.iter().all(|s| s.abs() <= 1e-12 * mag), "Σ f = {sum:?} of {mag} N");
        let energy = |x: &[f64]| sc.list.iter().map(|c| 0.5 * c.k * (sc.thickness - along(c, x)).max(0.0).powi(2)).sum::<f64>();
        for k in 0..3 * n {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[k] += 1e-7;
            xm[k] -= 1e-7;
            let grad = (energy(&xp) - energy(&xm)) / 2e-7;
            assert!((ct.f[k / 3][k % 3] + grad).abs() < 1e-6, "coordinate {k}: force {} against −∇E {}", ct.f[k / 3][k % 3], -grad);
        }
        // Symmetry and translation invariance of the product.
        let free = vec![1.0; n];
        let p: Vec<f64> = (0..3 * n).map(|k| (k as f64 * 0.37).sin()).collect();
        let q: Vec<f64> = (0..3 * n).map(|k| (k as f64 * 0.91).cos()).collect();
        let (mut ap, mut aq) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        ct.product::<false>(&sc, &free, &p, &mut ap);
        ct.product::<false>(&sc, &free, &q, &mut aq);
        let (qap, paq): (f64, f64) = (q.iter().zip(&ap).map(|(a, b)| a * b).sum(), p.iter().zip(&aq).map(|(a, b)| a * b).sum());
        assert!((qap - paq).abs() <= 1e-12 * (qap.abs() + paq.abs()), "qᵀAp {qap} vs pᵀAq {paq}");
        let t: Vec<f64> = (0..3 * n).map(|k| [0.3, -1.0, 0.7][k % 3]).collect();
        let mut at = vec![0.0; 3 * n];
        let tat = ct.product::<false>(&sc, &free, &t, &mut at);
        assert!(at.iter().all(|v| v.abs() < 1e-12) && tat.abs() < 1e-12, "a translation is pushed: {at:?}");
        ct.clear(&sc);
        assert!(ct.f.iter().all(|f| *f == [0.0; 4]) && ct.blk.iter().all(|b| *b == [0.0; 6]));
    }
}
