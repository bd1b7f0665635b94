//! Value parsers for flags: each rejects what the engine cannot use, with a reason. Help texts
//! of the flags that set a parameter come from the core's table ([`help`]).

/// A parameter's help line with its unit: "Spring stiffness k of every edge [N/m]".
pub fn help(p: &softsculpt::params::Param) -> String {
    let mut text: String = p.help.chars().take(1).flat_map(char::to_uppercase).chain(p.help.chars().skip(1)).collect();
    if !p.unit.is_empty() {
        text = format!("{text} [{}]", p.unit);
    }
    text
}

/// A finite number.
pub fn finite(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("'{s}' is not a number"))?;
    if !v.is_finite() {
        return Err(format!("must be a finite number, got '{s}'"));
    }
    Ok(v)
}

/// A finite number > 0.
pub fn positive(s: &str) -> Result<f64, String> {
    let v = finite(s)?;
    if v <= 0.0 {
        return Err(format!("must be greater than 0, got {v}"));
    }
    Ok(v)
}

/// A finite number ≥ 0.
pub fn non_negative(s: &str) -> Result<f64, String> {
    let v = finite(s)?;
    if v < 0.0 {
        return Err(format!("must not be negative, got {v}"));
    }
    Ok(v)
}

/// A whole number ≥ 0.
pub fn count(s: &str) -> Result<u64, String> {
    let t = s.trim();
    if t.starts_with('-') {
        return Err(format!("must not be negative, got {t}"));
    }
    t.parse().map_err(|_| format!("'{s}' is not a whole number"))
}

/// `--threads`: a whole number up to what the machine runs at once (0: every core,
/// `softsculpt::par::max_threads`), checked before anything is read. More would only take
/// turns (`--threads 1000` ran ~500× slower on 2 cores), and thousands of them stopped the
/// machine (`--threads 99999`: 2,498 threads after four minutes, load average 2,300).
pub fn threads(s: &str) -> Result<u64, String> {
    let n = count(s)?;
    softsculpt::par::check_threads(n)?;
    Ok(n)
}

/// A whole number ≥ 1.
pub fn count_positive(s: &str) -> Result<u64, String> {
    let n = count(s)?;
    if n == 0 {
        return Err("must be at least 1".into());
    }
    Ok(n)
}

/// A Newton iteration cap: a whole number in the table's range.
pub fn newton_cap(s: &str) -> Result<u64, String> {
    let n = count(s)?;
    let max = softsculpt::params::NEWTON_ITERATIONS.range.max as u64;
    if !(1..=max).contains(&n) {
        return Err(format!("must be a whole number from 1 to {max}, got {n}"));
    }
    Ok(n)
}

/// Three finite numbers separated by commas: `X,Y,Z`.
pub fn vec3(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected three comma-separated numbers X,Y,Z, got '{s}'"));
    }
    let mut out = [0.0; 3];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = finite(p).map_err(|e| format!("in '{s}': {e}"))?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn rejects_what_the_engine_cannot_use() {
        assert!(positive("0").is_err());
        assert!(positive("NaN").is_err());
        assert!(positive("inf").is_err());
        assert!(non_negative("-1").is_err());
        assert!(count("-5").is_err());
        assert!(vec3("1,2").is_err());
        assert!(vec3("1,x,3").is_err());
        assert_eq!(vec3("1, 2 ,3").unwrap(), [1.0, 2.0, 3.0]);
    }
}
