//! Similarity (params/similarity.rs): a model s times as large, with the modeler's preset scaled
//! by s, rests in the same shape scaled by s — so the modeler can keep a file's own units.

use softsculpt::body::{Material, SoftBody};
use softsculpt::mesh::{builtin, TriMesh};
use softsculpt::world::{World, WorldSettings};

/// A ball of radius `s` m (642 vertices), the modeler's preset scaled by `size`, settled for
/// `seconds` on the ground under gravity and 30 J × size⁴ of gas; its positions / s.
fn settled(s: f64, size: f64, seconds: f64) -> (Vec<f64>, Vec<&'static str>) {
    let ball = builtin::icosphere(3, 1.0);
    // Resting on the ground (lowest point at y = 0), every length × s.
    let lo = ball.positions.chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let mesh = TriMesh { positions: ball.positions.chunks_exact(3).flat_map(|p| [p[0] * s, (p[1] - lo) * s, p[2] * s]).collect(), triangles: ball.triangles.clone() };
    let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    let mut w = World::new(vec![body], WorldSettings::default());
    let skipped = w.apply_preset_scaled(0, "modeler", size).unwrap();
    let steps = (seconds / w.settings.dt).round() as u64;
    w.step_n(steps).unwrap();
    (w.bodies[0].positions().iter().map(|x| x / s).collect(), skipped)
}

#[test]
fn a_ball_scaled_by_s_rests_in_the_same_shape_scaled_by_s() {
    // The reference: radius 1 m at size 1 (the preset as tuned). At 1 cm the preset scaled gives
    // dt × s^½ too: the same dimensionless problem step by step, so the same shape at the same
    // scaled time up to rounding and the solver's tolerance (1e-3 relative residual per step, on
    // a sag of ~0.16 of the radius): compared at 4 s (0.4 s at 1 cm), when the ball has sagged
    // onto its footprint. Measured there 1.6e-5 of the radius; bound 1e-4 (the unscaled preset
    // is off by more than 1, checked below). Why not later: the ball at rest is unstable — an
    // asymmetry grows from rounding into a roll (measured on the 1 cm ball, its centre's x:
    // 1.3e-8 at 4 s, 9e-7 at 5, 6e-5 at 6, then a roll of 0.048 of the radius by 7 s, at ~70×
    // per second; the 1 m ball's grows from 1e-17 at ~3× per second), so a comparison at 8 s
    // (as this test once made) met a roll whenever a change to the solver moved the
    // rounding — at 1e-4 and 1e-7 tolerance before, with the ground's releases at Newton
    // iterations 1–4 after (off by 0.12). Why: the 642-vertex ball starts balanced on one vertex
    // (its single lowest point), an unstable orientation of its facets — the 1 m ball's centre x
    // doubles every ~2 s over 40 s (1.7e-17 → 2.8e-9) and it rolls to a stable one; checked
    // once, throwaway. Starting it on a face would make the rest stable.
    // At 20 m dt stays 1/60 s, finer than similar: the path is less damped and friction holds
    // another footprint; compared at rest (40 s, against the reference at 8 s): measured 1.7e-5
    // of the radius (0.048 with the ground's releases at 2, 4, 8, … only); bound 0.06 (the preset unscaled on the 1 cm ball is off by more than
    // 0.05·20, so the bound still tells scaled from unscaled).
    let (reference, none) = settled(1.0, 1.0, 4.0);
    let (rest, _) = settled(1.0, 1.0, 8.0);
    assert!(none.is_empty());
    let top = |x: &[f64]| x.chunks_exact(3).map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
    let sag = 2.0 - top(&reference);
    assert!(sag > 0.02, "the reference ball sags under its weight (by {sag} m)");
    for (s, seconds, bound, reference) in [(0.01, 4.0, 1e-4, &reference), (20.0, 40.0, 0.06, &rest)] {
        let (x, _) = settled(s, s, seconds);
        let worst = x.iter().zip(reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        println!("size {s}: off by {worst:e} of the radius");
        assert!(worst < bound, "size {s}: rest shape off by {worst} of the radius");
    }
    // Unscaled parameters on the 1 cm ball: nothing like the reference (the check has teeth).
    let (x, _) = settled(0.01, 1.0, 4.0);
    let worst = x.iter().zip(&reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst > 1.0, "unscaled, the 1 cm ball rests differently (off by {worst})");
}

#[test]
fn an_open_sheet_takes_the_preset_without_gas() {
    // A cloth: one hemisphere's worth of faces is still open; an open body gets no gas.
    let ball = builtin::icosphere(2, 1.0);
    let tris: Vec<[u32; 3]> = ball.triangles.iter().copied().filter(|t| t.iter().any(|&v| ball.positions[3 * v as usize + 1] > 0.0)).collect();
    let sheet = TriMesh { positions: ball.positions.clone(), triangles: tris };
    let prepared = softsculpt::mesh::prepare(softsculpt::mesh::ObjData { positions: sheet.positions.clone(), arities: vec![3; sheet.triangles.len()], indices: sheet.triangles.iter().flatten().copied().collect() }).unwrap();
    assert!(prepared.report.edges.boundary > 0);
    let body = SoftBody::new(&prepared.mesh, 1.0, Material::default()).unwrap();
    let mut w = World::new(vec![body], WorldSettings::default());
    let skipped = w.apply_preset_scaled(0, "modeler", 1.0).unwrap();
    assert_eq!(skipped, vec!["gas.nrt"]);
    assert_eq!(w.bodies[0].material.nrt(), 0.0);
    // Everything else of the preset applied: implicit stepping, gravity and ground; it steps.
    assert_eq!(w.settings.dt, 1.0 / 60.0);
    w.step_n(60).unwrap();
}

