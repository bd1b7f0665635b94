//! The scene file format: what a TOML scene may say, field by field, with units and defaults.
//! `docs/scenes.md` is the user's version of this file; keep the two in step.
//!
//! Unknown keys are errors (`deny_unknown_fields`; an event's keys are its action's,
//! `super::actions`), so a typo never silently falls back to a default. Bodies, obstacles and
//! events keep their source span, so checks done after parsing can name the line.

pub use super::actions::ActionSpec;
use crate::params as table;
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    #[serde(default)]
    pub world: WorldSpec,
    /// `[[body]]` tables.
    #[serde(default, rename = "body", skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<Spanned<BodySpec>>,
    /// `[[obstacle]]` tables.
    #[serde(default, rename = "obstacle", skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<Spanned<ObstacleSpec>>,
    /// `[[event]]` tables, in time order.
    #[serde(default, rename = "event", skip_serializing_if = "Vec::is_empty")]
    pub events: Vec<Spanned<EventSpec>>,
}

/// `[world]`: what every body shares.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldSpec {
    /// Time step (s).
    pub dt: f64,
    /// Length of the run (s).
    pub duration: f64,
    /// `euler`, `midpoint`, `rk4`, `symplectic` or `implicit`.
    pub integrator: String,
    /// Implicit integrator: relative residual at which a step's Newton iterations stop.
    pub tolerance: f64,
    /// Implicit integrator: most Newton iterations per step.
    pub newton_iterations: u32,
    /// Gravitational acceleration g (m/s²) along −y.
    pub gravity: f64,
    /// Wind velocity (m/s).
    pub wind: [f64; 3],
    /// Wind drag coefficient (N·s/m³).
    pub wind_drag: f64,
    /// The ground plane y = height; absent means no ground.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ground: Option<GroundSpec>,
    /// Distance kept between bodies in contact (m).
    pub contact_thickness: f64,
    /// Coulomb friction between bodies (dimensionless).
    pub contact_friction: f64,
}

impl Default for WorldSpec {
    fn default() -> Self {
        WorldSpec {
            dt: table::DT.number(),
            duration: table::DURATION.number(),
            integrator: table::INTEGRATOR.choice().into(),
            tolerance: table::TOLERANCE.number(),
            newton_iterations: table::NEWTON_ITERATIONS.number() as u32,
            gravity: table::GRAVITY.number(),
            wind: table::WIND.vector(),
            wind_drag: table::WIND_DRAG.number(),
            ground: None,
            contact_thickness: table::CONTACT_THICKNESS.number(),
            contact_friction: table::CONTACT_FRICTION.number(),
        }
    }
}

/// `[world.ground]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct GroundSpec {
    /// Height of the plane (m).
    pub height: f64,
    /// Coulomb friction (dimensionless).
    pub friction: f64,
    /// Restitution of the normal velocity, 0..1.
    pub restitution: f64,
}

impl Default for GroundSpec {
    fn default() -> Self {
        GroundSpec { height: table::GROUND_HEIGHT.number(), friction: table::GROUND_FRICTION.number(), restitution: table::GROUND_RESTITUTION.number() }
    }
}

