//! `softsculpt sweep SCENE --grid GRID.toml --out DIR [--workers N] [--scheduler ADDR]
//! [--frames N]`: a parameter sweep of a scene on Dask distributed. The sweep is the Python
//! package's (`softsculpt.sweep`, in `softsculpt/sweeps.py`; docs/python.md): this command runs `python -m softsculpt
//! sweep` with the same arguments, in the Python that `SOFTSCULPT_PYTHON` names (default
//! `python3`), and says how to install the package if that Python lacks it.

use clap::Args;
use std::path::PathBuf;
use std::process::Command;

#[derive(Args, Debug)]
pub struct SweepArgs {
    /// The scene file (.toml); see docs/scenes.md.
    pub scene: PathBuf,
    /// TOML file listing each parameter's values by its table id (`stiffness = [100, 300]`).
    #[arg(long, value_name = "FILE")]
    pub grid: PathBuf,
    /// Directory for sweep.parquet, sweep.csv and each run's folder.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Worker processes of the local Dask cluster (default: every core; 0: one run after
    /// another in one process, without Dask).
    #[arg(long, value_parser = crate::args::count, value_name = "N")]
    pub workers: Option<u64>,
    /// A Dask scheduler's address (tcp://host:8786): the sweep runs on that cluster instead.
    #[arg(long, value_name = "ADDR")]
    pub scheduler: Option<String>,
    /// Also write N OBJ frames of every run (N ≥ 2).
    #[arg(long, value_parser = crate::args::count_positive, value_name = "N")]
    pub frames: Option<u64>,
    /// Replace an earlier sweep's outputs in --out (a folder holding anything else is refused).
    #[arg(long)]
    pub overwrite: bool,
}

pub fn run(a: SweepArgs) -> Result<(), String> {
    let python = std::env::var("SOFTSCULPT_PYTHON").unwrap_or_else(|_| "python3".into());
    let found = Command::new(&python).args(["-c", "import softsculpt.sweeps, dask.distributed, pandas, pyarrow"]).output();
    match found {
        Err(e) => return Err(format!("sweep runs in Python, and '{python}' did not start ({e}): set SOFTSCULPT_PYTHON to a Python with the softsculpt package (docs/python.md)")),
        Ok(o) if !o.status.success() => {
            let why = String::from_utf8_lossy(&o.stderr).lines().last().unwrap_or("").to_string();
            return Err(format!("sweep runs in Python, and '{python}' cannot import the softsculpt package with Dask, pandas and pyarrow ({why}): install it (pip install 'crates/softsculpt-py[sweep]', docs/python.md) or set SOFTSCULPT_PYTHON"));
        }
        Ok(_) => {}
    }
    let mut cmd = Command::new(&python);
    cmd.args(["-m", "softsculpt", "sweep"]).arg(&a.scene).arg("--grid").arg(&a.grid).arg("--out").arg(&a.out);
    if let Some(n) = a.workers {
        cmd.arg("--workers").arg(n.to_string());
    }
    if let Some(s) = &a.scheduler {
        cmd.arg("--scheduler").arg(s);
    }
    if let Some(n) = a.frames {
        cmd.arg("--frames").arg(n.to_string());
    }
    if a.overwrite {
        cmd.arg("--overwrite");
    }
    let status = cmd.status().map_err(|e| format!("'{python}' did not start: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        // The Python side printed its own one `error:` line.
        std::process::exit(status.code().unwrap_or(1))
    }
}
