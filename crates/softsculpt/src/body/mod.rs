//! A soft body: its material, masses, pins, prestress, frozen state, gas reference and state, in
//! flat arrays. A body does not step on its own: a [`crate::world::World`] steps it (a lone body
//! is a one-body world), handing it the world's settings.
//!
//! The body's own stage of a world step ([`SoftBody::integrate`]):
//! 1. **faces**    – exact volume and Σ face normals per vertex, in one pass over faces.
//! 2. **gas**      – the pressure P = nRT / V from the selected volume, minus the surroundings'.
//! 3. **springs**  – Hooke + spring damping on every edge (and on the bending springs, if any).
//! 4. **external** – wind and user face pressures (only when set).
//! 5. **vertices** – a = f / m + g_vec − c v, then the integrator (fused into this pass for
//!    symplectic Euler); the force accumulator is cleared on the way.
//!
//! Stages 1–4 add into one force accumulator; `forces.rs` explains how the gas force shares it.
//! The ground, obstacles and contacts are the world's stages that follow (`crate::world`); the
//! body's **plastic** stage (`plastic.rs`: rest lengths flow where the strain exceeds the yield
//! strain) comes last, on the step's final positions.
//!
//! All arrays are `xyz` interleaved per vertex (`[x0, y0, z0, x1, …]`), so a renderer can read
//! positions without copying and a spring touches one cache line per end.

mod external;
mod faces;
mod forces;
mod freeze;
mod gas;
mod growth;
pub(crate) mod hinges;
pub mod implicit;
mod integrate;
pub mod material;
mod modeling;
mod parforces;
mod persist;
mod plastic;
mod remesh;
pub(crate) mod selfcontact;
mod springs;
mod stats;
mod targets;
mod tension;

pub use faces::Faces;
pub use freeze::{FreezeOptions, FreezeReport, Supports};
pub use gas::GasReference;
pub use plastic::PlasticState;
pub use material::{moles, Material, VolumeMode, DEFAULT_TEMPERATURE, GAS_CONSTANT};
pub use springs::Springs;
pub use implicit::{LineStats, Relaxed, SolverIterations};
pub use stats::Stats;
pub use targets::Target;

use crate::error::{MeshError, SimError};
use crate::mesh::{topology, TriMesh};
use crate::settings::WorldSettings;

/// Per-vertex and per-face data that the force stages read.
#[derive(Debug, Clone)]
pub(crate) struct Model {
    pub faces: Faces,
    pub springs: Springs,
    /// Bending springs across every interior edge (stiffness `Material::bending_stiffness`).
    pub bending: Springs,
    /// Hinges at every interior edge (flexural rigidity `Material::rigidity`; `hinges.rs`),
    /// their rest angles and weights from the frozen shape.
    pub hinges: hinges::Hinges,
    /// Every edge shared by exactly two faces.
    pub closed: bool,
    /// Vertex masses mi (kg).
    pub mass: Vec<f64>,
    /// 1 / mi (1/kg), 0 for pinned vertices.
    pub inv_mass: Vec<f64>,
    /// User force on each vertex (N, flat xyz), e.g. the mouse grab.
    pub user_force: Vec<f64>,
    /// Load kept by a freeze under load (N, flat xyz), see `SoftBody::freeze_under_load`.
    pub prestress: Vec<f64>,
    /// user_force + prestress: what the vertex stage adds (N, flat xyz).
    pub external: Vec<f64>,
    pub external_active: bool,
    /// User pressure on each face (Pa), pushing along the inward normal.
    pub face_pressure: Vec<f64>,
    pub face_pressure_active: bool,
    pub gas: GasReference,
    /// Target springs (`targets.rs`).
    pub targets: targets::Targets,
    /// Self-contacts of the current step, for the implicit solve (`selfcontact.rs`): set by the
    /// world before the body's step, empty otherwise.
    pub self_contacts: selfcontact::SelfContacts,
    /// Energy taken out by the plastic stage so far (J, `plastic.rs`).
    pub plastic_dissipation: f64,
}

