//! The backward-Euler system of one body: forces, residual, preconditioner and the matrix-free
//! product, each one pass that the thread pool splits into chunks (`crate::par`).
//!
//! Unknown: the end-of-step velocity v⁺ (flat xyz). With x_t = x + dt v⁺ the residual is
//!
//!   r(v⁺) = M (v⁺ − v) − dt f(x_t, v⁺)                                  (kg·m/s)
//!
//! and Newton's matrix is ∂r/∂v⁺ = M − dt ∂f/∂v − dt² ∂f/∂x = M + dt D + dt² K, with K = −∂f/∂x
//! and D = −∂f/∂v. What enters the matrix, per force (the residual always uses the exact force):
//!
//! - **spring** (i, j), l = |x_j − x_i|, d = (x_j − x_i)/l, L rest length: f_i = [k (l − L) +
//!   cs (v_j − v_i)·d] d. Its elastic Hessian block is k [(1 − L/l)(I − d dᵀ) + d dᵀ]; the
//!   transverse factor (1 − L/l) is negative for a compressed spring, so it is clamped at 0
//!   (the block is then positive semi-definite: Choi & Ko 2002, the standard projection) —
//!   or, once a step's Newton iteration has overshot (`absolute`, set by the Newton loop:
//!   `mod.rs`), replaced by its absolute value |1 − L/l| (Chen et al. 2024, trust-region
//!   eigenvalue filtering: the absolute value where the quadratic model proved untrustworthy).
//!   Damping adds cs d dᵀ to D. The derivative of the damping force through d (∝ cs (v·d)/l) is
//!   not symmetric and is dropped. Per spring: B = dt² K_e + dt D_e = a I + b d dᵀ with
//!   a = dt² k α, b = dt² k (1 − α) + dt cs, α = max(0, 1 − L/l) (or |1 − L/l| after an
//!   overshoot: then b < 0 for a spring compressed below about half its rest length, but B's
//!   eigenvalues a, a and a + b = dt² k + dt cs stay positive); it couples i and j as
//!   [B −B; −B B]. Bending springs are the same with k_b.
//! - **hinge** (`body/hinges.rs`) f_v = −D w (θ − θ̄ + τ θ̇) ∇_v θ on its four vertices: the
//!   Gauss–Newton part dt² D w ∇θ ∇θᵀ (positive semi-definite, rank one) and the damping's
//!   dt τ D w ∇θ ∇θᵀ (exact but for ∇θ's dependence on x, dropped) enter the matrix,
//!   applied as c_h ∇θ (∇θ · p) per hinge, or, once a conjugate gradient runs long, summed
//!   with the springs into 3×3 blocks per coupled pair (`blocks.rs`, [`System::prepare`]);
//!   the indefinite dt² D w (θ − θ̄) ∇²θ is dropped (it vanishes at the rest angle). Its diagonal 3×3 blocks go
//!   into the block-Jacobi preconditioner and its rank-one blocks into the multigrid's coarse
//!   levels (`multigrid/`).
//! - **viscous damping** −c m v: D += c m I (exact).
//! - **gravity**, user forces, the kept load of a freeze under load: constant, nothing.
//! - **gas** f_i = (P − P_ref) ∇_i V, P = nRT/V: −∂f/∂x = (nRT/V²) ∇V ∇Vᵀ − (P − P_ref) ∇²V. The
//!   first term is positive semi-definite and rank one: it is applied as γ g (g · p) with
//!   g_i = Σ n_f (= 6 ∇_i V) and γ = dt² nRT / (36 V²), never as a dense matrix. The second is
//!   dropped: ∇²V (per face, p_b × x_c + x_b × p_c over the corners) is indefinite — it would
//!   break the conjugate gradient's positive definiteness — and small next to the springs
//!   (P · edge / 6 against k: 1e-4 of k in the standard workload). In the box and sphere volume
//!   modes the same rank-one term with their V is used as an approximation.
//! - **wind** and **face pressures**: their derivatives (through the face normals and the face
//!   velocities) are dropped: the wind's velocity term cw·area/9 per face pair is ~1 % of m/dt
//!   for a 642-vertex body at dt = 1/60 s, and face pressures are loads.
//! - **target springs** f_i = k_t (a_i − x_i) − c_t v_i (`body/targets.rs`): K += k_t I,
//!   D += c_t I (exact), so any strength is stable.
//! - **self-contacts** (`body/selfcontact.rs`): one-sided penalty springs ½ k_c (h − d)² between
//!   a vertex and a face of the same body, d linear in x in the step's frame: K += k_c u uᵀ
//!   where d < h (exact). Forces and diagonal blocks are scattered on the calling thread before
//!   the vertex pass; the product adds the rank-one terms after its chunked pass.
//! - **pins**: a pinned vertex keeps v⁺ = v; its rows and columns are removed (its residual,
//!   preconditioner and product entries are 0).
//! - **the ground** (`ground.rs`): a held vertex has its v⁺_y prescribed (0 at rest; a vertex
//!   landing in the step: `ground.rs`); that row and column are removed the same way, and the
//!   residual's removed component is kept as the ground's impulse (`GroundSet::react`).
//!
//! Dropping terms from the matrix only slows Newton's convergence (an inexact Newton method);
//! the solution it converges to is the backward-Euler step with every force exact.

