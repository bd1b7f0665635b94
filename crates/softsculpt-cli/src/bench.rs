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
        println!("{:>9} {:>9} {:>12} {:>18} {:>16}", "vertices", "springs", "ms/step", "ns/spring-step", "final volume");
    }
    for &level in &a.levels {
        let mut best = f64::INFINITY;
        let mut volume = 0.0;
        let (mut nv, mut ns) = (0, 0);
        for _ in 0..a.reps {
            let mut world = workload::world(level);
            nv = world.bodies[0].vertex_count();
            ns = world.bodies[0].spring_count();
            let t0 = Instant::now();
            for _ in 0..a.steps {
                world.step().map_err(|e| format!("bench level {level}: {e}"))?;
            }
            best = best.min(t0.elapsed().as_secs_f64());
            volume = world.bodies[0].exact_volume();
        }
        let ms = best * 1e3 / a.steps as f64;
        let ns_spring = best * 1e9 / (a.steps as f64 * ns as f64);
        if a.json {
            println!(
                "{}",
                json!({"vertices": nv, "springs": ns, "ms_per_step": ms, "ns_per_spring_step": ns_spring, "volume": volume, "level": level, "steps": a.steps})
            );
        } else {
            println!("{nv:>9} {ns:>9} {ms:>12.4} {ns_spring:>18.3} {volume:>16.9}");
        }
    }
    Ok(())
}
