//! The JSON reports calls put in the result slot, each written once, in a [`reports!`] block
//! beside the call that serializes it:
//!
//! ```ignore
//! reports! {
//!     /// What a freeze leaves unbalanced …
//!     pub struct FreezeReport {
//!         /// Largest net force (N) …
//!         pub residual: f64,
//!         …
//!     }
//! }
//! ```
//!
//! which emits the struct (serde's `Serialize`: the JSON the page reads) and records its name,
//! doc comments and fields, with their TypeScript types ([`TsType`]; a field may say its own
//! with `#[ts = "'y' | 'z'"]`), in the module's `REPORTS` ([`Report`]). The crate root gathers
//! them (`softsculpt_wasm::reports`), and `tests/abi.rs` writes their TypeScript interfaces into
//! `web/src/engine/abi.ts`. A new field is written once, in its struct here; the page's type
//! follows when the file is written again (`UPDATE_ABI=1`). Imports nothing of the crate.

/// A Rust type a report field holds, and its TypeScript type in the JSON.
pub trait TsType {
    fn ts() -> String;
}

macro_rules! ts_types {
    ($ts:literal: $($t:ty),*) => { $(impl TsType for $t { fn ts() -> String { $ts.to_string() } })* };
}
// JSON numbers, whatever their width in Rust.
ts_types!("number": u32, u64, usize, i32, i64, f64);
ts_types!("boolean": bool);
ts_types!("string": String, &str);
impl<T: TsType> TsType for Option<T> {
    fn ts() -> String {
        format!("{} | null", T::ts())
    }
}
impl<T: TsType> TsType for Vec<T> {
    fn ts() -> String {
        let t = T::ts();
        if t.contains(' ') { format!("({t})[]") } else { format!("{t}[]") }
    }
}

/// One field of a report.
#[derive(Debug)]
pub struct Field {
    pub name: &'static str,
    /// Its doc comment, a line per entry (as rustdoc has it: a leading space kept).
    pub doc: &'static [&'static str],
    /// Its TypeScript type ([`TsType`], or the field's `#[ts = …]`).
    pub ts: fn() -> String,
}

/// One report: what its `reports!` block said of it.
#[derive(Debug)]
pub struct Report {
    pub name: &'static str,
    pub doc: &'static [&'static str],
    pub fields: &'static [Field],
}

/// The reports of one module: see the module documentation. Only doc comments (and `#[ts]` on
/// a field) may stand before a struct or a field; every field is `pub`.
macro_rules! reports {
    (@structs [$($r:expr,)*]) => {
        /// This module's reports (`report.rs`).
        pub(crate) const REPORTS: &[$crate::report::Report] = &[$($r,)*];
    };
    (@structs [$($r:expr,)*]
        $(#[doc = $d:literal])*
        pub struct $name:ident {
            $( $(#[doc = $fd:literal])* $(#[ts = $ts:literal])? pub $field:ident : $t:ty ),* $(,)?
        }
        $($rest:tt)*
    ) => {
        $(#[doc = $d])*
        #[derive(Debug, serde::Serialize)]
        pub struct $name {
            $( $(#[doc = $fd])* pub $field: $t, )*
        }
        impl $crate::report::TsType for $name {
            fn ts() -> String {
                stringify!($name).to_string()
            }
        }
        $crate::report::reports!(@structs [$($r,)* $crate::report::Report {
            name: stringify!($name),
            doc: &[$($d),*],
            fields: &[$($crate::report::Field {
                name: stringify!($field),
                doc: &[$($fd),*],
                ts: $crate::report::reports!(@ts $t $(, $ts)?),
            }),*],
        },] $($rest)*);
    };
    (@structs $($bad:tt)*) => {
        compile_error!("reports!: only `pub struct`s of `pub` fields, each with its doc comment, stand in the block");
    };
    (@ts $t:ty) => { <$t as $crate::report::TsType>::ts };
    (@ts $t:ty, $ts:literal) => { || String::from($ts) };
    ($($body:tt)*) => { $crate::report::reports!(@structs [] $($body)*); };
}
pub(crate) use reports;

/// The JSON of a report, for the result slot.
pub fn json(r: &impl serde::Serialize) -> Vec<u8> {
    serde_json::to_vec(r).unwrap_or_default()
}
