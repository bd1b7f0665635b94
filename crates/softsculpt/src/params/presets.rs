//! Presets: named sets of parameter values, defined once here beside the table. Applying one
//! ([`World::apply_preset`](crate::world::World::apply_preset), `world/params.rs`) sets each
//! listed parameter (in order) through
//! [`World::set_param`](crate::world::World::set_param), so every value is checked against the
//! table's range like any other.
//!
//! - `modeler`: the world and material the modeler opens a model with — stiff enough bending to
//!   carry a mushroom's cap (bending springs k_b = k, and hinges of flexural rigidity
//!   D = 0.05 J, `body/hinges.rs`, which keep that bending stiffness when the mesh is
//!   subdivided: measured in the modeler on the mushroom subdivided once, a mirrored pull of its
//!   cap held 2 s took 5.4 % of its volume and folded an edge 9.6° further with the springs
//!   alone, 0.7 % and 0.3° with the hinges — as on the unsubdivided mushroom, 0.3 % and 1.1°),
//!   damped to settle within a second or two, 30 J of gas, on the ground,
//!   stepped implicitly at one 1/60 s step per frame with a residual tolerance of 1e-3 (measured in
//!   Chromium: the resting shape is the same to four digits as at 1e-6, at twice the speed; see
//!   BENCHMARKS.md). Every value is a material or world property, not one of the mesh's: the
//!   reasons each stays the same when the mesh is subdivided are in `web/src/engine/models.ts`.
//!
//! The material presets (`balloon`, `jelly`, `clay`, `cloth`, `stiff_rubber`) set only body
//! parameters — stiffness, spring damping, bending, damping, gas and plasticity — so they go on
//! any body in any world (a scene body's `preset`, `simulate --preset`). Each is chosen to behave
//! the same at any mesh resolution:
//! - the edge stiffness k (N/m) of an equilateral lattice is a membrane of modulus 2k/√3 (N/m)
//!   and the spring damping cs a membrane viscosity 2cs/√3 (N·s/m), neither depending on the
//!   edge length, so a subdivided body stretches the same under the same load;
//! - the damping c (1/s) acts per unit mass, the gas nRT (J) on the volume, plasticity on the
//!   strain (dimensionless) at a rate (1/s): none sees the edge length;
//! - bending springs are the one term that does (the flexural rigidity of k_b springs across
//!   edges of length h goes as k_b h², so it weakens 4× per subdivision): every material preset
//!   leaves them at 0, and gets its shape from the gas and the membrane instead — and, where it
//!   needs to resist folding, from hinges (the flexural rigidity D in J, `body/hinges.rs`, the
//!   same at any resolution).
//!
//! Values, each checked by `tests/presets.rs` on every built-in model and after two
//! subdivisions with the implicit integrator at 1/60 s:
//! - `balloon`: a soft skin (k 100 N/m) on 30 J of gas, lightly damped (c 0.5 1/s), with
//!   hinges of D = 0.02 J: bouncy. Why the hinges: without them a press's dent is a
//!   snapped-through equilibrium of the skin, as for stiff rubber below — measured on the
//!   modeler's rooted mushroom, a 15 cm dent (cosine, 35 cm radius) let go kept 12.6 cm after
//!   12 s (a new-user trial: "keeps the dent", like clay); with D = 0.02 J, 0.1 mm. At 0.05 J
//!   (the modeler's own) the subdivided octopus's first second did not converge (the tests below).
//! - `jelly`: a softer skin (k 60 N/m) held round by 20 J of gas, little damping (c 0.5 1/s,
//!   cs 0.05), with light hinges (D = 0.01 J): wobbles a while after a push and springs back,
//!   from a deep dent too. Why c 0.5: at 0.3 1/s the rooted mushroom's cap, let go after the
//!   default grab (8 cm), still swayed 1 cm 5 s later (`examples/clay.rs`); at 0.5, 4 mm — within
//!   the 5 mm every elastic preset must spring back to in 5 s (`tests/presets.rs`) — and it still
//!   sways for seconds (the motion's e-folding time 2 s). Without hinges it kept a press's dent as the hinge-less balloon did
//!   (14.1 cm of 15 on the rooted mushroom 5 s after release); with D = 0.01 J, 0.8 mm
//!   (`examples/dent.rs`; the cap still sways a few cm, as a jelly does). D = 0.02 J (the
//!   balloon's) springs back as well but made the subdivided octopus ~10× slower to step than
//!   the balloon (a frame of 175 s, split; `examples/preset_frames.rs`); at 0.01 J it costs
//!   what the balloon does (34 s against 29 s for its first 20 frames).
//! - `clay`: a firm skin (k 300 N/m) on 20 J of gas, heavily damped (c 4 1/s, cs 0.5), with
//!   hinges (D = 0.05 J) whose rest angles flow past the yield as the rest lengths do (a 3.9 cm
//!   plate yielding at a curvature of 0.26 1/m past its rest shape's, `body/plastic.rs`,
//!   "Bending"): a press, a pull or a fold keeps its shape and then stays (measured with
//!   `examples/clay.rs`, the modeler's default press and grab: kept 91 % and 96 % on the rooted
//!   mushroom, 93 % of the press on the sphere, 112 % of the press and 102 % of the pull on the
//!   octopus, unchanged from 5 s to 10 s after release; the mushroom's cap pulled 0.4 m down at
//!   its rim for 1 s, `tests/presets.rs`: 77 % kept). Why a yield strain of 0.5 %: at 1 % (κ_y
//!   0.51 1/m, a yield angle of ~6° at each hinge of the 362-vertex mushroom) the rim pulled down
//!   kept 62 %: what sprang back was the hinges' elastic range, a few degrees at each of the
//!   fold's hinges (with the hinges' yield alone × 0.3, 78 %; with the springs' alone × 0.3, 58 %);
//!   at 0.3 % it kept 82 % (95 % of the press). Without hinges the mushroom's dent snapped 23 %
//!   deeper after release and the octopus's pull crept back 4 % from 5 s to 10 s (measured at a
//!   yield strain of 1 %); the subdivided octopus's first second costs 3× the CPU time it did
//!   without hinges. Plastic:
//!   strain beyond 0.5 % flows into the rest lengths at 5 1/s (the excess halves every 0.14 s), so
//!   a hard press leaves a dent (measured on the modeler's sphere on the ground: a 10 N press for
//!   0.5 s, 52 cm deep, leaves 7.5 cm — measured before P_ref followed only the gas's share of
//!   the flow, `body/plastic.rs`) while the body still carries its own weight (a yield strain
//!   of 0.3 % keeps 10 cm of the same press but slumps on: 2.00 → 1.44 m tall after 5 s, against
//!   1.63 m); the gas reference follows, so it never creeps under its gas.
//! - `cloth`: no gas (open meshes), a stiff weave (k 400 N/m), damped (c 1 1/s, cs 0.2): drapes.
//! - `stiff_rubber`: a stiff skin (k 2000 N/m, cs 0.5) on 30 J of gas, damped (c 1 1/s), with
//!   hinges of D = 0.1 J: hardly dents, bounces back at once. Without the hinges a stiff skin
//!   has snapped-through equilibria (a dented ping-pong ball): measured in the modeler, the
//!   octopus grabbed at a tentacle kept a 178° fold and lost 2.6 % of its volume for good; with
//!   them, no fold and no loss.

