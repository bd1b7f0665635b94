//! Every parameter of a body, with its unit. All of them can change between steps.

use crate::error::SimError;

/// Ideal gas constant R (J/(mol·K)).
pub const GAS_CONSTANT: f64 = 8.314462618;

/// Time integrator of the state (x, v).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    /// Explicit forward Euler: x' = x + dt v, v' = v + dt a(x, v). Order 1; gains energy.
    Euler,
    /// Explicit midpoint (RK2): slopes at (x + dt/2 v, v + dt/2 a). Order 2.
    Midpoint,
    /// Classic fourth-order Runge–Kutta on (x, v). Order 4.
    Rk4,
    /// Semi-implicit (symplectic) Euler: v' = v + dt a(x, v); x' = x + dt v'. Order 1; energy
    /// stays bounded (no drift) for conservative forces. The default.
    Symplectic,
}

impl Integrator {
    pub const NAMES: &'static [&'static str] = &["euler", "midpoint", "rk4", "symplectic"];
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Euler => "euler",
            Integrator::Midpoint => "midpoint",
            Integrator::Rk4 => "rk4",
            Integrator::Symplectic => "symplectic",
        }
    }
    pub fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "euler" => Integrator::Euler,
            "midpoint" => Integrator::Midpoint,
            "rk4" => Integrator::Rk4,
            "symplectic" => Integrator::Symplectic,
            _ => return None,
        })
    }
}

/// Which volume the gas law uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VolumeMode {
    /// Exact enclosed volume V = Σ_faces xa · (xb × xc) / 6. The pressure force is then exactly
    /// P ∂V/∂x, so the gas is a conservative force. The default.
    Exact,
    /// Axis-aligned bounding box volume (the original paper's approximation).
    Box,
    /// Bounding sphere 4/3 π r³, r the largest distance from the vertex centroid (the paper's
    /// other approximation).
    Sphere,
}

impl VolumeMode {
    pub const NAMES: &'static [&'static str] = &["exact", "box", "sphere"];
    pub fn name(self) -> &'static str {
        match self {
            VolumeMode::Exact => "exact",
            VolumeMode::Box => "box",
            VolumeMode::Sphere => "sphere",
        }
    }
    pub fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "exact" => VolumeMode::Exact,
            "box" => VolumeMode::Box,
            "sphere" => VolumeMode::Sphere,
            _ => return None,
        })
    }
}

/// A rigid ground plane y = height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    /// Height of the plane (m).
    pub height: f64,
    /// Coulomb friction coefficient μ (dimensionless): a contact impulse j along the normal
    /// removes up to μ j of tangential velocity.
    pub friction: f64,
    /// Coefficient of restitution e in [0, 1] (dimensionless): 0 is inelastic (the default).
    pub restitution: f64,
}

impl Ground {
    pub fn at(height: f64) -> Self {
        Ground { height, friction: 0.5, restitution: 0.0 }
    }
}

/// Parameters of a body. Names in error messages match the CLI flags.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// Spring stiffness k (N/m), the same for every edge.
    pub stiffness: f64,
    /// Damping along each spring cs (N·s/m): force cs ((vj − vi) · d) d on i.
    pub spring_damping: f64,
    /// Stiffness of the bending springs (N/m), which join the two vertices opposite each edge
    /// and so resist folding across it; 0 (the default) leaves the surface free to fold, as in
    /// the original model. They use the same damping cs.
    pub bending_stiffness: f64,
    /// Viscous damping rate c (1/s): force −c mi vi, velocities decay as e^(−c t).
    pub damping: f64,
    /// Gravitational acceleration g (m/s²) along −y.
    pub gravity: f64,
    /// Amount of gas n (mol).
    pub gas_amount: f64,
    /// Gas temperature T (K).
    pub temperature: f64,
    /// Which volume the gas law uses.
    pub volume_mode: VolumeMode,
    /// Wind velocity w (m/s).
    pub wind: [f64; 3],
    /// Wind drag coefficient cw (N·s/m³ = kg/(m²·s)): force cw · area · ((w − v_face) · n) n on a
    /// face that sees the wind.
    pub wind_drag: f64,
    /// Optional ground plane.
    pub ground: Option<Ground>,
    /// Rigid obstacles (spheres, boxes, capsules) the body cannot enter.
    pub obstacles: Vec<super::obstacles::Obstacle>,
    /// Time integrator.
    pub integrator: Integrator,
    /// Keep the body's vertices out of its own faces. Only a [`crate::world::World`] does this
    /// (it needs the broad phase); off by default.
    pub self_collision: bool,
}