use super::adjacency::{FaceRows, HingeRows, SpringRows};
use super::Relaxed;
use super::blocks::{Blocks, Pieces};
use std::sync::atomic::{AtomicU64, Ordering};
use super::ground::GroundSet;
use super::super::{gas, Model};
use super::super::forces::Fault;
use super::super::external;
use super::super::selfcontact::ContactTerms;
use crate::body::Material;
use crate::par::{chunk, chunks, Out, Threads};
use crate::settings::WorldSettings;

mod product;
mod rows;

use rows::{face_pass, hinge_pass, Rows};

/// Vertices per chunk of a vertex pass (independent of the thread count).
pub(crate) const VCHUNK: usize = 2048;
/// Hinges or faces per chunk.
const ECHUNK: usize = 4096;

/// What a step holds fixed: material, settings, model, the state at the step's start, dt.
#[derive(Clone, Copy)]
pub(crate) struct Frame<'a> {
    pub p: &'a Material,
    pub w: &'a WorldSettings,
    pub m: &'a Model,
    pub x: &'a [f64],
    pub v: &'a [f64],
    pub dt: f64,
    /// What of the hinges this solve lets go of (the relaxed retry of a step: `mod.rs`).
    pub relax: Relaxed,
}

/// Everything the Newton iterations of one body need, allocated once.
#[derive(Debug, Clone, Default)]
pub(crate) struct System {
    pub edges: SpringRows,
    pub bends: SpringRows,
    pub faces: FaceRows,
    /// Per CSR entry of `edges` (and of `bends`), in row order: the spring's (a, b, d) as the
    /// product reads them. The vertex pass writes them there once per Newton evaluation
    /// (`gather_springs`), so that each of the many products of the conjugate gradient streams
    /// one array in order instead of gathering per-spring values through the spring index
    /// (measured: the product was 63 % of the step, bound by those indirect loads).
    pub ecoef: Vec<[f64; 5]>,
    pub bcoef: Vec<[f64; 5]>,
    /// Bending springs take part (k_b > 0), as in the explicit stages.
    pub bending: bool,
    /// Hinges (`body/hinges.rs`): per vertex the hinges around it; per hinge at (x_t, v⁺) the
    /// gradient ∇θ at its four vertices (1/m), the force scale −D w (θ − θ̄ + τ θ̇) (J) and the matrix
    /// coefficient (dt² + dt τ) D w (kg·m²); the product's per-hinge c_h (∇θ · p) (`HingeProducts`).
    pub hrows: HingeRows,
    pub hg: Vec<[f64; 12]>,
    /// Per entry of `hrows`, in row order: the hinge's ∇_i θ at that row's vertex, copied there
    /// by the vertex pass (as `ecoef`), so the product streams it instead of gathering `hg`.
    pub hcoef: Vec<[f64; 3]>,
    pub hf: Vec<f64>,
    pub hc: Vec<f64>,
    /// Per hinge at x_t: its bending energy ½ D w r² (J), for the step's potential
    /// (`potential.rs`).
    pub he: Vec<f64>,
    hp: HingeProducts,
    /// The matrix as 3×3 blocks for the products of a hinged body (`blocks.rs`), summed by
    /// [`System::prepare`] when the conjugate gradient asks (`cg::BLOCKS_AFTER`); every
    /// evaluation marks them stale.
    pub blocks: Blocks,
    /// Hinges take part (B > 0).
    pub hinged: bool,
    /// n_f = (x_b − x_a) × (x_c − x_a) per face (m², xyz).
    pub nf: Vec<f64>,
    /// g_i = Σ n_f around vertex i (m²), the gas's gradient direction; used when `gamma` ≠ 0.
    pub g: Vec<f64>,
    /// Scalar diagonal m (1 + dt c) + dt c_t + dt² k_t per vertex (kg).
    pub diag: Vec<f64>,
    /// Inverse of each vertex's 3×3 diagonal block (xx, yy, zz, xy, xz, yz), 0 when pinned.
    pub pre: Vec<f64>,
    /// Wind and face pressure forces (N), when present.
    pub fext: Vec<f64>,
    /// dt² nRT / (36 V²) (kg/m⁴·… so that γ g gᵀ is in kg): the gas's rank-one term.
    pub gamma: f64,
    /// Self-contact terms (`body/selfcontact.rs`), used when the model has self-contacts.
    pub contact: ContactTerms,
    /// The vertices the ground constrains this step (`ground.rs`).
    pub ground: GroundSet,
    /// Compressed springs enter the matrix with their transverse stiffness's absolute value
    /// instead of clamped at 0 (see the module documentation; the Newton loop sets it).
    pub absolute: bool,
    /// The last evaluation's springs' (and bending springs') energy Σ ½ k (l − L)² and the gas's
    /// (`gas::energy`) at its x_t (J), for the step's potential (`potential.rs`).
    pub spring_energy: f64,
    pub gas_energy: f64,
    /// Reduction slots, one per chunk.
    pub vslots: Vec<[f64; 4]>,
    hslots: Vec<f64>,
    /// The last evaluation met a hinge with a crushed face (`hinges::bend_crushed`): what
    /// makes a refused step a candidate for the relaxed retry (`mod.rs`).
    pub crushed: bool,
    fslots: Vec<f64>,
}

