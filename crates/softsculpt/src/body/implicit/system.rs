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
use super::super::hinges::{bend_crushed, rate, Hinges};
use std::sync::atomic::{AtomicU64, Ordering};
use super::ground::GroundSet;
use super::super::{gas, Model};
use super::super::forces::Fault;
use super::super::external;
use super::super::selfcontact::ContactTerms;
use crate::body::Material;
use crate::par::{chunk, chunks, Out, Threads};
use crate::settings::WorldSettings;

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

/// The vertex pass's per-entry outputs for its rows: `ecoef`, `bcoef`, `hcoef`.
type RowCoefs<'a> = (&'a mut [[f64; 5]], &'a mut [[f64; 5]], &'a mut [[f64; 3]]);

/// The vertex pass's inputs.
struct Rows<'a> {
    fr: &'a Frame<'a>,
    s: f64,
    gas: bool,
    fext_on: bool,
    edges: &'a SpringRows,
    bends: &'a SpringRows,
    faces: &'a FaceRows,
    absolute: bool,
    bending: bool,
    hinged: bool,
    hrows: &'a HingeRows,
    hg: &'a [[f64; 12]],
    hf: &'a [f64],
    hc: &'a [f64],
    nf: &'a [f64],
    gamma: f64,
    fext: &'a [f64],
    contacts: bool,
    cf: &'a [[f64; 4]],
    cblk: &'a [[f64; 6]],
    held: &'a [bool],
    grounded: bool,
}

/// Add row `i` of a spring kind at (x_t, v⁺): Σ ±fs d into `f`, Σ (a I + b d dᵀ) into `blk`,
/// Σ|fs d| into `abs`, Σ ¼ k (l − L)² into `energy` (each spring's ½ k (l − L)², half in each of
/// its rows); each entry kk's (a, b, d) into `coef[kk − base]`. Each spring is evaluated
/// in both its ends' rows, always from its first end i to its second j (d = (x_j − x_i)/l), so
/// both rows get the same bits, the forces are exactly opposite (momentum is kept to the last
/// bit) and no pass over the springs has to write them for the rows to gather (measured on the
/// modeler's 10,242-vertex sphere landing: the same time within noise, on 1 and 2 threads, as
/// with that pass, whose arrays of 64 B per spring are gone; the same bits).
/// `(k, cs, absolute)`: stiffness, damping, and how a compressed spring's negative transverse
/// factor 1 − L/l enters the matrix (clamped at 0, or its absolute value).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn gather_springs(rows: &SpringRows, rest: &[f64], (k, cs, absolute): (f64, f64, bool), dt: f64, (xt, vp): (&[f64], &[f64]), i: usize, (f, blk, abs, energy): (&mut [f64; 3], &mut [f64; 6], &mut f64, &mut f64), coef: &mut [[f64; 5]], base: usize) {
    let (dt2k, dtcs) = (dt * dt * k, dt * cs);
    for kk in rows.start[i] as usize..rows.start[i + 1] as usize {
        let e = rows.spring[kk] as usize;
        let o = rows.other[kk] as usize;
        let (sign, lo, hi) = if o > i { (1.0, 3 * i, 3 * o) } else { (-1.0, 3 * o, 3 * i) };
        let dx = [xt[hi] - xt[lo], xt[hi + 1] - xt[lo + 1], xt[hi + 2] - xt[lo + 2]];
        let l = (dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]).sqrt();
        let inv = 1.0 / l;
        let u = [dx[0] * inv, dx[1] * inv, dx[2] * inv];
        let dvn = (vp[hi] - vp[lo]) * u[0] + (vp[hi + 1] - vp[lo + 1]) * u[1] + (vp[hi + 2] - vp[lo + 2]) * u[2];
        let rest = rest[e];
        let fs = k * (l - rest) + cs * dvn;
        // ½ k (l − L)² per spring, half in each end's row.
        *energy += 0.25 * k * (l - rest) * (l - rest);
        let alpha = if absolute { (1.0 - rest * inv).abs() } else { (1.0 - rest * inv).max(0.0) };
        let (fx, fy, fz) = (fs * u[0], fs * u[1], fs * u[2]);
        f[0] += sign * fx;
        f[1] += sign * fy;
        f[2] += sign * fz;
        *abs += fx.abs() + fy.abs() + fz.abs();
        let (a, b) = (dt2k * alpha, dt2k * (1.0 - alpha) + dtcs);
        let [dx, dy, dz] = u;
        coef[kk - base] = [a, b, dx, dy, dz];
        blk[0] += a + b * dx * dx;
        blk[1] += a + b * dy * dy;
        blk[2] += a + b * dz * dz;
        blk[3] += b * dx * dy;
        blk[4] += b * dx * dz;
        blk[5] += b * dy * dz;
    }
}

