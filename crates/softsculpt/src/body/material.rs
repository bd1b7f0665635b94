//! A body's material: what the body itself is made of, with units. Everything the world imposes
//! (gravity, wind, ground, obstacles, integrator, time step, contacts) is in
//! [`crate::settings::WorldSettings`] instead. All of it can change between steps.

pub use crate::error::{check_non_negative, check_positive};
use crate::error::SimError;
use crate::params as table;
use crate::params::field::{check_fields, choice_field, flag_field, number_field, Field};

/// Ideal gas constant R (J/(mol·K)) (the table's, which the page's generated params.ts shares).
pub const GAS_CONSTANT: f64 = table::GAS_CONSTANT;

/// The amount of gas n (mol) whose product n R T is `nrt` (J) at `temperature` (K): the one
/// place nRT becomes n (the table's `gas.nrt`, a scene's `nrt`, an event's, `set_nrt`).
pub fn moles(nrt: f64, temperature: f64) -> f64 {
    nrt / (GAS_CONSTANT * temperature)
}

/// Default temperature (K) used when a total nRT is given.
pub const DEFAULT_TEMPERATURE: f64 = table::TEMPERATURE.number();

/// Which volume the gas law uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VolumeMode {
    /// Exact enclosed volume V = Σ_faces xa · (xb × xc) / 6. The pressure force is then exactly
    /// P ∂V/∂x, so the gas is a conservative force. The default.
    Exact,
    /// Axis-aligned bounding box volume (the original paper's approximation).
    Box,
    /// Bounding sphere 4/3 π r³, r the largest distance from the vertex centroid (the paper's
    /// other approximation).
    Sphere,
    /// Bounding ellipsoid along the principal axes of the vertex cloud, scaled to enclose every
    /// vertex: 4/3 π s³ √det C with C the vertices' covariance and s² the largest
    /// (x − c)ᵀ C⁻¹ (x − c) (the paper's third bounding volume; `gas.rs`).
    Ellipsoid,
}

impl VolumeMode {
    pub const NAMES: &'static [&'static str] = table::VOLUME_CHOICES;
    pub fn name(self) -> &'static str {
        match self {
            VolumeMode::Exact => "exact",
            VolumeMode::Box => "box",
            VolumeMode::Sphere => "sphere",
            VolumeMode::Ellipsoid => "ellipsoid",
        }
    }
    pub fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "exact" => VolumeMode::Exact,
            "box" => VolumeMode::Box,
            "sphere" => VolumeMode::Sphere,
            "ellipsoid" => VolumeMode::Ellipsoid,
            _ => return None,
        })
    }
}

/// The material of a body. Names in error messages match the CLI flags.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Spring stiffness k (N/m), the same for every edge.
    pub stiffness: f64,
    /// Damping along each spring cs (N·s/m): force cs ((vj − vi) · d) d on i.
    pub spring_damping: f64,
    /// Stiffness of the bending springs (N/m), which join the two vertices opposite each edge
    /// and so resist folding across it; 0 (the default) leaves the surface free to fold, as in
    /// the original model. They use the same damping cs.
    pub bending_stiffness: f64,
    /// Flexural rigidity D (J = N·m) of the hinges (`hinges.rs`): the bending energy
    /// Σ_edges ½ D (|ē|² / Ā) (θ − θ̄)², θ the dihedral angle at an edge, θ̄ its value in the
    /// frozen shape, |ē| and Ā the edge's length and its two faces' area there. A plate rolled
    /// into a cylinder of radius R stores ½ D A / R², a thin plate's, at any mesh resolution
    /// (unlike the bending springs'). 0 (the default): none.
    pub rigidity: f64,
    /// Viscous damping rate c (1/s): force −c mi vi, velocities decay as e^(−c t).
    pub damping: f64,
    /// Amount of gas n (mol).
    pub gas_amount: f64,
    /// Gas temperature T (K).
    pub temperature: f64,
    /// Which volume the gas law uses.
    pub volume_mode: VolumeMode,
    /// Keep the body's vertices out of its own faces (the world's contact stage does it).
    pub self_collision: bool,
    /// Plasticity (`plastic.rs`): yield strain (dimensionless). Where a spring's strain
    /// |l / L − 1| exceeds it, its rest length flows toward the length at which the strain is
    /// the yield strain. 0 with a flow rate: every strain flows.
    pub yield_strain: f64,
    /// Plasticity: flow rate (1/s) at which the excess strain relaxes (e^(−rate t)); 0 (the
    /// default) = elastic, no plasticity.
    pub flow_rate: f64,
}

impl Default for Material {
    /// The defaults of the parameter table (`crate::params`).
    fn default() -> Self {
        Material {
            stiffness: table::STIFFNESS.number(),
            spring_damping: table::SPRING_DAMPING.number(),
            bending_stiffness: table::BENDING.number(),
            rigidity: table::RIGIDITY.number(),
            damping: table::DAMPING.number(),
            gas_amount: table::GAS_AMOUNT.number(),
            temperature: table::TEMPERATURE.number(),
            volume_mode: VolumeMode::Exact,
            self_collision: table::SELF_COLLISION.flag(),
            yield_strain: table::YIELD.number(),
            flow_rate: table::FLOW.number(),
        }
    }
}

impl Material {
    /// The retardation time τ = c_s / k (s) the hinges' damping uses (`hinges.rs`): the same
    /// relaxation time as the edges'; 0 without edge stiffness.
    pub fn retardation_time(&self) -> f64 {
        if self.stiffness > 0.0 {
            self.spring_damping / self.stiffness
        } else {
            0.0
        }
    }

    /// Whether the plastic stage runs (a flow rate above 0).
    pub fn is_plastic(&self) -> bool {
        self.flow_rate > 0.0
    }

    /// n R T (J): the product the gas law uses.
    pub fn nrt(&self) -> f64 {
        self.gas_amount * GAS_CONSTANT * self.temperature
    }

    /// Set the gas by its product nRT (J), keeping the temperature.
    pub fn set_nrt(&mut self, nrt: f64) {
        self.gas_amount = moles(nrt, self.temperature);
    }

    /// The body parameters that are fields of a material, each with its table entry: get, set
    /// and validation by id read this list (`world/params.rs`). A new material parameter is its
    /// table entry, its field and its line here. (Not here: `mass`, the body's vertex masses;
    /// `gas.nrt`, made of two fields; `gas.ambient`, the body's gas reference; and
    /// `gas.amount`/`gas.temperature` are set through the body, which re-derives its gas.)
    pub const FIELDS: &'static [Field<Material>] = &[
        number_field!(Material, table::STIFFNESS, stiffness),
        number_field!(Material, table::SPRING_DAMPING, spring_damping),
        number_field!(Material, table::BENDING, bending_stiffness),
        number_field!(Material, table::RIGIDITY, rigidity),
        number_field!(Material, table::DAMPING, damping),
        number_field!(Material, table::GAS_AMOUNT, gas_amount),
        number_field!(Material, table::TEMPERATURE, temperature),
        choice_field!(Material, table::VOLUME, volume_mode: VolumeMode, "volume mode"),
        flag_field!(Material, table::SELF_COLLISION, self_collision),
        number_field!(Material, table::YIELD, yield_strain),
        number_field!(Material, table::FLOW, flow_rate),
    ];

    /// Reject non-finite or out-of-range values with a message naming the parameter (its table
    /// id) and its unit: every field against its table range ([`Material::FIELDS`]).
    pub fn validate(&self) -> Result<(), SimError> {
        check_fields(Material::FIELDS, self)
    }
}
