//! `softsculpt simulate INPUT --out OUT.obj [options]` (a stable contract: keep the flags).

use crate::args::{self, help};
use crate::progress::Progress;
use crate::{input, output};
use softsculpt::params::{self as table, Value};
use clap::Args;
use softsculpt::body::{Material, SoftBody, VolumeMode};
use softsculpt::world::{Ground, Integrator, World, WorldSettings};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// Mesh to simulate: an .obj, .ply, .stl, .gltf or .glb file, or builtin:NAME (sphere,
    /// mushroom, octopus, kangaroo).
    pub input: String,
    /// Where to write the final shape, atomically; the extension chooses the format: .obj,
    /// .ply, .stl or .glb.
    #[arg(long, value_name = "OUT.obj")]
    pub out: PathBuf,
    /// The input's up axis: z rotates a Z-up file to Y-up (x, y, z → x, z, −y) for the run
    /// (gravity along −y) and the output back to Z-up; y keeps it. Units are never changed.
    #[arg(long, value_parser = input::parse_up, value_name = "y|z")]
    pub up: Option<softsculpt::mesh::UpAxis>,
    /// The output's up axis (default: the input's, --up): z writes it Z-up (Blender's PLY and
    /// STL importers), y Y-up.
    #[arg(long = "out-up", value_parser = input::parse_up, value_name = "y|z")]
    pub out_up: Option<softsculpt::mesh::UpAxis>,
    /// Write OBJ and PLY as triangles (each polygon a fan) instead of the input's polygons:
    /// some readers (trimesh) refuse a PLY that mixes quads and triangles. STL and GLB are
    /// always triangles.
    #[arg(long)]
    pub triangulate: bool,
    /// Off a terminal, print a progress line every 5 s on stderr (on a terminal a bar shows anyway).
    #[arg(long)]
    pub progress: bool,
    /// Number of steps.
    #[arg(long, allow_hyphen_values = true, default_value = "1000", value_parser = args::count, value_name = "N")]
    pub steps: u64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::DT.number(), value_parser = args::positive, value_name = "S", help = help(&table::DT))]
    pub dt: f64,
    #[arg(long, default_value = table::INTEGRATOR.choice(), value_parser = parse_integrator, help = help(&table::INTEGRATOR))]
    pub integrator: Integrator,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::TOLERANCE.number(), value_parser = args::positive, value_name = "TOL", help = help(&table::TOLERANCE))]
    pub tolerance: f64,
    #[arg(long = "newton-iterations", allow_hyphen_values = true, default_value_t = table::NEWTON_ITERATIONS.number() as u64, value_parser = args::newton_cap, value_name = "N", help = help(&table::NEWTON_ITERATIONS))]
    pub newton_iterations: u64,
    /// Threads for the force stages and the implicit solver (0 or absent: every core); the
    /// implicit solver gives the same bits on any count, the explicit integrators on 2 or more
    /// (one thread sums the springs in another order: equal to rounding, 1e-12 relative).
    #[arg(long, allow_hyphen_values = true, value_parser = args::threads, value_name = "N")]
    pub threads: Option<u64>,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::STIFFNESS.number(), value_parser = args::non_negative, value_name = "K", help = help(&table::STIFFNESS))]
    pub stiffness: f64,
    #[arg(long = "spring-damping", allow_hyphen_values = true, default_value_t = table::SPRING_DAMPING.number(), value_parser = args::non_negative, value_name = "CS", help = help(&table::SPRING_DAMPING))]
    pub spring_damping: f64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::BENDING.number(), value_parser = args::non_negative, value_name = "KB", help = help(&table::BENDING))]
    pub bending: f64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::RIGIDITY.number(), value_parser = args::non_negative, value_name = "D", help = help(&table::RIGIDITY))]
    pub rigidity: f64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::DAMPING.number(), value_parser = args::non_negative, value_name = "C", help = help(&table::DAMPING))]
    pub damping: f64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::MASS.number(), value_parser = args::positive, value_name = "M", help = help(&table::MASS))]
    pub mass: f64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::GAS_NRT.number(), value_parser = args::non_negative, value_name = "NRT", help = help(&table::GAS_NRT))]
    pub gas: f64,
    #[arg(long, default_value = table::VOLUME.choice(), value_parser = parse_volume, help = help(&table::VOLUME))]
    pub volume: VolumeMode,
    #[arg(long = "yield", allow_hyphen_values = true, default_value_t = table::YIELD.number(), value_parser = args::non_negative, value_name = "STRAIN", help = help(&table::YIELD))]
    pub yield_strain: f64,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::FLOW.number(), value_parser = args::non_negative, value_name = "RATE", help = help(&table::FLOW))]
    pub flow: f64,
    /// A named preset's values first (material: balloon, jelly, clay, cloth, stiff_rubber; or
    /// modeler, which sets the world too); the flags given explicitly override it.
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// The flags given on the command line (filled from the matches: they override a preset).
    #[arg(skip)]
    pub explicit: Vec<String>,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::GRAVITY.number(), value_parser = args::finite, value_name = "G", help = help(&table::GRAVITY))]
    pub gravity: f64,
    #[arg(long, allow_hyphen_values = true, value_parser = args::finite, value_name = "H", help = format!("{}; no ground unless given", help(&table::GROUND_HEIGHT)))]
    pub ground: Option<f64>,
    #[arg(long, allow_hyphen_values = true, default_value_t = table::GROUND_FRICTION.number(), value_parser = args::non_negative, value_name = "MU", help = help(&table::GROUND_FRICTION))]
    pub friction: f64,
    #[arg(long, allow_hyphen_values = true, value_parser = args::vec3, value_name = "X,Y,Z", help = help(&table::WIND))]
    pub wind: Option<[f64; 3]>,
    #[arg(long = "wind-drag", allow_hyphen_values = true, default_value_t = table::WIND_DRAG.number(), value_parser = args::non_negative, value_name = "CW", help = help(&table::WIND_DRAG))]
    pub wind_drag: f64,
    /// Initial velocity of every vertex (m/s).
    #[arg(long, allow_hyphen_values = true, value_parser = args::vec3, value_name = "X,Y,Z")]
    pub velocity: Option<[f64; 3]>,
    /// Stop early once the largest vertex speed (m/s) stays below TOL for 100 consecutive steps.
    #[arg(long = "until-rest", allow_hyphen_values = true, value_parser = args::positive, value_name = "TOL")]
    pub until_rest: Option<f64>,
    /// Write statistics as JSON lines to this file.
    #[arg(long, value_name = "FILE.jsonl")]
    pub stats: Option<PathBuf>,
    /// Statistics every N steps (default max(1, steps/100)); step 0 and the last step always.
    #[arg(long = "stats-every", allow_hyphen_values = true, value_parser = args::count_positive, value_name = "N")]
    pub stats_every: Option<u64>,
    /// Run an explicit integrator at a --dt above the model's stability bound (refused
    /// otherwise, with the dt that would be stable).
    #[arg(long)]
    pub force: bool,
}

