//! From bodies back to a scene file: what the modeler writes when it saves a scene.
//!
//! Each body is written as it is now, as inline OBJ text: that shape becomes its rest shape
//! when the scene is opened, and the gas's surroundings pressure is set to the current pressure
//! (`gas.ambient`), so the body opens in equilibrium — like a freeze. Masses, pins, material and
//! gas are kept; velocities, inflation and kept loads are not (a snapshot keeps those).
//! World settings (contacts included) come from the world's settings; obstacles and events from
//! the scene the bodies came from, if any (as written in its file).

use super::spec::{BodySpec, GasSpec, GroundSpec, MassSpec, RegionSpec, SceneSpec, WorldSpec};
use crate::body::SoftBody;
use crate::world::WorldSettings;
use toml::Spanned;

/// A scene of `bodies` (name, body) in a world with `settings` (its dt included), running for
/// `duration` (s), keeping the obstacles and events of `template`.
pub fn scene_of(settings: &WorldSettings, bodies: &[(&str, &SoftBody)], duration: f64, template: Option<&SceneSpec>) -> SceneSpec {
    let w = settings;
    let world = WorldSpec {
        dt: w.dt,
        duration,
        integrator: w.integrator.name().to_string(),
        tolerance: w.tolerance,
        newton_iterations: w.newton_iterations,
        gravity: w.gravity,
        wind: w.wind,
        wind_drag: w.wind_drag,
        ground: w.ground.map(|g| GroundSpec { height: g.height, friction: g.friction, restitution: g.restitution }),
        contact_thickness: w.contact.thickness,
        contact_friction: w.contact.friction,
    };
    let bodies = bodies.iter().map(|(name, b)| Spanned::new(0..0, body_spec(name, b))).collect();
    SceneSpec {
        world,
        bodies,
        obstacles: template.map(|t| t.obstacles.clone()).unwrap_or_default(),
        events: template.map(|t| t.events.clone()).unwrap_or_default(),
    }
}

fn body_spec(name: &str, b: &SoftBody) -> BodySpec {
    let p = &b.material;
    let m = b.masses();
    let total: f64 = m.iter().sum();
    // Vertices grouped by mass (exact values, in order of first appearance); one group = uniform.
    let mut groups: Vec<(f64, Vec<u32>)> = Vec::new();
    for (i, &mi) in m.iter().enumerate() {
        match groups.iter_mut().find(|g| g.0 == mi) {
            Some(g) => g.1.push(i as u32),
            None => groups.push((mi, vec![i as u32])),
        }
    }
    let masses = if groups.len() > 1 {
        groups.into_iter().map(|(mass, v)| MassSpec { region: RegionSpec { vertices: Some(v), ..Default::default() }, mass }).collect()
    } else {
        Vec::new()
    };
    let pinned: Vec<u32> = (0..b.vertex_count()).filter(|&i| b.is_pinned(i)).map(|i| i as u32).collect();
    let gas = (p.gas_amount > 0.0).then(|| GasSpec {
        amount: Some(p.gas_amount),
        temperature: Some(p.temperature),
        nrt: None,
        volume: Some(p.volume_mode.name().to_string()),
        ambient: Some(b.pressure()),
    });
    BodySpec {
        name: Some(name.to_string()),
        obj: Some(String::from_utf8_lossy(&b.to_mesh().to_obj(&format!("{name}, saved by SoftSculpt"))).into_owned()),
        mass: total,
        stiffness: p.stiffness,
        spring_damping: p.spring_damping,
        bending: p.bending_stiffness,
        rigidity: p.rigidity,
        damping: p.damping,
        yield_strain: p.yield_strain,
        flow: p.flow_rate,
        gas,
        self_collision: p.self_collision,
        pins: if pinned.is_empty() { Vec::new() } else { vec![RegionSpec { vertices: Some(pinned), ..Default::default() }] },
        masses,
        ..BodySpec::default()
    }
}
