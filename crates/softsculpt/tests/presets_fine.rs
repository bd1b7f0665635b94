//! Issue #37, item 1 at the finer resolution the issue asks for: each material takes the
//! modeler's default press and grab as its name says on the mushroom, the sphere and the
//! octopus each subdivided twice (5,762, 10,242 and 4× the octopus's vertices), with the bounds
//! of `tests/presets.rs` (`common::material_takes_the_tools`).
//!
//! Too slow for `make test` on a shared two-core machine (the octopus ×2 press alone took
//! 560 s), so they are ignored there and run by `make test-fine`
//! (`cargo test --release -p softsculpt --test presets_fine -- --ignored --nocapture`).
//!
//! Measured (the change of depth at the brush, m; press / grab): the mushroom ×2 — balloon,
//! jelly, stiff rubber pressed 0.150 / 0.149 / 0.130 and back within 0.1 mm, grabbed 0.068 /
//! 0.083 / 0.072 and back within 1.5 mm; clay (yield strain 1 %, before the preset's 0.5 %)
//! kept 85 % of the press and 88 % of the grab with no creep from 5 s to 10 s. The sphere ×2 —
//! the three pressed 0.163 / 0.158 / 0.147 and back within 0.1 mm; clay kept 87 % of the press
//! (the grab slides the sphere, 6 mm of depth: only its creep is bounded). The octopus ×2 was
//! not finished in the time measured.

mod common;

#[test]
#[ignore = "slow: make test-fine"]
fn each_material_takes_a_press_and_a_grab_as_named_on_the_mushroom_subdivided_twice() {
    common::material_takes_the_tools("mushroom", 2);
}

#[test]
#[ignore = "slow: make test-fine"]
fn each_material_takes_a_press_and_a_grab_as_named_on_the_sphere_subdivided_twice() {
    common::material_takes_the_tools("sphere", 2);
}

#[test]
#[ignore = "slow: make test-fine"]
fn each_material_takes_a_press_and_a_grab_as_named_on_the_octopus_subdivided_twice() {
    common::material_takes_the_tools("octopus", 2);
}
