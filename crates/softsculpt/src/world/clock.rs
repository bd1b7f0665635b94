//! The world's clock: steps taken and simulated time.
//!
//! Time is t_base + since · dt, with `since` the steps taken since dt last changed and t_base the
//! time then — never a running sum of dt, so a long run does not drift (10⁶ steps of 1e-3 s end
//! at exactly 1000 s). Changing `WorldSettings::dt` between steps rebases the clock at the next
//! step, so the time stays continuous.

/// Steps and simulated time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clock {
    /// Steps since the world was made.
    pub(crate) steps: u64,
    /// Time (s) when `dt` last changed, and steps since.
    pub(crate) t_base: f64,
    pub(crate) since: u64,
    /// The time step (s) `since` counts in.
    pub(crate) dt: f64,
}

impl Clock {
    pub fn new(dt: f64) -> Self {
        Clock { steps: 0, t_base: 0.0, since: 0, dt }
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.t_base + self.since as f64 * self.dt
    }

    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Count further steps in `dt` (s) from now on.
    pub(crate) fn rebase(&mut self, dt: f64) {
        if dt != self.dt {
            self.t_base = self.time();
            self.since = 0;
            self.dt = dt;
        }
    }

    pub(crate) fn tick(&mut self) {
        self.steps += 1;
        self.since += 1;
    }
}