/// Norms of one evaluation, mass-weighted: Σ |r_i|² / m_i (J·kg… = (kg·m/s)²/kg).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    pub res2: f64,
    pub noise2: f64,
}

/// One value per hinge that the product's hinge pass writes (each hinge its own) and its row
/// pass reads after the join: f64 bits in atomics, so that `product` can take `&self`.
#[derive(Debug, Default)]
struct HingeProducts(Vec<AtomicU64>);

impl Clone for HingeProducts {
    fn clone(&self) -> Self {
        HingeProducts(self.0.iter().map(|a| AtomicU64::new(a.load(Ordering::Relaxed))).collect())
    }
}

impl HingeProducts {
    fn new(n: usize) -> Self {
        HingeProducts((0..n).map(|_| AtomicU64::new(0)).collect())
    }
    #[inline(always)]
    fn set(&self, h: usize, v: f64) {
        self.0[h].store(v.to_bits(), Ordering::Relaxed);
    }
    #[inline(always)]
    fn get(&self, h: usize) -> f64 {
        f64::from_bits(self.0[h].load(Ordering::Relaxed))
    }
}

impl System {
    pub fn new(m: &Model) -> Self {
        let n = m.mass.len();
        let nf = m.faces.len();
        System {
            edges: SpringRows::new(n, &m.springs.i, &m.springs.j),
            bends: SpringRows::new(n, &m.bending.i, &m.bending.j),
            faces: FaceRows::new(n, m.faces.triangles()),
            ecoef: vec![[0.0; 5]; 2 * m.springs.len()],
            bcoef: vec![[0.0; 5]; 2 * m.bending.len()],
            bending: false,
            // The hinges' arrays (~230 B per hinge, and the blocks' sparsity ~90 B per hinge)
            // wait for the first evaluation with D > 0; the blocks themselves (~940 B per vertex)
            // for the first sum (`blocks.rs`).
            hrows: HingeRows::default(),
            hg: Vec::new(),
            hcoef: Vec::new(),
            hf: Vec::new(),
            hc: Vec::new(),
            he: Vec::new(),
            spring_energy: 0.0,
            gas_energy: 0.0,
            hp: HingeProducts::default(),
            blocks: Blocks::default(),
            hinged: false,
            nf: vec![0.0; 3 * nf],
            g: vec![0.0; 3 * n],
            diag: vec![0.0; n],
            pre: vec![0.0; 6 * n],
            fext: vec![0.0; 3 * n],
            gamma: 0.0,
            contact: ContactTerms::default(),
            ground: GroundSet::new(n),
            absolute: false,
            vslots: vec![[0.0; 4]; chunks(n, VCHUNK)],
            hslots: vec![0.0; chunks(m.hinges.len(), ECHUNK)],
            crushed: false,
            fslots: vec![0.0; chunks(nf, ECHUNK)],
        }
    }

