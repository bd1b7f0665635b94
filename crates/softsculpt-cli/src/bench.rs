//! `softsculpt bench`: the standard workload (a stable contract: keep the keys).
//!
//! The workload is `softsculpt::workload` (icospheres, see there). Only the stepping loop is
//! timed; the final exact volume shows that the physics matches other engines'.

use crate::args;
use clap::Args;
use serde_json::json;
use softsculpt::workload;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Icosphere subdivision levels (comma-separated).
    #[arg(long, default_value = "4,5,6,7", value_delimiter = ',', value_parser = parse_level)]
    pub levels: Vec<u32>,
    /// Steps per timed run.
    #[arg(long, default_value = "1000", value_parser = args::count_positive)]
    pub steps: u64,
    /// Timed runs per level; the fastest is reported.
    #[arg(long, default_value = "3", value_parser = args::count_positive)]
    pub reps: u64,
    /// One JSON object per level instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Integrator instead of the workload's symplectic Euler.
    #[arg(long, value_parser = crate::simulate::parse_integrator)]
    pub integrator: Option<softsculpt::Integrator>,
    /// Time step (s) instead of the workload's 1e-4.
    #[arg(long, allow_hyphen_values = true, value_parser = args::positive, value_name = "S")]
    pub dt: Option<f64>,
    /// Spring stiffness (N/m) instead of the workload's 1000.
    #[arg(long, allow_hyphen_values = true, value_parser = args::non_negative, value_name = "K")]
    pub stiffness: Option<f64>,
    /// Implicit integrator's tolerance (default: the parameter table's).
    #[arg(long, allow_hyphen_values = true, value_parser = args::positive, value_name = "TOL")]
    pub tolerance: Option<f64>,
    /// Threads (0 or absent: every core).
    #[arg(long, allow_hyphen_values = true, value_parser = args::threads, value_name = "N")]
    pub threads: Option<u64>,    /// Off a terminal, print a progress line every 5 s on stderr (on a terminal a bar shows anyway).
    #[arg(long)]
    pub progress: bool,
}

fn parse_level(s: &str) -> Result<u32, String> {
    let l: u32 = s.trim().parse().map_err(|_| format!("'{s}' is not a subdivision level"))?;
    if l > 9 {
        return Err(format!("level {l} is too large (at most 9: 2,621,442 vertices)"));
    }
    Ok(l)
}

pub fn run(a: BenchArgs) -> Result<(), String> {
    if !a.json {
        println!("{:>9} {:>9} {:>12} {:>18} {:>16} {:>8} {:>8}", "vertices", "springs", "ms/step", "ns/spring-step", "final volume", "newton", "linear");
    }
    // Progress between repetitions, never inside the timed loop.
    let mut bar = crate::progress::Progress::counted("bench", (a.levels.len() as u64).saturating_mul(a.reps).saturating_mul(a.steps), "steps", true, a.progress);
    let mut done = 0u64;
    for &level in &a.levels {
        let mut best = f64::INFINITY;
        let mut volume = 0.0;
        let (mut nv, mut ns) = (0, 0);
        let (mut newton, mut linear) = (0u64, 0u64);
        for _ in 0..a.reps {
            let mut world = workload::world(level);
            if let Some(i) = a.integrator {
                world.settings.integrator = i;
            }
            if let Some(dt) = a.dt {
                world.settings.dt = dt;
            }
            if let Some(k) = a.stiffness {
                world.bodies[0].material.stiffness = k;
            }
            if let Some(t) = a.tolerance {
                world.settings.tolerance = t;
            }
            world.set_threads(a.threads.unwrap_or(0) as usize).map_err(|e| format!("--threads: {e}"))?;
            (newton, linear) = (0, 0);
            nv = world.bodies[0].vertex_count();
            ns = world.bodies[0].spring_count();
            let t0 = Instant::now();
            for _ in 0..a.steps {
                world.step().map_err(|e| format!("bench level {level}: {e}"))?;
                // Only the iteration counts: `World::stats` sums every energy, an O(n) pass as
                // costly as half an explicit step, which the timing must not include.
                let it = world.bodies[0].solver_iterations();
                newton += it.newton as u64;
                linear += it.linear as u64;
            }
            best = best.min(t0.elapsed().as_secs_f64());
            done = done.saturating_add(a.steps);
            bar.set(done);
            volume = world.bodies[0].exact_volume();
        }
        let ms = best * 1e3 / a.steps as f64;
        let ns_spring = best * 1e9 / (a.steps as f64 * ns as f64);
        if a.json {
            println!(
                "{}",
                json!({"vertices": nv, "springs": ns, "ms_per_step": ms, "ns_per_spring_step": ns_spring, "volume": volume, "level": level, "steps": a.steps,
                       "newton_per_step": newton as f64 / a.steps as f64, "linear_per_step": linear as f64 / a.steps as f64})
            );
        } else {
            let (nps, lps) = (newton as f64 / a.steps as f64, linear as f64 / a.steps as f64);
            bar.suspend(|| println!("{nv:>9} {ns:>9} {ms:>12.4} {ns_spring:>18.3} {volume:>16.9} {nps:>8.2} {lps:>8.1}"));
        }
    }
    bar.finish();
    Ok(())
}
