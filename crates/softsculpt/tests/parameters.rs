//! The parameter table: one place for every default, unit, range and help line, which the
//! materials, worlds, scene format and docs follow; get and set by id with checked ranges.

use softsculpt::body::Material;
use softsculpt::mesh::builtin::icosphere;
use softsculpt::params::{self, ParamId, Scope, Value, TABLE};
use softsculpt::scene::spec::{BodySpec, WorldSpec};
use softsculpt::world::{Ground, World, WorldSettings};
use softsculpt::SoftBody;
use std::path::PathBuf;

fn doc_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/parameters.md")
}

/// docs/parameters.md is the table's Markdown; `UPDATE_DOCS=1` rewrites it.
#[test]
fn the_parameter_page_is_generated_from_the_table() {
    let want = params::markdown();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(doc_path(), &want).unwrap();
    }
    let have = std::fs::read_to_string(doc_path()).unwrap_or_default();
    assert!(have == want, "docs/parameters.md is stale: run UPDATE_DOCS=1 cargo test -p softsculpt --test parameters");
    for p in TABLE {
        assert!(have.contains(&format!("`{}`", p.id)), "{} is documented", p.id);
    }
}

/// web/src/engine/params.ts is the table's TypeScript (ids as a type, rows, R); `UPDATE_DOCS=1`
/// rewrites it.
#[test]
fn the_pages_parameter_types_are_generated_from_the_table() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../web/src/engine/params.ts");
    let want = params::typescript::typescript();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, &want).unwrap();
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(have == want, "web/src/engine/params.ts is stale: run UPDATE_DOCS=1 cargo test -p softsculpt --test parameters");
    for p in TABLE {
        assert!(have.contains(&format!("| '{}'", p.id)) && have.contains(&format!("id: '{}'", p.id)), "{} is a ParamId", p.id);
    }
    assert!(have.contains(&format!("GAS_CONSTANT = {};", softsculpt::GAS_CONSTANT)));
}

/// The typed ids are the table's, one each, in its order, and read back from their strings.
#[test]
fn every_typed_id_is_one_entry_of_the_table() {
    assert_eq!(ParamId::ALL.len(), TABLE.len());
    for (id, p) in ParamId::ALL.iter().zip(TABLE) {
        assert_eq!(id.param(), p);
        assert_eq!(ParamId::find(p.id).unwrap(), *id);
        assert_eq!(id.to_string(), p.id);
    }
    assert_eq!(ParamId::find("stifness").unwrap_err().to_string(), "stifness: no such parameter");
}

#[test]
fn every_default_is_valid_and_ids_are_unique() {
    for (k, p) in TABLE.iter().enumerate() {
        assert!(p.check(&p.default).is_ok(), "{}: default {:?} outside its range", p.id, p.default);
        assert!(!p.help.is_empty(), "{} has help", p.id);
        assert!(TABLE[..k].iter().all(|q| q.id != p.id), "{} twice", p.id);
        assert!(p.id.chars().all(|c| c.is_ascii_lowercase() || c == '_' || c == '.'), "{} is snake_case", p.id);
    }
}

