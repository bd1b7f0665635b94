//! The core's errors as a [`Fail`] for the page: each kind with the fields the page reads
//! (`kind`, `message`, and per kind the parameter and its unit, the step and its cause, a line).

use crate::Fail;
use softsculpt::body::BodyError;
use softsculpt::params::{self, ParamError};
use softsculpt::snapshot::SnapshotError;
use softsculpt::{MeshError, SimError, StepError};


pub fn mesh_fail(e: MeshError) -> Fail {
    let line = if let MeshError::Parse { line, .. } = e {
        Some(line)
    } else {
        None
    };
    let f = Fail::new("mesh", e.to_string());
    match line {
        Some(l) => f.with("line", l),
        None => f,
    }
}

/// A simulation error: a parameter refused, a wrong length (usage), or a blow-up (step).
pub fn sim_fail(e: SimError) -> Fail {
    match &e {
        SimError::BadParameter { name, .. } => {
            Fail::new("parameter", e.to_string()).with("parameter", *name)
        }
        SimError::Length { .. } => Fail::usage(e.to_string()),
        SimError::NonFinite { step } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("cause", "non_finite"),
        SimError::Collapsed { step, volume } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("cause", "collapsed")
            .with("volume", *volume),
        SimError::NotConverged { step, time, .. } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("time", *time)
            .with("converged", false)
            .with("cause", "not_converged"),
        SimError::Interrupted { step, time } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("time", *time)
            .with("cause", "interrupted"),
    }
}

pub fn body_fail(e: BodyError) -> Fail {
    match e {
        BodyError::Mesh(m) => mesh_fail(m),
        BodyError::Sim(s) => sim_fail(s),
    }
}

/// Names the parameter and its unit.
pub fn param_fail(e: ParamError) -> Fail {
    let unit = params::find(&e.id).map(|p| p.unit).unwrap_or("");
    Fail::new("parameter", e.to_string())
        .with("parameter", e.id)
        .with("unit", unit)
}

pub fn step_fail(e: StepError) -> Fail {
    let mut f = Fail::new("step", e.to_string())
        .with("time", e.time)
        .with("step", e.step);
    // What went wrong, for the page to say in the user's terms: `cause` is `non_finite` (a
    // blow-up), `collapsed` (the gas volume fell to zero or below; `volume` m³) or
    // `not_converged` (an implicit step did not converge: a shorter step may succeed).
    match e.error {
        SimError::NotConverged { .. } => f = f.with("converged", false).with("cause", "not_converged"),
        SimError::NonFinite { .. } => f = f.with("cause", "non_finite"),
        SimError::Collapsed { volume, .. } => f = f.with("cause", "collapsed").with("volume", volume),
        SimError::Interrupted { .. } => f = f.with("cause", "interrupted"),
        _ => {}
    }
    if let Some(l) = e.line {
        f = f.with("line", l);
    }
    if let Some(t) = e.rolled_back_to {
        f = f.with("rolled_back_to", t);
    }
    if let Some(t) = e.rewound_to {
        f = f.with("rewound_to", t);
    }
    f
}

pub fn snapshot_fail(e: SnapshotError) -> Fail {
    Fail::new("snapshot", e.to_string())
}
