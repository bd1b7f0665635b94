//! The modeler's mushroom as the modeler opens it, for tests and examples (included by path).

use softsculpt::mesh::builtin::builtin;
use softsculpt::params::Value;
use softsculpt::world::{World, WorldSettings};
use softsculpt::{Material, SoftBody};

/// The 362-vertex mushroom standing on the ground at y = 0, the foot (vertices below 1 cm)
/// pinned as the modeler roots it, the `modeler` preset (implicit steps of 1/60 s, 30 J of gas),
/// self-collision on or off; `crushed`: gas amount 0.0002 mol (nRT = 0.5 J), so the cap
/// collapses into a dome that folds onto itself.
pub fn modeler_mushroom(self_collision: bool, crushed: bool) -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let lo = mesh.positions.iter().skip(1).step_by(3).fold(f64::INFINITY, |a, &y| a.min(y));
    for y in mesh.positions.iter_mut().skip(1).step_by(3) {
        *y -= lo;
    }
    let mut body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    for i in 0..body.vertex_count() {
        if body.positions()[3 * i + 1] < 0.01 {
            body.set_pinned(i, true).unwrap();
        }
    }
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.set_param(0, "self_collision", Value::Flag(self_collision)).unwrap();
    if crushed {
        w.set_param(0, "gas.amount", Value::Number(0.0002)).unwrap();
    }
    w
}