/// Default temperature (K) used when a total nRT is given.
pub const DEFAULT_TEMPERATURE: f64 = 300.0;

impl Default for Params {
    fn default() -> Self {
        Params {
            stiffness: 1000.0,
            spring_damping: 1.0,
            bending_stiffness: 0.0,
            damping: 0.0,
            gravity: 9.81,
            gas_amount: 0.0,
            temperature: DEFAULT_TEMPERATURE,
            volume_mode: VolumeMode::Exact,
            wind: [0.0; 3],
            wind_drag: 1.0,
            ground: None,
            obstacles: Vec::new(),
            integrator: Integrator::Symplectic,
            self_collision: false,
        }
    }
}

fn bad(name: &'static str, message: String) -> SimError {
    SimError::BadParameter { name, message }
}

/// `value` must be finite and ≥ 0.
pub fn check_non_negative(name: &'static str, value: f64) -> Result<(), SimError> {
    if !value.is_finite() {
        return Err(bad(name, format!("must be a finite number, got {value}")));
    }
    if value < 0.0 {
        return Err(bad(name, format!("must not be negative, got {value}")));
    }
    Ok(())
}

/// `value` must be finite and > 0.
pub fn check_positive(name: &'static str, value: f64) -> Result<(), SimError> {
    if !(value.is_finite() && value > 0.0) {
        return Err(bad(name, format!("must be a finite number greater than 0, got {value}")));
    }
    Ok(())
}

impl Params {
    /// n R T (J): the product the gas law uses.
    pub fn nrt(&self) -> f64 {
        self.gas_amount * GAS_CONSTANT * self.temperature
    }

    /// Set the gas by its product nRT (J), keeping the temperature.
    pub fn set_nrt(&mut self, nrt: f64) {
        self.gas_amount = nrt / (GAS_CONSTANT * self.temperature);
    }

    /// Reject non-finite or out-of-range values with a message naming the parameter.
    pub fn validate(&self) -> Result<(), SimError> {
        check_non_negative("stiffness", self.stiffness)?;
        check_non_negative("spring-damping", self.spring_damping)?;
        check_non_negative("bending", self.bending_stiffness)?;
        check_non_negative("damping", self.damping)?;
        if !self.gravity.is_finite() {
            return Err(bad("gravity", format!("must be finite, got {}", self.gravity)));
        }
        check_non_negative("gas", self.gas_amount)?;
        check_positive("temperature", self.temperature)?;
        if self.wind.iter().any(|w| !w.is_finite()) {
            return Err(bad("wind", format!("must be finite, got {:?}", self.wind)));
        }
        check_non_negative("wind-drag", self.wind_drag)?;
        if let Some(g) = self.ground {
            if !g.height.is_finite() {
                return Err(bad("ground", format!("must be finite, got {}", g.height)));
            }
            check_non_negative("friction", g.friction)?;
            if !(0.0..=1.0).contains(&g.restitution) {
                return Err(bad("restitution", format!("must be between 0 and 1, got {}", g.restitution)));
            }
        }
        for (k, o) in self.obstacles.iter().enumerate() {
            o.validate().map_err(|m| bad("obstacle", format!("obstacle {}: {m}", k + 1)))?;
        }
        Ok(())
    }
}

/// Time step (s): finite and > 0.
pub fn check_dt(dt: f64) -> Result<(), SimError> {
    check_positive("dt", dt)
}