    /// Fits `m` (same vertex, spring and face counts as when built).
    pub fn fits(&self, m: &Model) -> bool {
        self.diag.len() == m.mass.len() && self.ecoef.len() == 2 * m.springs.len() && self.bcoef.len() == 2 * m.bending.len() && 3 * m.faces.len() == self.nf.len() && (self.hf.is_empty() || self.hf.len() == m.hinges.v.len())
    }

    /// The hinges' arrays, allocated on the first evaluation that has hinges.
    fn ensure_hinges(&mut self, m: &Model) {
        let nh = m.hinges.v.len();
        if self.hf.len() != nh {
            self.hrows = HingeRows::new(m.mass.len(), &m.hinges.v);
            self.hg = vec![[0.0; 12]; nh];
            self.hcoef = vec![[0.0; 3]; 4 * nh];
            self.hf = vec![0.0; nh];
            self.hc = vec![0.0; nh];
            self.he = vec![0.0; nh];
            self.hp = HingeProducts::new(nh);
        }
        if !self.blocks.fits(m.mass.len(), self.hrows.entry.len()) {
            self.blocks = Blocks::new(m.mass.len(), &self.edges, &self.bends, &self.hrows, &m.hinges.v);
        }
    }

    /// The products' blocks from the last evaluation's pieces (`blocks.rs`), if the body is
    /// hinged and they are not summed yet (`Cg::solve` calls it once a solve runs long). Until
    /// then the products take the pieces themselves: the same matrix up to rounding.
    pub fn prepare(&mut self, th: &Threads, m: &Model) {
        if !self.hinged || self.blocks.ready {
            return;
        }
        let pieces = Pieces {
            edges: &self.edges,
            bends: &self.bends,
            ecoef: &self.ecoef,
            bcoef: &self.bcoef,
            bending: self.bending,
            hrows: &self.hrows,
            hcoef: &self.hcoef,
            hg: &self.hg,
            hc: &self.hc,
            diag: &self.diag,
            inv_mass: &m.inv_mass,
        };
        let mut slots = std::mem::take(&mut self.vslots);
        self.blocks.assemble(th, VCHUNK, &pieces, &mut slots);
        self.vslots = slots;
    }

    /// Whether the products take the summed blocks (a hinged body after `prepare`, until the
    /// next evaluation) rather than the pieces.
    fn block_products(&self) -> bool {
        self.hinged && self.blocks.ready
    }