/// Material::default(), WorldSettings::default() and the scene format's defaults are the
/// table's: read back by id, every body and world parameter is its default.
#[test]
fn materials_worlds_and_scene_files_default_to_the_table() {
    let settings = WorldSettings { ground: Some(Ground::at(params::GROUND_HEIGHT.number())), ..WorldSettings::default() }; // to read its fields
    let world = World::single(SoftBody::new(&icosphere(1, 1.0), params::MASS.number(), Material::default()).unwrap(), settings);
    for p in TABLE {
        match (p.scope, p.id) {
            // The mass comes back as the sum of the vertex masses: 1/42 summed 42 times, within
            // 42 roundings of 1 (42 · 1.1e-16 < 1e-14).
            (Scope::Body, "mass") => assert!(matches!(world.param(0, "mass").unwrap(), Value::Number(m) if (m - 1.0).abs() < 1e-14)),
            (Scope::Body | Scope::World, id) if id != "ground" => assert_eq!(world.param(0, p.id).unwrap(), p.default, "{}", p.id),
            _ => {}
        }
    }
    assert_eq!(WorldSettings::default().ground, None, "no ground by default");
    let (b, w) = (BodySpec::default(), WorldSpec::default());
    let scene = [
        (b.mass, &params::MASS),
        (b.stiffness, &params::STIFFNESS),
        (b.spring_damping, &params::SPRING_DAMPING),
        (b.bending, &params::BENDING),
        (b.rigidity, &params::RIGIDITY),
        (b.damping, &params::DAMPING),
        (w.dt, &params::DT),
        (w.duration, &params::DURATION),
        (w.gravity, &params::GRAVITY),
        (w.wind_drag, &params::WIND_DRAG),
        (w.contact_thickness, &params::CONTACT_THICKNESS),
        (w.contact_friction, &params::CONTACT_FRICTION),
    ];
    for (value, p) in scene {
        assert_eq!(value, p.number(), "scene default of {}", p.id);
    }
    assert_eq!(w.integrator, params::INTEGRATOR.choice());
    assert_eq!(softsculpt::world::obstacles::DEFAULT_FRICTION, params::OBSTACLE_FRICTION.number());
}

fn world() -> World {
    let mut m = Material::default();
    m.set_nrt(10.0);
    World::single(SoftBody::new(&icosphere(1, 1.0), 1.0, m).unwrap(), WorldSettings::default())
}

#[test]
fn parameters_set_by_id_go_to_the_body_or_the_world() {
    let mut w = world();
    w.set_param(0, "stiffness", Value::Number(250.0)).unwrap();
    assert_eq!(w.bodies[0].material.stiffness, 250.0);
    w.set_param(0, "gravity", Value::Number(3.0)).unwrap();
    assert_eq!(w.settings.gravity, 3.0);
    w.set_param(0, "wind", Value::Vector([1.0, 0.0, -2.0])).unwrap();
    assert_eq!(w.settings.wind, [1.0, 0.0, -2.0]);
    w.set_param(0, "integrator", params::choice("integrator", "rk4").unwrap()).unwrap();
    assert_eq!(w.param(0, "integrator").unwrap(), Value::Choice("rk4"));
    w.set_param(0, "ground", Value::Flag(true)).unwrap();
    w.set_param(0, "ground.height", Value::Number(-1.5)).unwrap();
    assert_eq!(w.settings.ground.map(|g| g.height), Some(-1.5));
    // nRT = n R T: setting the product keeps T (300 K) and sets n (tolerance: one rounding of
    // the division and of the product, relative 1e-15).
    w.set_param(0, "gas.nrt", Value::Number(20.0)).unwrap();
    let Value::Number(nrt) = w.param(0, "gas.nrt").unwrap() else { panic!() };
    assert!((nrt - 20.0).abs() < 1e-13, "{nrt}");
    w.set_param(0, "mass", Value::Number(2.0)).unwrap();
    let Value::Number(m) = w.param(0, "mass").unwrap() else { panic!() };
    assert!((m - 2.0).abs() < 1e-13, "{m}");
}

