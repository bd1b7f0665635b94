//! Bad scene files get one clear error naming the line and the key, never a panic.

use softsculpt::scene::{SceneError, SceneRun};

fn error(text: &str) -> SceneError {
    let mut resolve = |p: &str| -> Result<Vec<u8>, String> { Err(format!("no such file '{p}'")) };
    match SceneRun::load(text, &mut resolve) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

const BODY: &str = "[[body]]\nmodel = \"sphere\"\n";

#[test]
fn an_unknown_key_is_named_with_its_line() {
    let e = error(&format!("[world]\ndt = 0.001\ngravty = 9.81\n{BODY}"));
    eprintln!("{e}");
    assert_eq!(e.line, Some(3));
    assert!(e.to_string().contains("gravty"), "{e}");
    let e = error(&format!("{BODY}stifness = 10\n"));
    eprintln!("{e}");
    assert_eq!(e.line, Some(3));
    assert!(e.to_string().contains("stifness") && e.to_string().contains("body"), "{e}");
}

#[test]
fn a_wrong_type_names_the_key_and_line() {
    let e = error(&format!("{BODY}mass = \"heavy\"\n"));
    eprintln!("{e}");
    assert_eq!(e.line, Some(3));
    assert!(e.to_string().contains("body[0].mass"), "{e}");
    let e = error("[world]\nwind = [1, 2]\n");
    eprintln!("{e}");
    assert_eq!(e.line, Some(2));
    assert!(e.to_string().contains("wind"), "{e}");
}

#[test]
fn a_syntax_error_gives_its_line() {
    let e = error("[world]\ndt = = 1\n");
    eprintln!("{e}");
    assert_eq!(e.line, Some(2));
}

#[test]
fn a_missing_mesh_file_is_named() {
    let e = error("\n[[body]]\nmesh = \"nowhere.obj\"\n");
    eprintln!("{e}");
    // At the line that names it (the table's header is line 2).
    assert_eq!(e.line, Some(3));
    assert!(e.to_string().contains("body[0].mesh") && e.to_string().contains("nowhere.obj"), "{e}");
}

#[test]
fn events_out_of_order_and_negative_times_are_refused() {
    let e = error(&format!("{BODY}[[event]]\ntime = 2\naction = \"freeze\"\n[[event]]\ntime = 1\naction = \"freeze\"\n"));
    eprintln!("{e}");
    // The out-of-order time's own line (its event's header is line 6).
    assert_eq!(e.line, Some(7));
    assert!(e.to_string().contains("event[1].time") && e.to_string().contains("order"), "{e}");
    let e = error(&format!("{BODY}[[event]]\ntime = -1\naction = \"freeze\"\n"));
    eprintln!("{e}");
    assert_eq!(e.line, Some(4));
    assert!(e.to_string().contains("event[0].time"), "{e}");
}

#[test]
fn an_action_with_missing_or_stray_keys_is_refused() {
    let e = error(&format!("{BODY}[[event]]\ntime = 0\naction = \"force\"\nregion = {{ all = true }}\n"));
    eprintln!("{e}");
    assert!(e.to_string().contains("needs `force`"), "{e}");
    let e = error(&format!("{BODY}[[event]]\ntime = 0\naction = \"freeze\"\nforce = [1, 0, 0]\n"));
    assert!(e.to_string().contains("does not take `force`"), "{e}");
    let e = error(&format!("{BODY}[[event]]\ntime = 0\naction = \"explode\"\n"));
    assert!(e.to_string().contains("unknown action 'explode'"), "{e}");
    let e = error(&format!("{BODY}[[event]]\ntime = 0\naction = \"freeze\"\nbody = \"ghost\"\n"));
    assert!(e.to_string().contains("no body is named 'ghost'"), "{e}");
}

/// Serde reads the actions (`scene::actions`): an unknown one is named at its own line and key,
/// with the valid ones; a stray key inside a region is the region's, not the action's.
#[test]
fn an_unknown_action_names_its_line_key_and_the_valid_ones() {
    let e = error(&format!("{BODY}[[event]]\ntime = 0\naction = \"explode\"\n"));
    eprintln!("{e}");
    assert_eq!((e.line, e.key.as_deref()), (Some(5), Some("event[0].action")));
    assert!(e.message.contains("one of: freeze, reset, set_gas, set_wind, force, pressure, pin, unpin, inflate, set_mass"), "{e}");
    let e = error(&format!("{BODY}[[event]]\ntime = 0\naction = \"force\"\nregion = {{ al = true }}\nforce = [1, 0, 0]\n"));
    eprintln!("{e}");
    assert!(e.message.contains("unknown field `al`") && e.message.contains("`center`"), "{e}");
}

#[test]
fn bad_values_regions_and_obstacles_are_refused() {
    for (text, want) in [
        (format!("[world]\ndt = 0\n{BODY}"), "world.dt"),
        (format!("[world]\nintegrator = \"leapfrog\"\n{BODY}"), "unknown integrator"),
        ("[[body]]\nmodel = \"teapot\"\n".to_string(), "unknown built-in model 'teapot'"),
        ("[[body]]\nmodel = \"sphere\"\nmesh = \"a.obj\"\n".to_string(), "exactly one of"),
        ("[[body]]\n".to_string(), "needs a surface"),
        (format!("{BODY}stiffness = -5\n"), "body[0].stiffness"),
        (format!("{BODY}bending = -5\n"), "body[0].bending"),
        (format!("{BODY}rigidity = -0.5\n"), "body[0].rigidity"),
        (format!("{BODY}rigidity = nan\n"), "body[0].rigidity"),
        (format!("{BODY}rigidity = inf\n"), "body[0].rigidity"),
        (format!("{BODY}rigidity = \"stiff\"\n"), "rigidity"),
        (format!("{BODY}pins = [{{ center = [9, 9, 9], radius = 0.1 }}]\n"), "selects no vertex"),
        (format!("{BODY}pins = [{{ center = [0, 0, 0] }}]\n"), "needs both"),
        (format!("{BODY}on_ground = true\n"), "needs a ground"),
        (format!("{BODY}[[obstacle]]\nshape = \"cone\"\n"), "unknown shape 'cone'"),
        (format!("{BODY}[[obstacle]]\nshape = \"sphere\"\ncenter = [0, 0, 0]\n"), "needs `radius`"),
        (format!("{BODY}[[obstacle]]\nshape = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nhalf_extents = [1, 1, 1]\n"), "does not take `half_extents`"),
        ("[world]\ndt = 0.001\n".to_string(), "no [[body]]"),
        (format!("{BODY}gas = {{ amount = 1, nrt = 3 }}\n"), "not both"),
    ] {
        let e = error(&text);
        assert!(e.to_string().contains(want), "{text}\n→ {e}\n(wanted '{want}')");
    }
}

#[test]
fn a_tolerance_that_is_not_a_positive_number_is_refused_in_a_scene() {
    // TOML has nan and inf literals; each bad value gets the key and its line.
    for bad in ["0", "-1", "nan", "inf"] {
        let e = error(&format!("[world]\nintegrator = \"implicit\"\ntolerance = {bad}\n{BODY}"));
        assert!(e.to_string().contains("tolerance"), "{bad}: {e}");
    }
}

#[test]
fn an_implicit_scene_with_a_tolerance_loads_and_runs() {
    let text = format!("[world]\nintegrator = \"implicit\"\ntolerance = 1e-5\ndt = 0.0166\nduration = 0.1\n{BODY}");
    let mut resolve = |p: &str| -> Result<Vec<u8>, String> { Err(format!("no such file '{p}'")) };
    let mut run = SceneRun::load(&text, &mut resolve).unwrap();
    assert_eq!(run.world.settings.integrator, softsculpt::Integrator::Implicit);
    assert_eq!(run.world.settings.tolerance, 1e-5);
    run.run(|_| {}).unwrap();
    assert!(run.world.stats(0).solver_iterations.newton > 0);
}
