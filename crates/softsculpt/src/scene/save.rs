//! From bodies back to a scene file: what the modeler writes when it saves a scene.
//!
//! Each body is written as it is now, as inline OBJ text: that shape becomes its rest shape
//! when the scene is opened, and the gas's surroundings pressure is set to the current pressure
//! (`gas.ambient`), so the body opens in equilibrium — like a freeze. Masses, pins, material and
//! gas are kept; velocities, inflation and kept loads are not (a project file keeps those).
//! World settings come from the first body; obstacles, events and the contact settings from the
//! scene the bodies came from, if any.

use super::spec::{BodySpec, GasSpec, GroundSpec, MassSpec, RegionSpec, SceneSpec, WorldSpec};
use crate::body::SoftBody;
use toml::Spanned;

/// A scene of `bodies` (name, body), stepping by `dt` (s) for `duration` (s), keeping the
/// obstacles, events and contact settings of `template`.
pub fn scene_of(bodies: &[(&str, &SoftBody)], dt: f64, duration: f64, template: Option<&SceneSpec>) -> SceneSpec {
    let first = &bodies[0].1.params;
    let t = template.map(|t| &t.world);
    let world = WorldSpec {
        dt,
        duration,
        integrator: first.integrator.name().to_string(),
        gravity: first.gravity,
        wind: first.wind,
        wind_drag: first.wind_drag,
        ground: first.ground.map(|g| GroundSpec { height: g.height, friction: g.friction, restitution: g.restitution }),
        contact_thickness: t.map_or(WorldSpec::default().contact_thickness, |w| w.contact_thickness),
        contact_friction: t.map_or(WorldSpec::default().contact_friction, |w| w.contact_friction),
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
    let p = &b.params;
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
        damping: p.damping,
        gas,
        self_collision: p.self_collision,
        pins: if pinned.is_empty() { Vec::new() } else { vec![RegionSpec { vertices: Some(pinned), ..Default::default() }] },
        masses,
        ..BodySpec::default()
    }
}