/// The flags a preset may set, as (clap id, flag, parameter id, value) from the arguments.
fn preset_flags(a: &SimulateArgs) -> Vec<(&'static str, &'static str, &'static str, Value)> {
    let mut flags = vec![
        ("stiffness", "--stiffness", "stiffness", Value::Number(a.stiffness)),
        ("spring_damping", "--spring-damping", "spring_damping", Value::Number(a.spring_damping)),
        ("bending", "--bending", "bending", Value::Number(a.bending)),
        ("rigidity", "--rigidity", "rigidity", Value::Number(a.rigidity)),
        ("damping", "--damping", "damping", Value::Number(a.damping)),
        ("gas", "--gas", "gas.nrt", Value::Number(a.gas)),
        ("volume", "--volume", "gas.volume", Value::Choice(a.volume.name())),
        ("yield_strain", "--yield", "yield", Value::Number(a.yield_strain)),
        ("flow", "--flow", "flow", Value::Number(a.flow)),
        ("gravity", "--gravity", "gravity", Value::Number(a.gravity)),
        ("wind_drag", "--wind-drag", "wind_drag", Value::Number(a.wind_drag)),
        ("integrator", "--integrator", "integrator", Value::Choice(a.integrator.name())),
        ("dt", "--dt", "dt", Value::Number(a.dt)),
        ("tolerance", "--tolerance", "tolerance", Value::Number(a.tolerance)),
        ("newton_iterations", "--newton-iterations", "newton_iterations", Value::Number(a.newton_iterations as f64)),
    ];
    if let Some(w) = a.wind {
        flags.push(("wind", "--wind", "wind", Value::Vector(w)));
    }
    if let Some(h) = a.ground {
        flags.push(("ground", "--ground", "ground", Value::Flag(true)));
        flags.push(("ground", "--ground", "ground.height", Value::Number(h)));
    }
    flags.push(("friction", "--friction", "ground.friction", Value::Number(a.friction)));
    flags
}

/// Set preset `name` on the world, then again every flag given explicitly (they override it).
fn apply_preset(world: &mut World, name: &str, a: &SimulateArgs) -> Result<(), String> {
    world.apply_preset(0, name).map_err(|e| format!("--preset: {e}"))?;
    for (id, flag, param, value) in preset_flags(a) {
        if a.explicit.iter().any(|e| e == id) && !(param == "ground.friction" && world.settings.ground.is_none()) {
            world.set_param(0, param, value).map_err(|e| format!("{flag}: {e}"))?;
        }
    }
    Ok(())
}

