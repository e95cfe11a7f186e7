//! The accuracy report of the special functions: for every function, the largest relative
//! error against its 30-digit mpmath reference table (tests/special/data/mpmath_table.rs,
//! produced by scripts/elliptic_reference.py) and where it occurs.
//!
//! `cargo run --release --example special_accuracy`. The bounds on these maxima are asserted
//! by the tests in tests/special/mpmath_reference.rs, which this example includes.

#[path = "../tests/special/mpmath_reference.rs"]
mod mpmath_reference;

fn main() {
    for worst in mpmath_reference::all() {
        println!("{worst}");
    }
}