/// What a step without an event changes of a body, besides its plastic state: positions (m)
/// and velocities (m/s), flat xyz, and the implicit integrator's memory of its last step. The
/// rollback's backup and the rewind points are copies of it (`world/rollback.rs`).
#[derive(Debug, Default)]
pub(crate) struct State {
    pub x: Vec<f64>,
    pub v: Vec<f64>,
    /// The implicit integrator's warm start (`implicit/mod.rs`): v⁺ − v of the last accepted
    /// implicit step (m/s, flat xyz; empty: none, the next step starts cold) and its dt (s).
    /// Carried from step to step, so it is state (snapshot version 4).
    pub warm: Vec<f64>,
    pub warm_dt: f64,
    /// Where the implicit integrator's kept coarse levels were assembled
    /// (`implicit/keep.rs`); empty: none. State for the same reason as the warm start
    /// (snapshot version 6).
    pub kept: implicit::Kept,
}

/// By hand for `clone_from`, which keeps the buffers (the derived one allocates anew): the
/// rollback copies every body's state into the same backup before each call.
impl Clone for State {
    fn clone(&self) -> Self {
        State { x: self.x.clone(), v: self.v.clone(), warm: self.warm.clone(), warm_dt: self.warm_dt, kept: self.kept.clone() }
    }

    fn clone_from(&mut self, o: &Self) {
        self.x.clone_from(&o.x);
        self.v.clone_from(&o.v);
        self.warm.clone_from(&o.warm);
        self.warm_dt = o.warm_dt;
        self.kept.clone_from(&o.kept);
    }
}

impl State {
    /// Its size in bytes, about (the f64 and u32 arrays).
    pub fn bytes(&self) -> usize {
        8 * (self.x.len() + self.v.len() + self.warm.len() + self.kept.xt.len()) + 4 * self.kept.held.len()
    }
}

/// Scratch arrays, allocated once (the Runge–Kutta ones on first use), never inside a step.
/// Nothing in them carries over from one step to the next (the accumulator is zero between
/// steps), so a clone starts from fresh buffers and a restored body rebuilds them.
#[derive(Debug, Default)]
pub(crate) struct Work {
    /// Forces of the rare stages: wind, user face pressures, targets (N, flat xyz, see
    /// `forces.rs`), zero between steps.
    pub f: Vec<f64>,
    /// Intermediate state and stage accelerations of the explicit Runge–Kutta methods.
    pub xs: Vec<f64>,
    pub vs: Vec<f64>,
    pub a: [Vec<f64>; 4],
    /// The implicit integrator's system and vectors, built on its first step.
    pub implicit: Option<Box<implicit::Implicit>>,
    /// The explicit stages' partition into chunks and their buffers, built on the first
    /// explicit step.
    pub par: Option<Box<parforces::ParForces>>,
    /// Iterations of the last step (reported in the statistics; not state).
    pub iterations: SolverIterations,
}

impl Work {
    pub fn new(n3: usize) -> Self {
        Work { f: vec![0.0; n3], ..Default::default() }
    }
}

impl Clone for Work {
    fn clone(&self) -> Self {
        Work { iterations: self.iterations, ..Work::new(self.f.len()) }
    }
}

/// Inverse masses (1/kg, 0 for pinned vertices), spring ends, positions and velocities.
pub(crate) struct RigidView<'a> {
    pub inv_mass: &'a [f64],
    pub ei: &'a [u32],
    pub ej: &'a [u32],
    pub x: &'a mut [f64],
    pub v: &'a mut [f64],
}

/// The last frozen shape, for [`SoftBody::reset`].
#[derive(Debug, Clone)]
pub(crate) struct Frozen {
    pub x: Vec<f64>,
    pub rest: Vec<f64>,
    pub bending_rest: Vec<f64>,
    pub gas: GasReference,
    pub prestress: Vec<f64>,
}

/// A soft body. See the module documentation.
#[derive(Debug, Clone)]
pub struct SoftBody {
    /// Material; change it freely between steps (each step validates it).
    pub material: Material,
    pub(crate) model: Model,
    pub(crate) state: State,
    pub(crate) work: Work,
    pub(crate) frozen: Frozen,
}

