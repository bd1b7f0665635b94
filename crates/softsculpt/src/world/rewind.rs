//! Where a failed frame goes back to: the last sound state ([`Budget::rewind`], the modeler).
//!
//! [`World::step_n`] rolls a failed call back to its start, but the start of the failing frame
//! may already be collapsing: a body turned half inside out, its volume near zero. So a world
//! advanced under a budget that rewinds keeps a few rewind points — what its steps change
//! (positions, velocities, the implicit warm start and kept levels, the plastic state: the
//! rollback's `Backup`) and the clock, every [`REWIND_EVERY`] simulated seconds since the
//! caller's last change — and on a failure goes back to the last one known good: the newest
//! point whose gas-filled bodies were healthy (each at least [`HEALTHY`] of its volume at the
//! first point) and stayed healthy until the next point. Nothing older than the caller's last
//! change is kept: the caller says so ([`World::forget_rewind`]: the modeler on every edit),
//! and a change of dt, of the bodies' sizes or a scene event fired since clears the points
//! too, so going back never undoes a change: at worst it is the state the change left.

use super::rollback::Backup;
use super::{Budget, Clock, World};

/// Simulated seconds between rewind points (at least; see [`REWIND_OVERHEAD`]).
pub const REWIND_EVERY: f64 = 0.25;
/// The share of the budget's time the points may take: the interval grows to a point's cost /
/// this (copying a 163,842-vertex world's state takes a few ms natively).
pub const REWIND_OVERHEAD: f64 = 0.03;
/// Points kept (the newest; [`REWIND_KEEP`] × [`REWIND_EVERY`] = 2 s of simulated time back)…
pub const REWIND_KEEP: usize = 8;
/// …within this many bytes: the oldest go first, the first point (the state the last change
/// left) stays.
pub const REWIND_BYTES: usize = 96 * 1024 * 1024;
/// A gas-filled body is healthy while its volume is at least this share of its volume at the
/// first point.
pub const HEALTHY: f64 = 0.5;

/// One rewind point.
#[derive(Debug)]
struct Point {
    clock: Clock,
    /// The pairs of bodies with contacts off then (`overlaps.rs`): they part as the bodies move.
    overlaps: super::overlaps::Overlaps,
    volumes: Vec<f64>,
    state: Backup,
    bytes: usize,
}

/// The rewind points since the caller's last change (see the module documentation). A copy of
/// the world starts without any: its past is the original's.
#[derive(Debug, Default)]
pub(crate) struct Rewind {
    points: Vec<Point>,
    /// Per body: its volume at the first point, or 0 for a body without gas.
    base: Vec<f64>,
    /// What a change would alter: dt, the bodies' vertex counts, the scene events' cursor.
    mark: (f64, Vec<usize>, usize, usize),
    /// Simulated seconds since the newest point.
    since: f64,
    /// Wall-clock seconds the last point took (0 without a clock).
    cost: f64,
}

impl Clone for Rewind {
    fn clone(&self) -> Self {
        Rewind::default()
    }
}

impl Rewind {
    /// Simulated seconds between points: [`REWIND_EVERY`], or longer where a point is costly.
    fn every(&self) -> f64 {
        REWIND_EVERY.max(self.cost / REWIND_OVERHEAD)
    }

    fn healthy(&self, p: &Point) -> bool {
        p.volumes.iter().zip(&self.base).all(|(&v, &b)| !(b > 0.0) || (v.is_finite() && v >= HEALTHY * b))
    }
}

impl World {
    /// The caller changed the model: the rewind points before it are no longer its past.
    pub fn forget_rewind(&mut self) {
        self.rewind.points.clear();
    }

    /// The number of rewind points kept (for the tests and the statistics).
    pub fn rewind_points(&self) -> usize {
        self.rewind.points.len()
    }

    fn rewind_mark(&self) -> (f64, Vec<usize>, usize, usize) {
        (self.settings.dt, self.bodies.iter().map(|b| b.vertex_count()).collect(), self.events.next, self.events.loads.len())
    }

    /// Before a frame: forget the points if something changed since the last one, and keep
    /// the state as it is now if there are none.
    pub(super) fn rewind_before(&mut self, budget: &Budget) {
        let mark = self.rewind_mark();
        if mark != self.rewind.mark {
            self.rewind.points.clear();
            self.rewind.mark = mark;
        }
        if self.rewind.points.is_empty() {
            self.rewind_point(budget);
        }
    }

    /// After a frame that advanced `simulated` seconds: a point if one is due.
    pub(super) fn rewind_after(&mut self, budget: &Budget, simulated: f64) {
        if self.rewind_mark() != self.rewind.mark {
            // A scene event fired in the frame: the points before it are not its past.
            self.rewind.points.clear();
            self.rewind.mark = self.rewind_mark();
        }
        self.rewind.since += simulated;
        if self.rewind.points.is_empty() || self.rewind.since >= self.rewind.every() - 1e-9 {
            self.rewind_point(budget);
        }
    }

    /// Keep the state as it is now (the first point of a change also takes the bodies' volumes
    /// as the measure of health), then drop the oldest points past [`REWIND_KEEP`] or
    /// [`REWIND_BYTES`] (never the first).
    fn rewind_point(&mut self, budget: &Budget) {
        let now = budget.real_time.map(|r| r.now);
        let t0 = now.map(|f| f());
        let volumes: Vec<f64> = self.bodies.iter().map(|b| b.volume()).collect();
        if self.rewind.points.is_empty() {
            self.rewind.base = self.bodies.iter().zip(&volumes).map(|(b, &v)| if b.material.gas_amount > 0.0 && v > 0.0 { v } else { 0.0 }).collect();
        }
        let mut state = Backup::default();
        state.save(&self.bodies);
        let bytes = state.bytes();
        self.rewind.points.push(Point { clock: self.clock, overlaps: self.overlaps.clone(), volumes, state, bytes });
        self.rewind.since = 0.0;
        if let (Some(now), Some(t0)) = (now, t0) {
            self.rewind.cost = now() - t0;
        }
        let points = &mut self.rewind.points;
        let mut total: usize = points.iter().map(|p| p.bytes).sum();
        while points.len() > 2 && (points.len() > REWIND_KEEP || total > REWIND_BYTES) {
            total -= points[1].bytes;
            points.remove(1);
        }
    }

    /// After a failed frame (the world rolled back to the failing step's start): back to the
    /// newest healthy point whose successor was healthy too (the newest point's successor is
    /// the failure, whose state is not known: it is chosen only if it is the only one), else
    /// the first point (the state the last change left). The newer points go. Its simulated
    /// time, or None if there is no point that fits the world (the rollback stands).
    pub(super) fn rewind_to_good(&mut self) -> Option<f64> {
        // A scene event fired in this frame's steps before the failing one (the rollback undid
        // only the failing step): the points are from before it, so none is the world's past.
        let changed = self.rewind_mark() != self.rewind.mark;
        let r = &mut self.rewind;
        if changed || r.points.is_empty() || !r.points[0].state.fits(&self.bodies) {
            r.points.clear();
            return None;
        }
        let mut k = r.points.len().saturating_sub(2);
        while k > 0 && !(r.healthy(&r.points[k]) && r.healthy(&r.points[k + 1])) {
            k -= 1;
        }
        r.points.truncate(k + 1);
        let p = &r.points[k];
        p.state.restore(&mut self.bodies);
        self.clock = p.clock;
        self.overlaps.clone_from(&p.overlaps);
        r.since = 0.0;
        Some(self.clock.time())
    }
}