/// A preset carries what it needs to run: the presets are tuned for the implicit integrator
/// (the modeler's), and a stiff one (stiff_rubber, clay) is above what the default explicit
/// step can take (on the sphere: stable below ~2.6e-4 s against the default 1e-3 s). So when
/// neither `--integrator` nor `--dt` was given and the explicit step is above the model's
/// stability bound (`World::dt_limit`), the implicit integrator steps it, with a note saying so.
fn implicit_for_preset(world: &mut World, name: &str, a: &SimulateArgs) {
    if a.explicit.iter().any(|e| e == "integrator" || e == "dt") {
        return;
    }
    let was = world.settings.integrator;
    if let Some(limit) = world.implicit_if_unstable() {
        eprintln!(
            "note: --preset {name}: {} is stable only below ~{limit:.1e} s for this model, not at --dt {} s; the implicit integrator steps it (give --integrator or --dt to choose)",
            was.name(),
            world.settings.dt
        );
    }
}

/// The ids of the arguments given on the command line (not defaulted).
pub fn explicit(m: &clap::ArgMatches) -> Vec<String> {
    m.ids().filter(|id| m.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine)).map(|id| id.to_string()).collect()
}

pub fn parse_integrator(s: &str) -> Result<Integrator, String> {
    Integrator::from_name(s).ok_or_else(|| format!("unknown integrator '{s}' (use one of {})", Integrator::NAMES.join(", ")))
}

fn parse_volume(s: &str) -> Result<VolumeMode, String> {
    VolumeMode::from_name(s).ok_or_else(|| format!("unknown volume mode '{s}' (use one of {})", VolumeMode::NAMES.join(", ")))
}

/// Consecutive calm steps that count as "at rest" for --until-rest.
pub const REST_WINDOW: u64 = 100;

/// How far above the stability bound (`World::dt_limit`) a step is refused. The bound is
/// Gershgorin's over-estimate of the fastest mode: measured on the sphere, `--preset cloth`
/// (bound 6.5e-4 s) ran dropped at 1e-3 s and blew up at 1.3e-3 s; `stiff_rubber` and `clay`
/// (bound 2.6e-4 s) collapsed at 1e-3 s, at steps 12 and 300, and ran at 2.5e-4 s. So a step
/// up to twice the bound is run with a warning, beyond it refused.
const REFUSE_ABOVE: f64 = 2.0;

/// Before an explicit run: its step against the model's stability bound (`World::dt_limit`, the
/// bound behind the modeler's `World::stable_dt`): more than [`REFUSE_ABOVE`] times it is
/// refused with the advice that fixes it (a dt that is stable, or the implicit integrator)
/// unless `force`; above it, a warning. Before this check the run failed part-way with advice
/// that pointed the wrong way ("stiffer springs").
pub fn check_stable(world: &World, force: bool, dt_name: &str) -> Result<(), String> {
    let s = &world.settings;
    let Some(limit) = world.dt_limit(s.integrator) else { return Ok(()) };
    if s.dt <= limit {
        return Ok(());
    }
    let stable = world.stable_dt(s.integrator).unwrap_or(limit);
    let what = format!("{dt_name} {} s is above the largest step {} is stable at for this model, about {limit:.2e} s (its stiffest vertex's fastest mode)", s.dt, s.integrator.name());
    let fix = format!("give {dt_name} {stable} (with a margin) or less, or the implicit integrator (stable at any dt)");
    if s.dt > REFUSE_ABOVE * limit && !force {
        return Err(format!("{what}: {fix}; --force runs it anyway"));
    }
    eprintln!("warning: {what}; it may blow up: {fix}");
    Ok(())
}