/// blk += c g gᵀ, blk a symmetric 3×3 as (xx, yy, zz, xy, xz, yz): a rank-one term's diagonal
/// block (the gas's γ g gᵀ, a hinge's c_h ∇θ ∇θᵀ).
#[inline(always)]
fn add_outer(blk: &mut [f64; 6], c: f64, g: [f64; 3]) {
    blk[0] += c * g[0] * g[0];
    blk[1] += c * g[1] * g[1];
    blk[2] += c * g[2] * g[2];
    blk[3] += c * g[0] * g[1];
    blk[4] += c * g[0] * g[2];
    blk[5] += c * g[1] * g[2];
}

/// Inverse of the symmetric 3×3 (xx, yy, zz, xy, xz, yz) by its adjugate.
#[inline(always)]
fn inverse_sym(m: &[f64; 6]) -> [f64; 6] {
    let [a, d, f, b, c, e] = *m; // [[a b c] [b d e] [c e f]]
    let (c00, c11, c22) = (d * f - e * e, a * f - c * c, a * d - b * b);
    let (c01, c02, c12) = (c * e - b * f, b * e - c * d, b * c - a * e);
    let det = a * c00 + b * c01 + c * c02;
    let inv = 1.0 / det;
    [c00 * inv, c11 * inv, c22 * inv, c01 * inv, c02 * inv, c12 * inv]
}