#[test]
fn bad_values_are_refused_naming_the_parameter_and_its_unit() {
    let mut w = world();
    let msg = |w: &mut World, id: &str, v: Value| w.set_param(0, id, v).unwrap_err().to_string();
    assert_eq!(msg(&mut w, "stiffness", Value::Number(-1.0)), "stiffness: must be ≥ 0 N/m, got -1");
    assert_eq!(msg(&mut w, "dt", Value::Number(0.0)), "dt: must be > 0 s, got 0");
    assert_eq!(msg(&mut w, "gravity", Value::Number(f64::NAN)), "gravity: must be finite m/s², got NaN");
    assert_eq!(msg(&mut w, "ground.restitution", Value::Number(1.5)), "ground.restitution: must be between 0 and 1, got 1.5");
    assert_eq!(msg(&mut w, "integrator", Value::Choice("verlet")), "integrator: unknown choice 'verlet' (one of: euler, midpoint, rk4, symplectic, implicit)");
    // The implicit integrator's tolerance: a positive finite number (0, −1 and NaN refused).
    for bad in [0.0, -1.0, f64::NAN] {
        assert_eq!(msg(&mut w, "tolerance", Value::Number(bad)), format!("tolerance: must be > 0, got {bad}"));
    }
    assert_eq!(msg(&mut w, "newton_iterations", Value::Number(2.5)), "newton_iterations: must be a whole number, got 2.5");
    assert_eq!(msg(&mut w, "newton_iterations", Value::Number(0.0)), "newton_iterations: must be between 1 and 1000, got 0");
    assert_eq!(msg(&mut w, "wind", Value::Number(1.0)), "wind: expected three numbers [x, y, z], got Number(1.0)");
    assert_eq!(msg(&mut w, "ground.height", Value::Number(1.0)), "ground.height: there is no ground (set `ground` to true first)");
    assert_eq!(msg(&mut w, "stifness", Value::Number(1.0)), "stifness: no such parameter");
    assert_eq!(msg(&mut w, "duration", Value::Number(1.0)), "duration: is set in a scene file, not on a world");
    // Nothing changed.
    assert_eq!(w.bodies[0].material.stiffness, Material::default().stiffness);
    assert_eq!(w.settings, WorldSettings::default());
}

/// The JSON the binding hands to the page: one object per parameter, in table order.
#[test]
fn the_table_as_json_lists_every_parameter() {
    let json: serde_json::Value = serde_json::from_str(&params::table_json()).unwrap();
    let rows = json.as_array().unwrap();
    assert_eq!(rows.len(), TABLE.len());
    for (row, p) in rows.iter().zip(TABLE) {
        assert_eq!(row["id"], p.id);
        assert_eq!(row["unit"], p.unit);
        assert_eq!(row["help"], p.help);
    }
    let stiffness = &rows[1];
    assert_eq!((stiffness["scope"].as_str(), stiffness["default"].as_f64(), stiffness["min"].as_f64()), (Some("body"), Some(100.0), Some(0.0)));
    assert!(stiffness["max"].is_null());
    let integrator = rows.iter().find(|r| r["id"] == "integrator").unwrap();
    assert_eq!(integrator["choices"].as_array().unwrap().len(), 5);
}

/// Every preset's values are parameters of the table, each within its range, and applying the
/// modeler's sets them on the world (implicit at 1/60 s, 30 J of gas: nRT read back to 1e-12
/// relative, the rounding of n = nRT / (R T) and back); an unknown preset is refused by name.
#[test]
fn presets_hold_valid_values_and_apply_them() {
    use softsculpt::params::presets::{preset, PRESETS};
    for p in PRESETS {
        for (id, v) in p.values {
            let param = params::find(id.id()).unwrap_or_else(|e| panic!("{}: {e}", p.name));
            assert!(param.check(v).is_ok(), "{}: {id} = {v:?} outside its range", p.name);
        }
    }
    let body = softsculpt::SoftBody::new(&softsculpt::mesh::builtin::icosphere(1, 0.5), 1.0, softsculpt::Material::default()).unwrap();
    let mut w = softsculpt::World::single(body, softsculpt::WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    assert_eq!(w.settings.integrator, softsculpt::Integrator::Implicit);
    assert_eq!(w.settings.dt, 1.0 / 60.0);
    assert!(w.settings.ground.is_some());
    assert!((w.bodies[0].material.nrt() - 30.0).abs() < 1e-12 * 30.0);
    assert_eq!(w.bodies[0].material.damping, 1.5);
    let e = w.apply_preset(0, "marble").unwrap_err().to_string();
    assert!(e.contains("unknown preset 'marble'") && e.contains("modeler") && e.contains("clay"), "{e}");
    assert!(preset("modeler").is_ok());
}
