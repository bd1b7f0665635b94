//! The binding's one table of exports (issue #39 item 3). Every raw export is written once, in
//! an [`exports!`] block of the module it belongs to:
//!
//! ```ignore
//! exports! {
//!     /// `n` steps …
//!     pub fn ss_step(w: u32, n: u32) -> i32 { … }
//!     /// # Safety …
//!     pub unsafe fn ss_restore(w: u32, ptr: *const u8, len: usize) -> i32 { … }
//! }
//! ```
//!
//! which emits each function as `#[no_mangle] pub extern "C"` (unchanged: the same symbols, the
//! same code) and records its name, doc comment and signature in the module's `EXPORTS`, a
//! `const` slice ([`Export`]). The crate root gathers them (`softsculpt_wasm::exports`), and
//! `tests/abi.rs` writes the page's side from them and from the other shared numbers (the layout
//! table's slots and the stats order, `views.rs`; the delta scopes, `history.rs`):
//! `web/src/engine/abi.ts`. The tables are data only the tests read: the wasm linker keeps only
//! the exports themselves, so the module is as it was.
//!
//! Types on the page are the wasm-level ones ([`WasmType`]): every 32-bit integer, pointer and
//! float is a JS `number`; 64-bit integers are `bigint`. A type without an impl is refused at
//! compile time.

/// A Rust type an export takes or returns, and what the page sees of it.
pub trait WasmType {
    /// Its TypeScript type.
    const TS: &'static str;
}

macro_rules! wasm_types {
    ($ts:literal: $($t:ty),*) => { $(impl WasmType for $t { const TS: &'static str = $ts; })* };
}
// On wasm32 `usize` and pointers are i32; u8 arrives widened to i32.
wasm_types!("number": u8, u32, i32, usize, isize, f32, f64);
wasm_types!("bigint": u64, i64);
wasm_types!("void": ());
impl<T> WasmType for *const T {
    const TS: &'static str = "number";
}
impl<T> WasmType for *mut T {
    const TS: &'static str = "number";
}

/// One argument of an export.
#[derive(Debug)]
pub struct Param {
    pub name: &'static str,
    /// As written in Rust (`*const u8`).
    pub rust: &'static str,
    /// On the page ([`WasmType::TS`]).
    pub ts: &'static str,
}

/// One raw export: what the `exports!` block said of it.
#[derive(Debug)]
pub struct Export {
    pub name: &'static str,
    /// Its doc comment, a line per entry (as rustdoc has it: a leading space kept).
    pub doc: &'static [&'static str],
    pub params: &'static [Param],
    /// The return type in Rust (`()` for none) and on the page (`void`).
    pub ret_rust: &'static str,
    pub ret_ts: &'static str,
    /// Declared `unsafe` (it reads memory the caller points to).
    pub unsafe_: bool,
}

/// The exports of one module: see the module documentation. Only doc comments may stand before
/// a function (they are kept on it and in the table).
macro_rules! exports {
    // The table, once every function is emitted.
    (@fns [$($e:expr,)*]) => {
        /// This module's raw exports (`abi.rs`).
        pub(crate) const EXPORTS: &[$crate::abi::Export] = &[$($e,)*];
    };
    (@fns [$($e:expr,)*] $(#[doc = $d:literal])* pub unsafe fn $name:ident ($($a:ident : $t:ty),* $(,)?) $(-> $r:ty)? $body:block $($rest:tt)*) => {
        $(#[doc = $d])*
        #[no_mangle]
        pub unsafe extern "C" fn $name($($a: $t),*) $(-> $r)? $body
        $crate::abi::exports!(@fns [$($e,)* $crate::abi::exports!(@entry true $name [$($d)*] ($($a: $t),*) $($r)?),] $($rest)*);
    };
    (@fns [$($e:expr,)*] $(#[doc = $d:literal])* pub fn $name:ident ($($a:ident : $t:ty),* $(,)?) $(-> $r:ty)? $body:block $($rest:tt)*) => {
        $(#[doc = $d])*
        #[no_mangle]
        pub extern "C" fn $name($($a: $t),*) $(-> $r)? $body
        $crate::abi::exports!(@fns [$($e,)* $crate::abi::exports!(@entry false $name [$($d)*] ($($a: $t),*) $($r)?),] $($rest)*);
    };
    (@fns $($bad:tt)*) => {
        compile_error!("exports!: only `pub fn` and `pub unsafe fn` exports, each with its doc comment, stand in the block");
    };
    (@entry $unsafe_:literal $name:ident [$($d:literal)*] ($($a:ident : $t:ty),*) $($r:ty)?) => {
        $crate::abi::Export {
            name: stringify!($name),
            doc: &[$($d),*],
            params: &[$($crate::abi::Param { name: stringify!($a), rust: stringify!($t), ts: <$t as $crate::abi::WasmType>::TS }),*],
            ret_rust: $crate::abi::exports!(@rust $($r)?),
            ret_ts: <$crate::abi::exports!(@ty $($r)?) as $crate::abi::WasmType>::TS,
            unsafe_: $unsafe_,
        }
    };
    (@rust) => { "()" };
    (@rust $r:ty) => { stringify!($r) };
    (@ty) => { () };
    (@ty $r:ty) => { $r };
    ($($body:tt)*) => { $crate::abi::exports!(@fns [] $($body)*); };
}
pub(crate) use exports;