impl Rows<'_> {
    #[allow(clippy::too_many_arguments)]
    fn run(&self, vr: std::ops::Range<usize>, vp: &[f64], xt: &[f64], (r, react): (&mut [f64], &mut [f64]), g: &mut [f64], diag: &mut [f64], pre: &mut [f64], coef: RowCoefs) -> [f64; 4] {
        let Frame { p, w, m, v, dt, .. } = *self.fr;
        let sys = self;
        let grav = [0.0, -w.gravity, 0.0];
        let c = p.damping;
        let targets = &m.targets;
        let (mut res2, mut noise2, mut energy) = (0.0, 0.0, 0.0);
        let (ecoef, bcoef, hcoef) = coef;
        let (ebase, bbase) = (sys.edges.start[vr.start] as usize, if sys.bending { sys.bends.start[vr.start] as usize } else { 0 });
        let hbase = if sys.hinged { sys.hrows.start[vr.start] as usize } else { 0 };
        for (li, i) in vr.enumerate() {
            let mi = m.mass[i];
            let mut f = [0.0; 3];
            let mut blk = [0.0; 6];
            let mut abs = 0.0;
            gather_springs(sys.edges, &m.springs.rest, (p.stiffness, p.spring_damping, sys.absolute), dt, (xt, vp), i, (&mut f, &mut blk, &mut abs, &mut energy), ecoef, ebase);
            if sys.bending {
                gather_springs(sys.bends, &m.bending.rest, (p.bending_stiffness, p.spring_damping, sys.absolute), dt, (xt, vp), i, (&mut f, &mut blk, &mut abs, &mut energy), bcoef, bbase);
            }
            if self.hinged {
                // Σ over the hinges around i: −D w (θ − θ̄ + τ θ̇) ∇_i θ, and c_h ∇_i θ ∇_i θᵀ.
                for k in sys.hrows.start[i] as usize..sys.hrows.start[i + 1] as usize {
                    let e = sys.hrows.entry[k];
                    let (h, s) = ((e / 4) as usize, 3 * (e % 4) as usize);
                    let g = &sys.hg[h][s..s + 3];
                    hcoef[k - hbase] = [g[0], g[1], g[2]];
                    let (fs, ch) = (sys.hf[h], sys.hc[h]);
                    f[0] += fs * g[0];
                    f[1] += fs * g[1];
                    f[2] += fs * g[2];
                    abs += fs.abs() * (g[0].abs() + g[1].abs() + g[2].abs());
                    add_outer(&mut blk, ch, [g[0], g[1], g[2]]);
                }
            }
            if self.gas {
                let mut gi = [0.0; 3];
                for k in sys.faces.start[i] as usize..sys.faces.start[i + 1] as usize {
                    let fidx = 3 * sys.faces.face[k] as usize;
                    gi[0] += sys.nf[fidx];
                    gi[1] += sys.nf[fidx + 1];
                    gi[2] += sys.nf[fidx + 2];
                }
                for d in 0..3 {
                    f[d] += self.s * gi[d];
                    g[3 * li + d] = gi[d];
                }
                abs += self.s.abs() * (gi[0].abs() + gi[1].abs() + gi[2].abs());
                add_outer(&mut blk, sys.gamma, gi);
            }
            if self.contacts {
                let (cf, cb) = (&self.cf[i], &self.cblk[i]);
                f[0] += cf[0];
                f[1] += cf[1];
                f[2] += cf[2];
                abs += cf[3];
                for q in 0..6 {
                    blk[q] += cb[q];
                }
            }
            let mut dg = mi * (1.0 + dt * c);
            let (kt, ct) = if targets.active() { (targets.k[i], targets.c[i]) } else { (0.0, 0.0) };
            if kt != 0.0 || ct != 0.0 {
                dg += dt * ct + dt * dt * kt;
            }
            // Rounding of the spring forces: k (l − L) loses ε |x| of l (x_j − x_i is rounded at the
            // scale of the positions), cs (Δv · d) ε |v|.
            let deg = (sys.edges.start[i + 1] - sys.edges.start[i]) as f64;
            let bdeg = if sys.bending { (sys.bends.start[i + 1] - sys.bends.start[i]) as f64 } else { 0.0 };
            let xa = xt[3 * i].abs() + xt[3 * i + 1].abs() + xt[3 * i + 2].abs();
            let va = vp[3 * i].abs() + vp[3 * i + 1].abs() + vp[3 * i + 2].abs();
            abs += (deg * p.stiffness + bdeg * p.bending_stiffness) * xa + (deg + bdeg) * p.spring_damping * va;
            let pinned = m.inv_mass[i] == 0.0;
            // Ground constraint: v⁺_y prescribed (`ground.rs`).
            let held = self.grounded && self.held[i];
            let mut r2 = 0.0;
            let mut scale = 0.0;
            for d in 0..3 {
                let k3 = 3 * i + d;
                let mut fd = f[d] + mi * grav[d] - c * mi * vp[k3];
                if m.external_active {
                    fd += m.external[k3];
                }
                if self.fext_on {
                    fd += sys.fext[k3];
                }
                if kt != 0.0 || ct != 0.0 {
                    fd += kt * (targets.anchor[k3] - xt[k3]) - ct * vp[k3];
                }
                let mut rd = if pinned { 0.0 } else { mi * (vp[k3] - v[k3]) - dt * fd };
                if held && d == 1 {
                    react[li] = rd;
                    rd = 0.0;
                }
                r[3 * li + d] = rd;
                r2 += rd * rd;
                scale += dt * fd.abs() + mi * (vp[k3].abs() + v[k3].abs());
            }
            scale += dt * abs;
            diag[li] = if pinned { 0.0 } else { dg };
            if pinned {
                pre[6 * li..6 * li + 6].fill(0.0);
            } else {
                blk[0] += dg;
                blk[1] += dg;
                blk[2] += dg;
                if held {
                    // The inverse of the x–z block alone: y's row and column removed.
                    (blk[1], blk[3], blk[5]) = (1.0, 0.0, 0.0);
                }
                let mut inv = inverse_sym(&blk);
                if held {
                    inv[1] = 0.0;
                }
                pre[6 * li..6 * li + 6].copy_from_slice(&inv);
                res2 += r2 / mi;
                // Rounding of r_i: a few ulps of the magnitudes summed into it.
                let nz = 16.0 * f64::EPSILON * scale;
                noise2 += nz * nz / mi;
            }
        }
        [res2, noise2, energy, 0.0]
    }
}