pub fn run(a: SimulateArgs) -> Result<(), String> {
    let out_format = input::out_format(&a.out)?;
    input::out_up(a.out_up, a.up, out_format)?;
    let loaded = input::load(&a.input, a.up)?;
    input::warn(&a.input, &loaded);

    let mut material = Material {
        stiffness: a.stiffness,
        spring_damping: a.spring_damping,
        bending_stiffness: a.bending,
        rigidity: a.rigidity,
        damping: a.damping,
        volume_mode: a.volume,
        yield_strain: a.yield_strain,
        flow_rate: a.flow,
        ..Material::default()
    };
    material.set_nrt(a.gas);
    let settings = WorldSettings {
        gravity: a.gravity,
        wind: a.wind.unwrap_or(table::WIND.vector()),
        wind_drag: a.wind_drag,
        ground: a.ground.map(|h| Ground { friction: a.friction, ..Ground::at(h) }),
        integrator: a.integrator,
        dt: a.dt,
        tolerance: a.tolerance,
        newton_iterations: a.newton_iterations as u32,
        ..WorldSettings::default()
    };
    let mut body = SoftBody::new(&loaded.mesh, a.mass, material).map_err(|e| format!("{}: {e}", a.input))?;
    if let Some(v) = a.velocity {
        body.set_uniform_velocity(v).map_err(|e| format!("--velocity: {e}"))?;
    }
    // A lone body is a one-body world.
    let mut world = World::single(body, settings);
    world.set_threads(a.threads.unwrap_or(0) as usize).map_err(|e| format!("--threads: {e}"))?;
    if let Some(name) = &a.preset {
        apply_preset(&mut world, name, &a)?;
        implicit_for_preset(&mut world, name, &a);
    }
    check_stable(&world, a.force, "--dt")?;
    if let Some(h) = a.ground {
        let (lo, _) = loaded.mesh.bounds();
        if lo[1] < h {
            eprintln!("warning: the mesh starts below the ground (lowest y {} < {h}); those vertices are lifted onto it in the first step", lo[1]);
        }
    }

    let every = a.stats_every.unwrap_or((a.steps / 100).max(1));
    let mut stats = match &a.stats {
        Some(p) => Some(output::Staged::create(p).map_err(|e| format!("--stats {e}"))?),
        None => None,
    };
    let mut emit = |world: &World, record: Option<serde_json::Value>| -> Result<(), String> {
        if let Some(s) = stats.as_mut() {
            let mut row = world.stats(0).to_json();
            // The first row (step 0) also records the run (record.rs): the stats keys as every
            // row has them, and "run".
            if let (Some(r), Some(map)) = (record, row.as_object_mut()) {
                map.insert("run".into(), r);
            }
            let mut line = row.to_string();
            line.push('\n');
            s.write(line.as_bytes())?;
        }
        Ok(())
    };
    let run_record = a.stats.is_some().then(|| crate::record::run(&world, &["body".to_string()], vec![crate::record::input(&a.input)]));
    emit(&world, run_record)?;

    // A bar for runs long enough to want one (1,000 steps and more).
    let mut bar = Progress::counted("simulate", a.steps, "steps", a.steps >= 1000, a.progress);
    let mut calm = 0u64;
    let mut stopped_at_rest = false;
    for step in 1..=a.steps {
        world.step().map_err(|e| format!("{}: {e}", a.input))?;
        if let Some(tol) = a.until_rest {
            calm = if world.bodies[0].max_speed() < tol { calm + 1 } else { 0 };
            if calm >= REST_WINDOW {
                stopped_at_rest = true;
            }
        }
        if step % every == 0 || step == a.steps || stopped_at_rest {
            emit(&world, None)?;
        }
        if step % 64 == 0 {
            bar.set(step);
        }
        if stopped_at_rest {
            break;
        }
    }
    bar.finish();
    let body = &world.bodies[0];
    if !body.is_finite() {
        return Err(format!(
            "{}: the simulation blew up (non-finite state at step {}); try a smaller --dt, more damping, or another --integrator",
            a.input,
            world.steps()
        ));
    }
    if let Some(s) = stats {
        s.commit().map_err(|e| format!("--stats {e}"))?;
    }
    let out_up = input::out_up(a.out_up, a.up, out_format)?;
    let header = format!(
        "SoftSculpt simulate {} — {} steps of {} s ({}), {}-up",
        a.input,
        world.steps(),
        a.dt,
        a.integrator.name(),
        if out_up == softsculpt::mesh::UpAxis::Z { "Z" } else { "Y" }
    );
    let options = softsculpt::mesh::format::WriteOptions { up: out_up, triangulate: a.triangulate };
    let bytes = loaded.write_with(out_format, body.positions(), &header, options).map_err(|e| format!("--out {}: {e}", a.out.display()))?;
    output::write_atomic(&a.out, &bytes).map_err(|e| format!("--out {e}"))?;
    let rest = if stopped_at_rest { " (at rest)" } else { "" };
    // The enclosed volume (what `info` of the output reports); the gas's own in another mode.
    let gas = if body.material.volume_mode == VolumeMode::Exact { String::new() } else { format!(", the gas's {} volume {:.6} m^3", body.material.volume_mode.name(), body.volume()) };
    // (An open surface encloses nothing: no volume said, as `info` says.)
    let volume = if body.is_closed() { format!(", volume {:.6} m^3 enclosed{gas}", body.exact_volume()) } else { ", an open surface (no volume)".to_string() };
    eprintln!("wrote {} after {} steps, t = {:.4} s{rest}{volume}", a.out.display(), world.steps(), world.time());
    Ok(())
}
