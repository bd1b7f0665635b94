//! A parameter that is a field of a struct (a body's `Material`, the world's `WorldSettings`
//! and its `Ground`): the table entry and how to read and write the field, as fn pointers. Each
//! struct lists its fields once, beside its definition (`body/material.rs`, `settings.rs`), and
//! get, set and validation by id all go through that list; this module knows nothing of bodies
//! or worlds (`tests/layers.rs`), only the shape of such a list.

use super::{Param, Value};
use crate::error::SimError;

/// Parameter `param` stored in a field of `T`.
pub struct Field<T: 'static> {
    pub param: &'static Param,
    /// The field's value as the table's kind of value.
    pub get: fn(&T) -> Value,
    /// Write a value into the field. The caller has checked it first ([`Param::check`]: the
    /// right kind, in range); an Err is what the field refuses besides (a choice it does not
    /// know, a fraction for a count), without the id.
    pub set: fn(&mut T, Value) -> Result<(), String>,
}

/// The field of `fields` whose parameter is `id`.
pub fn field<T>(fields: &'static [Field<T>], id: &str) -> Option<&'static Field<T>> {
    fields.iter().find(|f| f.param.id == id)
}

/// Every field of `of` checked against its parameter's range: the first that does not fit,
/// named by its table id, with the table's message (which names the unit).
pub fn check_fields<T>(fields: &'static [Field<T>], of: &T) -> Result<(), SimError> {
    fields.iter().try_for_each(|f| f.param.check(&(f.get)(of)).map_err(|e| SimError::BadParameter { name: f.param.id, message: e.message }))
}

/// A [`Field`] of type `$t` for number parameter `$param`, stored in the f64 `$field` (a path
/// of field names, `contact.thickness`).
macro_rules! number_field {
    ($t:ty, $param:expr, $($field:ident).+) => {
        $crate::params::field::Field::<$t> {
            param: &$param,
            get: |s: &$t| $crate::params::Value::Number(s.$($field).+),
            set: |s: &mut $t, v| match v {
                $crate::params::Value::Number(x) => {
                    s.$($field).+ = x;
                    Ok(())
                }
                other => Err(format!("expected a number, got {other:?}")),
            },
        }
    };
}
pub(crate) use number_field;

/// A [`Field`] of type `$t` for flag parameter `$param`, stored in the bool `$field`.
macro_rules! flag_field {
    ($t:ty, $param:expr, $($field:ident).+) => {
        $crate::params::field::Field::<$t> {
            param: &$param,
            get: |s: &$t| $crate::params::Value::Flag(s.$($field).+),
            set: |s: &mut $t, v| match v {
                $crate::params::Value::Flag(x) => {
                    s.$($field).+ = x;
                    Ok(())
                }
                other => Err(format!("expected true or false, got {other:?}")),
            },
        }
    };
}
pub(crate) use flag_field;

/// A [`Field`] of type `$t` for choice parameter `$param`, stored in `$field` of a type `$ty`
/// with `name()` and `from_name(&str) -> Option<$ty>` (the integrator, the volume mode); a name
/// it does not know is refused as "unknown `$what`".
macro_rules! choice_field {
    ($t:ty, $param:expr, $field:ident: $ty:ty, $what:literal) => {
        $crate::params::field::Field::<$t> {
            param: &$param,
            get: |s: &$t| $crate::params::Value::Choice(s.$field.name()),
            set: |s: &mut $t, v| match v {
                $crate::params::Value::Choice(c) => <$ty>::from_name(c).map(|x| s.$field = x).ok_or_else(|| concat!("unknown ", $what).into()),
                other => Err(format!("expected a name, got {other:?}")),
            },
        }
    };
}
pub(crate) use choice_field;