/// Per hinge at (x_t, v⁺): its bend's gradient ∇r, the force scale −D w (r + τ ṙ) and the
/// matrix coefficient (dt² + dt τ) D w (`(b, tau)` = D in J, τ in s), with r = θ − θ̄ and
/// ∇r = ∇θ, each × the fade Φ where a face is crushed (`hinges::bend`); a degenerate hinge (a
/// face without area), or with `let_go` a hinge with a crushed face, gets zeros. Returns
/// whether any hinge has a crushed face. The damping's dependence on x through ∇r is dropped, as the
/// springs' is.
#[allow(clippy::type_complexity)]
fn hinge_pass(th: &Threads, hn: &Hinges, (b, tau, let_go): (f64, f64, bool), dt: f64, (xt, vp): (&[f64], &[f64]), (hg, hf, hc, he): (&mut [[f64; 12]], &mut [f64], &mut [f64], &mut [f64]), slots: &mut [f64]) -> bool {
    let nh = hn.v.len();
    let nch = chunks(nh, ECHUNK);
    let (go, fo, co, eo) = (Out::new(hg), Out::new(hf), Out::new(hc), Out::new(he));
    th.each(&mut slots[..nch], |c, slot| {
        let hr = chunk(c, ECHUNK, nh);
        // SAFETY: chunk c writes hinges hr only.
        let (hg, hf, hc, he) = unsafe { (go.range(hr.clone()), fo.range(hr.clone()), co.range(hr.clone()), eo.range(hr.clone())) };
        let mut crushed = false;
        for (lh, h) in hr.enumerate() {
            let (bent, flat) = bend_crushed(xt, &hn.v[h], hn.rest[h], hn.thin[h], let_go);
            crushed |= flat;
            match bent {
                Some((r, g)) => {
                    let bw = b * hn.weight[h];
                    for (q, gq) in g.iter().enumerate() {
                        hg[lh][3 * q..3 * q + 3].copy_from_slice(gq);
                    }
                    hf[lh] = -bw * (r + tau * rate(&g, &hn.v[h], vp));
                    hc[lh] = (dt * dt + dt * tau) * bw;
                    he[lh] = 0.5 * bw * r * r;
                }
                None => {
                    hg[lh] = [0.0; 12];
                    hf[lh] = 0.0;
                    hc[lh] = 0.0;
                    he[lh] = 0.0;
                }
            }
        }
        *slot = if crushed { 1.0 } else { 0.0 };
    });
    slots[..nch].iter().any(|&c| c != 0.0)
}

/// Per face n_f into `nf`; returns 6V = Σ x_a · n_f (per-chunk sums added in chunk order).
fn face_pass(th: &Threads, tris: &[[u32; 3]], x: &[f64], nf: &mut [f64], slots: &mut [f64]) -> f64 {
    let n = tris.len();
    let out = Out::new(nf);
    th.each(slots, |c, slot| {
        let fr = chunk(c, ECHUNK, n);
        // SAFETY: chunk c writes faces fr only.
        let nf = unsafe { out.range(3 * fr.start..3 * fr.end) };
        let mut six_v = 0.0;
        for (lf, t) in tris[fr].iter().enumerate() {
            let (a, b, cc) = (3 * t[0] as usize, 3 * t[1] as usize, 3 * t[2] as usize);
            let e1 = [x[b] - x[a], x[b + 1] - x[a + 1], x[b + 2] - x[a + 2]];
            let e2 = [x[cc] - x[a], x[cc + 1] - x[a + 1], x[cc + 2] - x[a + 2]];
            let n3 = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
            six_v += x[a] * n3[0] + x[a + 1] * n3[1] + x[a + 2] * n3[2];
            nf[3 * lf..3 * lf + 3].copy_from_slice(&n3);
        }
        *slot = six_v;
    });
    slots.iter().sum()
}

