//! `softsculpt`: the headless front end of the SoftSculpt engine.
//!
//! Subcommands: `simulate` (run a body and write the result), `run` (play a scene file), `info` (what a mesh is made of), `remesh`, `sketch` (an outline becomes a balloon),
//! `bench` (the standard workload), `sweep` (a parameter sweep on Dask, through the Python package). Every failure prints one line starting `error:` on stderr
//! and exits with status 1 (2 for a malformed command line); nothing panics on bad input. A
//! reader that closes the output pipe early ends the command quietly, by SIGPIPE (status 141 in
//! a shell), as other Unix tools.

mod args;
mod bench;
mod info;
mod input;
mod output;
mod progress;
mod record;
mod remesh;
mod run;
mod simulate;
mod sketch;
mod sweep;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "softsculpt", version, about = "Soft-body modeling engine: mass-spring-damper with ideal-gas pressure")]
#[command(allow_negative_numbers = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

// Parsed once per process: the size of its largest variant costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand)]
enum Command {
    /// Simulate a body and write its final shape (OBJ, PLY, STL or GLB).
    #[command(allow_negative_numbers = true)]
    Simulate(simulate::SimulateArgs),
    /// Play a scene file (bodies, obstacles, timed events) and write the results.
    Run(run::RunArgs),
    /// Print what a mesh is made of: counts, welds, defects, volume, bounds.
    Info(info::InfoArgs),
    /// Remesh to a target edge length (isotropic: regular triangles, the same shape).
    #[command(allow_negative_numbers = true)]
    Remesh(remesh::RemeshArgs),
    /// Sketch: a closed outline (lines of `x y`) becomes a balloon inflated to rest.
    #[command(allow_negative_numbers = true)]
    Sketch(sketch::SketchArgs),
    /// Run the standard benchmark workload (icospheres of increasing size).
    Bench(bench::BenchArgs),
    /// Run a scene over a grid of parameters on Dask (needs the Python package, docs/python.md).
    Sweep(sweep::SweepArgs),
}

fn main() -> ExitCode {
    // A reader that stops early (`softsculpt info mesh.obj | head -3`) closes the pipe: end
    // quietly, as other Unix tools do, rather than panic in `println!` (Rust starts programs
    // with SIGPIPE ignored, so a write to a closed pipe is an error every print unwraps).
    #[cfg(unix)]
    // SAFETY: restores the default action of one signal before any thread or I/O exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let matches = match Cli::command().try_get_matches() {
        Ok(m) => m,
        Err(e) => return clap_error(e),
    };
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(c) => c,
        Err(e) => return clap_error(e),
    };
    let result = match cli.command {
        Command::Simulate(mut a) => {
            a.explicit = matches.subcommand_matches("simulate").map(simulate::explicit).unwrap_or_default();
            simulate::run(a)
        }
        Command::Run(a) => run::run(a),
        Command::Info(a) => info::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Remesh(a) => remesh::run(a),
        Command::Sketch(a) => sketch::run(a),
        Command::Sweep(a) => sweep::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            // One line, whatever a library's message holds.
            let message = message.lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join("; ");
            eprintln!("error: {message}");
            ExitCode::from(1)
        }
    }
}

/// Help and version go to stdout as usual; a usage error is reduced to its one `error:` line.
fn clap_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                return ExitCode::from(2);
            }
            ExitCode::SUCCESS
        }
        _ => {
            // clap's first paragraph, on one line: a missing argument is named on the indented
            // lines under "the following required arguments were not provided:".
            let text = e.render().to_string();
            let first: Vec<&str> = text.lines().skip_while(|l| l.trim().is_empty()).take_while(|l| !l.trim().is_empty()).map(str::trim).collect();
            let first = if first.is_empty() { "error: invalid command line".to_string() } else { first.join(" ") };
            eprintln!("{first} (see --help)");
            ExitCode::from(2)
        }
    }
}