use super::{ParamError, ParamId, Value};

/// A named set of parameter values.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    pub name: &'static str,
    pub help: &'static str,
    /// (parameter, value), applied in this order.
    pub values: &'static [(ParamId, Value)],
}

pub const MODELER: Preset = Preset {
    name: "modeler",
    help: "what the modeler opens a model with: bending as stiff as the edges, damped, 30 J of gas, on the ground, implicit at 1/60 s",
    values: &[
        (ParamId::Stiffness, Value::Number(100.0)),
        (ParamId::SpringDamping, Value::Number(0.1)),
        (ParamId::Bending, Value::Number(100.0)),
        (ParamId::Rigidity, Value::Number(0.05)),
        (ParamId::Damping, Value::Number(1.5)),
        (ParamId::Gravity, Value::Number(9.81)),
        (ParamId::Ground, Value::Flag(true)),
        (ParamId::GroundHeight, Value::Number(0.0)),
        (ParamId::GroundFriction, Value::Number(0.5)),
        (ParamId::GasTemperature, Value::Number(300.0)),
        (ParamId::GasNrt, Value::Number(30.0)),
        (ParamId::Integrator, Value::Choice("implicit")),
        (ParamId::Tolerance, Value::Number(1e-3)),
        (ParamId::Dt, Value::Number(1.0 / 60.0)),
    ],
};