    /// Forces at (x_t, v⁺), the residual r (into `r`), the matrix's coefficients and the
    /// preconditioner. `xt` = x + dt v⁺ on entry.
    pub fn eval(&mut self, th: &Threads, fr: &Frame, vp: &[f64], xt: &[f64], r: &mut [f64]) -> Result<Eval, Fault> {
        let (p, w, m, dt) = (fr.p, fr.w, fr.m, fr.dt);

        self.blocks.ready = false;
        // Springs: evaluated in the vertex pass (`gather_springs`).
        self.bending = p.bending_stiffness > 0.0;
        self.hinged = p.rigidity > 0.0 && !m.hinges.v.is_empty() && fr.relax != Relaxed::Unbent;
        self.crushed = false;
        if self.hinged {
            self.ensure_hinges(m);
            let let_go = fr.relax == Relaxed::Crushed;
            self.crushed = hinge_pass(th, &m.hinges, (p.rigidity, p.retardation_time(), let_go), dt, (xt, vp), (&mut self.hg, &mut self.hf, &mut self.hc, &mut self.he), &mut self.hslots);
        }

        // Faces and gas: n_f per face and 6V (per-chunk sums in chunk order), then P.
        let nrt = p.nrt();
        let gas_active = nrt != 0.0 || m.gas.ambient_pressure != 0.0;
        let mut s = 0.0;
        self.gamma = 0.0;
        self.gas_energy = 0.0;
        if gas_active {
            let six_v = face_pass(th, m.faces.triangles(), xt, &mut self.nf, &mut self.fslots);
            if !six_v.is_finite() {
                return Err(Fault::NonFinite);
            }
            let volume = gas::measure(m.faces.triangles(), p.volume_mode, six_v, xt);
            if !(volume > 0.0) {
                return Err(if volume.is_finite() { Fault::Collapsed(volume) } else { Fault::NonFinite });
            }
            s = (gas::pressure(nrt, volume) - m.gas.ambient_pressure) / 6.0;
            self.gas_energy = gas::energy(nrt, volume, &m.gas);
            self.gamma = dt * dt * nrt / (36.0 * volume * volume);
        }

        // Wind and face pressures (rare; one thread, scattered per face).
        let wind = w.wind_drag > 0.0 && w.wind != [0.0; 3];
        let fext_active = wind || m.face_pressure_active;
        if fext_active {
            self.fext.fill(0.0);
            if wind {
                external::wind(m.faces.triangles(), xt, vp, w.wind, w.wind_drag, &mut self.fext);
            }
            if m.face_pressure_active {
                external::face_pressures(m.faces.triangles(), xt, &m.face_pressure, 1.0, &mut self.fext);
            }
        }

        // Self-contacts: their forces and diagonal blocks, read by the vertex pass.
        let contacts = m.self_contacts.active();
        if contacts {
            self.contact.eval(&m.self_contacts, m.mass.len(), dt, xt);
        }

        // Vertices: gather forces, residual, diagonal blocks.
        let rows = Rows {
            fr,
            s,
            gas: gas_active,
            fext_on: fext_active,
            edges: &self.edges,
            bends: &self.bends,
            faces: &self.faces,
            absolute: self.absolute,
            bending: self.bending,
            hinged: self.hinged,
            hrows: &self.hrows,
            hg: &self.hg,
            hf: &self.hf,
            hc: &self.hc,
            nf: &self.nf,
            gamma: self.gamma,
            fext: &self.fext,
            contacts,
            cf: &self.contact.f,
            cblk: &self.contact.blk,
            held: &self.ground.held,
            grounded: self.ground.active(),
        };
        let (g, diag, pre) = (Out::new(&mut self.g), Out::new(&mut self.diag), Out::new(&mut self.pre));
        let ro = Out::new(r);
        let react = Out::new(&mut self.ground.react);
        let (ec, bc, hcf) = (Out::new(&mut self.ecoef), Out::new(&mut self.bcoef), Out::new(&mut self.hcoef));
        let (es, bs, hs, hinged) = (&self.edges.start, &self.bends.start, &self.hrows.start, self.hinged);
        let n = m.mass.len();
        let mut slots = std::mem::take(&mut self.vslots);
        th.each(&mut slots, |c, slot| {
            let vr = chunk(c, VCHUNK, n);
            // SAFETY: chunk c writes vertices vr only; chunks are disjoint.
            // (The CSR entries of rows vr are start[vr.start]..start[vr.end]: also disjoint.)
            unsafe {
                let coef = (ec.range(es[vr.start] as usize..es[vr.end] as usize), bc.range(bs[vr.start] as usize..bs[vr.end] as usize), if hinged { hcf.range(hs[vr.start] as usize..hs[vr.end] as usize) } else { &mut [] });
                let (r, react) = (ro.range(3 * vr.start..3 * vr.end), react.range(vr.clone()));
                *slot = rows.run(vr.clone(), vp, xt, (r, react), g.range(3 * vr.start..3 * vr.end), diag.range(vr.clone()), pre.range(6 * vr.start..6 * vr.end), coef);
            }
        });
        let (mut res2, mut noise2, mut energy) = (0.0, 0.0, 0.0);
        for sl in &slots {
            res2 += sl[0];
            noise2 += sl[1];
            energy += sl[2];
        }
        self.spring_energy = energy;
        self.vslots = slots;
        if contacts {
            self.contact.clear(&m.self_contacts);
        }
        if !res2.is_finite() {
            return Err(Fault::NonFinite);
        }
        Ok(Eval { res2, noise2 })
    }
}