impl SoftBody {
    /// A body on `mesh` at rest (rest lengths = edge lengths), of total mass `mass` (kg) split
    /// equally over the vertices. Fails if the material is invalid or if there is gas and the
    /// mesh is not closed.
    pub fn new(mesh: &TriMesh, total_mass: f64, material: Material) -> Result<Self, BodyError> {
        material.validate()?;
        material::check_positive("mass", total_mass)?;
        let n = mesh.vertex_count();
        if n == 0 || mesh.triangles.is_empty() {
            return Err(MeshError::Empty("the mesh has no faces".into()).into());
        }
        if mesh.positions.iter().any(|p| !p.is_finite()) {
            return Err(MeshError::Invalid("the mesh has non-finite coordinates".into()).into());
        }
        if mesh.triangles.iter().flatten().any(|&i| i as usize >= n) {
            return Err(MeshError::Invalid("a face refers to a vertex that does not exist".into()).into());
        }
        let counts = topology::count_edges(&mesh.triangles);
        let closed = counts.boundary == 0 && counts.non_manifold == 0;
        if material.nrt() > 0.0 && !closed {
            return Err(MeshError::NotClosed { boundary_edges: counts.boundary, non_manifold_edges: counts.non_manifold }.into());
        }
        let x = mesh.positions.clone();
        let springs = Springs::new(&topology::edges(&mesh.triangles), &x);
        let bending = Springs::new(&topology::bending_pairs(&mesh.triangles), &x);
        let faces = Faces::new(mesh.triangles.clone(), n);
        let hinges = hinges::Hinges::new(&mesh.triangles);
        let m = total_mass / n as f64;
        let mut body = SoftBody {
            model: Model {
                faces,
                springs,
                bending,
                hinges,
                closed,
                mass: vec![m; n],
                inv_mass: vec![1.0 / m; n],
                user_force: vec![0.0; 3 * n],
                prestress: vec![0.0; 3 * n],
                external: vec![0.0; 3 * n],
                external_active: false,
                face_pressure: vec![0.0; mesh.triangles.len()],
                face_pressure_active: false,
                gas: GasReference { ambient_pressure: 0.0, reference_volume: 1.0 },
                targets: Default::default(),
                self_contacts: Default::default(),
                plastic_dissipation: 0.0,
            },
            state: State { v: vec![0.0; 3 * n], x, warm: Vec::new(), warm_dt: 0.0, kept: implicit::Kept::default() },
            work: Work::new(3 * n),
            frozen: Frozen { x: Vec::new(), rest: Vec::new(), bending_rest: Vec::new(), gas: GasReference { ambient_pressure: 0.0, reference_volume: 1.0 }, prestress: vec![0.0; 3 * n] },
            material,
        };
        body.model.gas.reference_volume = GasReference::volume_for(body.volume());
        body.frozen = Frozen { x: body.state.x.clone(), rest: body.model.springs.rest.clone(), bending_rest: body.model.bending.rest.clone(), gas: body.model.gas, prestress: body.model.prestress.clone() };
        body.hinges_to_frozen();
        Ok(body)
    }

    /// The hinges' rest angles and weights from the frozen shape (after every change of it).
    pub(crate) fn hinges_to_frozen(&mut self) {
        self.model.hinges.rest_to(&self.frozen.x);
    }

    /// The body's stage of a world step: forces and integration over `dt` seconds with the
    /// world's settings (gravity, wind, integrator); no contact of any kind. `step` is the
    /// world's step number and `time` (s) the time at its start, for the error; `threads` run
    /// the passes. The state is left as it failed on error (the world rolls back); the implicit
    /// integrator leaves it untouched.
    pub(crate) fn integrate(&mut self, world: &WorldSettings, dt: f64, step: u64, time: f64, threads: &crate::par::Threads) -> Result<(), SimError> {
        self.material.validate()?;
        if self.material.nrt() > 0.0 && !self.model.closed {
            return Err(SimError::BadParameter {
                name: "gas",
                message: "gas pressure needs a closed surface; this mesh is open or non-manifold".into(),
            });
        }
        let tol = world.tolerance;
        integrate::step(&self.material, world, &self.model, &mut self.state, &mut self.work, dt, threads).map_err(|e| e.at(step, time, tol))
    }