/// The body parameters every material preset sets, in this order.
const fn material(k: f64, cs: f64, d: f64, c: f64, nrt: f64, yield_strain: f64, flow: f64) -> [(ParamId, Value); 8] {
    [
        (ParamId::Stiffness, Value::Number(k)),
        (ParamId::SpringDamping, Value::Number(cs)),
        (ParamId::Bending, Value::Number(0.0)),
        (ParamId::Rigidity, Value::Number(d)),
        (ParamId::Damping, Value::Number(c)),
        (ParamId::GasNrt, Value::Number(nrt)),
        (ParamId::Yield, Value::Number(yield_strain)),
        (ParamId::Flow, Value::Number(flow)),
    ]
}

const BALLOON_VALUES: [(ParamId, Value); 8] = material(100.0, 0.1, 0.02, 0.5, 30.0, 0.0, 0.0);
const JELLY_VALUES: [(ParamId, Value); 8] = material(60.0, 0.05, 0.01, 0.5, 20.0, 0.0, 0.0);
/// The clay preset's flexural rigidity D (J): hinges whose rest angles flow past the yield
/// (module documentation, `clay`).
pub const CLAY_RIGIDITY: f64 = 0.05;
const CLAY_VALUES: [(ParamId, Value); 8] = material(300.0, 0.5, CLAY_RIGIDITY, 4.0, 20.0, 0.005, 5.0);
const CLOTH_VALUES: [(ParamId, Value); 8] = material(400.0, 0.2, 0.0, 1.0, 0.0, 0.0, 0.0);
const RUBBER_VALUES: [(ParamId, Value); 8] = material(2000.0, 0.5, 0.1, 1.0, 30.0, 0.0, 0.0);

pub const BALLOON: Preset = Preset { name: "balloon", help: "material: a soft skin on 30 J of gas, lightly damped; bouncy", values: &BALLOON_VALUES };
pub const JELLY: Preset = Preset { name: "jelly", help: "material: a softer skin held round by 20 J of gas, little damping; wobbles and springs back", values: &JELLY_VALUES };
pub const CLAY: Preset = Preset {
    name: "clay",
    help: "material: a firm, damped skin on 20 J of gas; strain and bending beyond 0.5 % flow at 5 1/s, so a press, a pull or a fold keeps its shape",
    values: &CLAY_VALUES,
};
pub const CLOTH: Preset = Preset { name: "cloth", help: "material: no gas (open meshes), a stiff damped weave; drapes", values: &CLOTH_VALUES };
pub const STIFF_RUBBER: Preset = Preset { name: "stiff_rubber", help: "material: a stiff skin on 30 J of gas; hardly dents, bounces back at once", values: &RUBBER_VALUES };

/// Every preset.
pub const PRESETS: &[Preset] = &[MODELER, BALLOON, JELLY, CLAY, CLOTH, STIFF_RUBBER];

impl Preset {
    /// Whether it sets only body parameters (a material preset, for a scene body).
    pub fn is_material(&self) -> bool {
        self.values.iter().all(|(id, _)| id.param().scope == super::Scope::Body)
    }
}

/// The preset called `name`.
pub fn preset(name: &str) -> Result<&'static Preset, ParamError> {
    PRESETS.iter().find(|p| p.name == name).ok_or_else(|| ParamError {
        id: "preset".into(),
        message: format!("unknown preset '{name}' (one of: {})", PRESETS.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")),
    })
}