/// The product and the preconditioner, for the conjugate gradient: matrix-free from the
/// pieces, or from a hinged body's blocks once summed.
impl System {
    /// out = A p, A = M + dt D + dt² K (see the module documentation); `gp` = g · p. Pinned
    /// rows are 0 (p is 0 there too), and so are the ground-held vertices' y rows (the callers'
    /// vectors are 0 there too: with both, the product is F A F, `ground.rs`).
    pub fn product(&self, th: &Threads, m: &Model, p: &[f64], gp: f64, out: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
        self.rows_pass::<false>(th, m, p, self.gamma * gp, &[], out, slots)
    }

    /// out = b − A' p, A' = A without the gas's rank-one term (the multigrid cycle's residual:
    /// `multigrid/`). Pinned rows are 0 (b and p are 0 there too).
    pub fn residual(&self, th: &Threads, m: &Model, p: &[f64], b: &[f64], out: &mut [f64], slots: &mut [[f64; 4]]) {
        assert!(b.len() >= 3 * m.mass.len());
        self.rows_pass::<true>(th, m, p, 0.0, b, out, slots);
    }

    /// The chunked pass of `product` (SUB = false) and `residual` (SUB = true): out = A p or
    /// b − A p, gg = γ (g · p); returns p · A p.
    #[allow(clippy::too_many_arguments)]
    fn rows_pass<const SUB: bool>(&self, th: &Threads, m: &Model, p: &[f64], gg: f64, b: &[f64], out: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
        let n = m.mass.len();
        assert!(p.len() >= 3 * n && self.diag.len() >= n && self.g.len() >= 3 * n && m.inv_mass.len() >= n);
        if self.hinged && !self.block_products() {
            // Per hinge c_h (∇θ · p), in as many ranges of hinges as there are vertex chunks
            // (each hinge's value is the same whatever the split).
            let (nh, nc) = (m.hinges.v.len(), slots.len());
            th.each(slots, |c, _| {
                for h in c * nh / nc..(c + 1) * nh / nc {
                    let (g, hv) = (&self.hg[h], &m.hinges.v[h]);
                    let mut s = 0.0;
                    for (q, &v) in hv.iter().enumerate() {
                        let o = 3 * v as usize;
                        s += g[3 * q] * p[o] + g[3 * q + 1] * p[o + 1] + g[3 * q + 2] * p[o + 2];
                    }
                    self.hp.set(h, self.hc[h] * s);
                }
            });
        }
        let o = Out::new(out);
        th.each(slots, |c, slot| {
            let vr = chunk(c, VCHUNK, n);
            // SAFETY: chunk c writes vertices vr only.
            let out = unsafe { o.range(3 * vr.start..3 * vr.end) };
            slot[0] = self.product_rows::<SUB>(m, vr, p, gg, b, out);
        });
        let mut pq: f64 = slots.iter().map(|s| s[0]).sum();
        if m.self_contacts.active() {
            // The self-contacts' rank-one terms, scattered in list order after the chunks.
            pq += self.contact.product::<SUB>(&m.self_contacts, &m.inv_mass, p, out);
            self.ground.filter(out);
        }
        pq
    }