/// `[[body]]`: one soft body. Exactly one of `model`, `mesh`, `obj` gives its surface.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct BodySpec {
    /// Name used by events (`body = "…"`) and for output files; default `body1`, `body2`, ….
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// A built-in model: `sphere`, `mushroom`, `octopus`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model: Option<String>,
    /// An OBJ file, relative to the scene file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// OBJ text inline (what the modeler writes for a shape it made).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub obj: Option<String>,
    /// Uniform scale applied first (dimensionless).
    pub scale: f64,
    /// Rotation applied second.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotate: Option<RotateSpec>,
    /// Translation applied last (m).
    pub translate: [f64; 3],
    /// Move the body so its lowest point touches the ground (needs `[world.ground]`).
    pub on_ground: bool,
    /// Total mass (kg), split equally over the vertices before `[[body.masses]]`.
    pub mass: f64,
    /// Spring stiffness k (N/m).
    pub stiffness: f64,
    /// Spring damping cs (N·s/m).
    pub spring_damping: f64,
    /// Bending spring stiffness (N/m).
    pub bending: f64,
    /// Flexural rigidity D of the hinges (J = N·m).
    pub rigidity: f64,
    /// Viscous damping c (1/s).
    pub damping: f64,
    /// Plasticity: yield strain (dimensionless; `crate::body::plastic`).
    #[serde(rename = "yield")]
    pub yield_strain: f64,
    /// Plasticity: flow rate (1/s); 0 = elastic.
    pub flow: f64,
    /// A material preset (`balloon`, `jelly`, `clay`, `cloth`, `stiff_rubber`): its values for
    /// every material key this body does not give itself.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub preset: Option<String>,
    /// Gas inside (absent: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gas: Option<GasSpec>,
    /// Initial velocity (m/s).
    pub velocity: [f64; 3],
    /// Collide the body with itself.
    pub self_collision: bool,
    /// Regions whose vertices are pinned (fixed in space).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub pins: Vec<RegionSpec>,
    /// Regions with their own vertex mass, applied in order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub masses: Vec<MassSpec>,
}

impl Default for BodySpec {
    fn default() -> Self {
        BodySpec {
            name: None,
            model: None,
            mesh: None,
            obj: None,
            scale: 1.0,
            rotate: None,
            translate: [0.0; 3],
            on_ground: false,
            mass: table::MASS.number(),
            stiffness: table::STIFFNESS.number(),
            spring_damping: table::SPRING_DAMPING.number(),
            bending: table::BENDING.number(),
            rigidity: table::RIGIDITY.number(),
            damping: table::DAMPING.number(),
            yield_strain: table::YIELD.number(),
            flow: table::FLOW.number(),
            preset: None,
            gas: None,
            velocity: [0.0; 3],
            self_collision: table::SELF_COLLISION.flag(),
            pins: Vec::new(),
            masses: Vec::new(),
        }
    }
}

/// A rotation by `degrees` about `axis`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RotateSpec {
    pub axis: [f64; 3],
    pub degrees: f64,
}

/// Gas: either `amount` (mol, with `temperature` K) or the product `nrt` (J).
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GasSpec {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub amount: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nrt: Option<f64>,
    /// `exact`, `box`, `sphere` or `ellipsoid`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub volume: Option<String>,
    /// Pressure of the surroundings P_ref (Pa, default 0): the gas pushes with P − P_ref. The
    /// modeler saves the current pressure here, so a saved shape opens in equilibrium.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ambient: Option<f64>,
}

/// A set of vertices, by exactly one of: a sphere (`center`, `radius`), a box (`min`, `max`),
/// a list of `vertices` (0-based, in the body's order), or `all = true`.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub center: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertices: Option<Vec<u32>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub all: Option<bool>,
}

/// `[[body.masses]]`: every vertex of `region` gets mass `mass` (kg).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MassSpec {
    pub region: RegionSpec,
    pub mass: f64,
}

/// `[[obstacle]]`: a rigid shape; `shape` picks which keys apply.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    /// `sphere`, `box`, `capsule` or `mesh`.
    pub shape: String,
    /// Sphere and box centre (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub center: Option<[f64; 3]>,
    /// Sphere and capsule radius (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Box half extents along its axes (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_extents: Option<[f64; 3]>,
    /// Box rotation (absent: axis-aligned).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotate: Option<RotateSpec>,
    /// Capsule segment ends (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b: Option<[f64; 3]>,
    /// Mesh obstacle: an OBJ file relative to the scene, or a built-in model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model: Option<String>,
    /// Mesh obstacle placement: uniform scale, then translation (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub translate: Option<[f64; 3]>,
    /// Coulomb friction (dimensionless), default 0.5.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
}

/// `[[event]]`: at `time` (s), do `action` to `body` (default: every body). The action and the
/// keys it takes are [`ActionSpec`] (`super::actions`).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
pub struct EventSpec {
    pub time: f64,
    #[serde(flatten, deserialize_with = "super::actions::read")]
    pub action: ActionSpec,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
}