    /// What the world's ground and obstacle stages read and write.
    pub(crate) fn rigid_view(&mut self) -> RigidView<'_> {
        RigidView { inv_mass: &self.model.inv_mass, ei: &self.model.springs.i, ej: &self.model.springs.j, x: &mut self.state.x, v: &mut self.state.v }
    }

    // ----- read access -------------------------------------------------------------------

    pub fn vertex_count(&self) -> usize {
        self.state.x.len() / 3
    }
    pub fn spring_count(&self) -> usize {
        self.model.springs.len()
    }
    pub fn face_count(&self) -> usize {
        self.model.faces.len()
    }
    pub fn triangles(&self) -> &[[u32; 3]] {
        self.model.faces.triangles()
    }
    /// Spring end vertices (i < j).
    pub fn spring_ends(&self) -> (&[u32], &[u32]) {
        (&self.model.springs.i, &self.model.springs.j)
    }
    /// Positions (m), flat xyz.
    pub fn positions(&self) -> &[f64] {
        &self.state.x
    }
    /// Velocities (m/s), flat xyz.
    pub fn velocities(&self) -> &[f64] {
        &self.state.v
    }
    /// Vertex masses (kg).
    pub fn masses(&self) -> &[f64] {
        &self.model.mass
    }
    pub fn is_pinned(&self, i: usize) -> bool {
        self.model.inv_mass[i] == 0.0
    }
    /// Bending spring ends and rest lengths (m).
    pub fn bending_ends(&self) -> (&[u32], &[u32]) {
        (&self.model.bending.i, &self.model.bending.j)
    }
    pub fn bending_rest_lengths(&self) -> &[f64] {
        &self.model.bending.rest
    }
    /// The hinges' rest angles θ̄ (rad), one per interior edge (`hinges.rs`): the frozen shape's,
    /// unless the plastic stage moved them (`plastic.rs`, "Bending").
    pub fn hinge_rest_angles(&self) -> &[f64] {
        &self.model.hinges.rest
    }
    /// Rest lengths (m), one per spring.
    pub fn rest_lengths(&self) -> &[f64] {
        &self.model.springs.rest
    }
    pub fn is_closed(&self) -> bool {
        self.model.closed
    }
    /// Pressure of the surroundings P_ref (Pa), set by [`SoftBody::freeze`].
    pub fn gas_reference(&self) -> GasReference {
        self.model.gas
    }
    /// Every position and velocity is finite.
    pub fn is_finite(&self) -> bool {
        self.state.x.iter().chain(&self.state.v).all(|a| a.is_finite())
    }
    /// The volume the gas uses (m³), in the selected mode.
    pub fn volume(&self) -> f64 {
        gas::measure(self.model.faces.triangles(), self.material.volume_mode, self.model.faces.volume6(&self.state.x), &self.state.x)
    }
    /// The exact enclosed volume (m³).
    pub fn exact_volume(&self) -> f64 {
        self.model.faces.volume6(&self.state.x) / 6.0
    }
    /// Gas pressure P = nRT / V (Pa).
    pub fn pressure(&self) -> f64 {
        gas::pressure(self.material.nrt(), self.volume())
    }
    /// Σ k (l − L) l over all springs, bending ones included (J): 3 nRT at inflated equilibrium
    /// without other forces.
    pub fn spring_virial(&self) -> f64 {
        self.model.springs.virial(self.material.stiffness, &self.state.x) + self.model.bending.virial(self.material.bending_stiffness, &self.state.x)
    }
    /// Newton and linear iterations of the body's last step (zeros for explicit integrators).
    pub fn solver_iterations(&self) -> SolverIterations {
        self.work.iterations
    }
    /// How the implicit line searches of this body ended since its solver was built (zeros for
    /// explicit integrators): `body::implicit::LineStats`.
    pub fn line_stats(&self) -> LineStats {
        self.work.implicit.as_ref().map_or_else(LineStats::default, |i| i.lines)
    }
    /// Largest vertex speed (m/s).
    pub fn max_speed(&self) -> f64 {
        self.state.v.chunks_exact(3).map(|v| v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).fold(0.0, f64::max).sqrt()
    }
}

/// Creating a body can fail on the mesh or on a parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum BodyError {
    Mesh(MeshError),
    Sim(SimError),
}
impl From<MeshError> for BodyError {
    fn from(e: MeshError) -> Self {
        BodyError::Mesh(e)
    }
}
impl From<SimError> for BodyError {
    fn from(e: SimError) -> Self {
        BodyError::Sim(e)
    }
}
impl std::fmt::Display for BodyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BodyError::Mesh(e) => e.fmt(f),
            BodyError::Sim(e) => e.fmt(f),
        }
    }
}
impl std::error::Error for BodyError {}
