//! Similarity: the same model at another size. A model `s` times as large (every length × s)
//! behaves like the original — the same shape under its weight and its gas, the same sag, the
//! same bounce, only slower or faster — when every parameter is scaled by `s^e`, `e` from the
//! parameter's unit with lengths × s, masses × s³ (the same density) and times × s^½ (the same
//! gravity: a fall through the model's height takes √(2 s h / g), Froude scaling):
//!
//! | unit | e | why |
//! |---|---|---|
//! | m | 1 | a length |
//! | kg | 3 | the same density |
//! | s | ½ | times of fall and sway, √(L/g) |
//! | N/m (k, k_b) | 2 | the sag k ΔL = m g: (s³)(1)/(s) |
//! | J (nRT), mol at fixed T | 4 | the gas force P A = nRT A / V: s⁴ s² / s³ = s³, like the weight |
//! | Pa | 1 | nRT / V |
//! | N·s/m (c_s) | 2.5 | k × time |
//! | 1/s (c) | −½ | 1 / time |
//! | m/s, N·s/m³ | ½ | a speed; wind drag F = c_w A v: s³ / (s² s^½) |
//! | m/s², K, – | 0 | gravity, temperature, numbers |
//!
//! So every force scales as s³, every static balance (springs against weight against gas
//! against the ground's reaction) holds at the scaled positions, and a body that rests at x
//! rests, scaled, at s x: the test below settles both. The modeler opens an imported model at
//! the file's own size with the `modeler` preset scaled this way from the size it was tuned on
//! (a 2.5 m bounding-box diagonal), instead of rescaling the mesh
//! ([`World::apply_preset_scaled`](crate::world::World::apply_preset_scaled),
//! `world/params.rs`).
//!
//! The time step: smaller models get `dt × s^½` (the same number of steps per sway, so the
//! backward-Euler steps damp them no more than the original: at a fixed 1/60 s a 2.5 cm ball
//! comes to rest in another, collapsed shape); larger ones keep `dt` (the modeler's frame), more
//! accurate than needed. The implicit tolerance is relative: as it is.

use super::{ParamError, ParamId, Value};

/// The exponent `e` of a unit (as written in the parameter table: `N·s/m³`, `m/s²`, `1/s`, …):
/// a value in that unit becomes `value × s^e` for the model `s` times as large. None for a unit
/// it does not know.
pub fn exponent(unit: &str) -> Option<f64> {
    // Each base or derived unit as (m, kg, s) powers, then L = s, M = s³, T = s^½.
    fn base(u: &str) -> Option<[f64; 3]> {
        Some(match u {
            "" | "1" | "K" => [0.0, 0.0, 0.0],
            "m" => [1.0, 0.0, 0.0],
            "kg" => [0.0, 1.0, 0.0],
            "s" => [0.0, 0.0, 1.0],
            "N" => [1.0, 1.0, -2.0],
            "J" => [2.0, 1.0, -2.0],
            "Pa" => [-1.0, 1.0, -2.0],
            // The gas amount at a fixed temperature carries nRT: an energy.
            "mol" => [2.0, 1.0, -2.0],
            _ => return None,
        })
    }
    fn factor(f: &str) -> Option<[f64; 3]> {
        let (u, p) = match f.char_indices().last() {
            Some((i, '²')) => (&f[..i], 2.0),
            Some((i, '³')) => (&f[..i], 3.0),
            _ => (f, 1.0),
        };
        base(u).map(|d| d.map(|x| x * p))
    }
    fn product(s: &str) -> Option<[f64; 3]> {
        s.split('·').try_fold([0.0; 3], |acc, f| factor(f).map(|d| [acc[0] + d[0], acc[1] + d[1], acc[2] + d[2]]))
    }
    let (num, den) = unit.split_once('/').unwrap_or((unit, ""));
    let (n, d) = (product(num)?, product(den)?);
    Some((n[0] - d[0]) + 3.0 * (n[1] - d[1]) + 0.5 * (n[2] - d[2]))
}

/// `value` of parameter `id` for the model `s` times as large (numbers and vectors; flags and
/// choices as they are).
pub fn scaled(id: ParamId, value: Value, s: f64) -> Result<Value, ParamError> {
    let p = id.param();
    let e = exponent(p.unit).ok_or_else(|| ParamError { id: p.id.into(), message: format!("no similarity rule for the unit '{}'", p.unit) })?;
    let f = s.powf(e);
    Ok(match value {
        Value::Number(x) => Value::Number(x * f),
        Value::Vector(v) => Value::Vector(v.map(|x| x * f)),
        other => other,
    })
}

/// Parameters a scaled preset also sets, from the table's defaults, scaled: they depend on the
/// model's size too (the body's mass, the distance kept in contact).
pub const SIZED_DEFAULTS: &[ParamId] = &[ParamId::Mass, ParamId::ContactThickness];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::TABLE;

    #[test]
    fn every_unit_of_the_table_has_a_rule_from_its_dimensions() {
        for p in TABLE {
            assert!(exponent(p.unit).is_some(), "{}: unit '{}'", p.id, p.unit);
        }
        // Spot checks against the module's table (dimensions worked by hand).
        for (u, e) in [("N/m", 2.0), ("N·s/m", 2.5), ("1/s", -0.5), ("J", 4.0), ("Pa", 1.0), ("kg", 3.0), ("m/s²", 0.0), ("N·s/m³", 0.5), ("m/s", 0.5), ("mol", 4.0), ("K", 0.0), ("", 0.0)] {
            assert_eq!(exponent(u), Some(e), "{u}");
        }
        assert_eq!(exponent("furlong"), None);
    }
}