    /// Rows `vr` of the product into `out`; returns their part of p · A p. On x86-64 with AVX2
    /// the same code is compiled a second time for it (VEX encoding; no FMA contraction, so the
    /// bits are the same either way) and chosen at run time, as in `springs.rs`.
    fn product_rows<const SUB: bool>(&self, m: &Model, vr: std::ops::Range<usize>, p: &[f64], gg: f64, b: &[f64], out: &mut [f64]) -> f64 {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports the feature the function is compiled for.
                return unsafe { self.product_rows_avx2::<SUB>(m, vr, p, gg, b, out) };
            }
        }
        self.product_rows_plain::<SUB>(m, vr, p, gg, b, out)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn product_rows_avx2<const SUB: bool>(&self, m: &Model, vr: std::ops::Range<usize>, p: &[f64], gg: f64, b: &[f64], out: &mut [f64]) -> f64 {
        self.product_rows_plain::<SUB>(m, vr, p, gg, b, out)
    }

    #[inline(always)]
    fn product_rows_plain<const SUB: bool>(&self, m: &Model, vr: std::ops::Range<usize>, p: &[f64], gg: f64, b: &[f64], out: &mut [f64]) -> f64 {
        let mut pq = 0.0;
        let grounded = self.ground.active();
        let blocks = self.block_products();
        for (li, i) in vr.enumerate() {
            if m.inv_mass[i] == 0.0 {
                out[3 * li..3 * li + 3].fill(0.0);
                continue;
            }
            let pi = [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
            let mut q = if blocks {
                // SAFETY: `rows_pass` asserts p.len() ≥ 3 n.
                unsafe { self.blocks.row(i, p) }
            } else {
                let dg = self.diag[i];
                let mut q = [dg * pi[0], dg * pi[1], dg * pi[2]];
                row_product(&self.edges, &self.ecoef, i, p, &pi, &mut q);
                if self.bending {
                    row_product(&self.bends, &self.bcoef, i, p, &pi, &mut q);
                }
                q
            };
            if self.hinged && !blocks {
                let (k0, k1) = (self.hrows.start[i] as usize, self.hrows.start[i + 1] as usize);
                for (&e, g) in self.hrows.entry[k0..k1].iter().zip(&self.hcoef[k0..k1]) {
                    let c = self.hp.get((e / 4) as usize);
                    q[0] += c * g[0];
                    q[1] += c * g[1];
                    q[2] += c * g[2];
                }
            }
            if gg != 0.0 {
                for d in 0..3 {
                    q[d] += gg * self.g[3 * i + d];
                }
            }
            if grounded && self.ground.held[i] {
                q[1] = 0.0;
            }
            pq += q[0] * pi[0] + q[1] * pi[1] + q[2] * pi[2];
            if SUB {
                for d in 0..3 {
                    q[d] = b[3 * i + d] - q[d]; // b is 0 where q is held at 0
                }
            }
            out[3 * li..3 * li + 3].copy_from_slice(&q);
        }
        pq
    }

    /// z_i = P_i⁻¹ r_i.
    #[inline(always)]
    pub fn precondition(&self, i: usize, r: &[f64; 3]) -> [f64; 3] {
        let b = &self.pre[6 * i..6 * i + 6];
        [b[0] * r[0] + b[3] * r[1] + b[4] * r[2], b[3] * r[0] + b[1] * r[1] + b[5] * r[2], b[4] * r[0] + b[5] * r[1] + b[2] * r[2]]
    }
}

#[inline(always)]
fn row_product(rows: &SpringRows, coef: &[[f64; 5]], i: usize, p: &[f64], pi: &[f64; 3], q: &mut [f64; 3]) {
    let (k0, k1) = (rows.start[i] as usize, rows.start[i + 1] as usize);
    for (&other, c) in rows.other[k0..k1].iter().zip(&coef[k0..k1]) {
        let o = 3 * other as usize;
        // SAFETY: `other` is a vertex of the body (the springs' indices are checked against the
        // vertex count when built) and `product` asserts p.len() ≥ 3 n.
        let pj = unsafe { [*p.get_unchecked(o), *p.get_unchecked(o + 1), *p.get_unchecked(o + 2)] };
        let dl = [pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2]];
        let [a, b, dx, dy, dz] = *c;
        let t = b * (dx * dl[0] + dy * dl[1] + dz * dl[2]);
        q[0] += a * dl[0] + t * dx;
        q[1] += a * dl[1] + t * dy;
        q[2] += a * dl[2] + t * dz;
    }
}
