//! Tests of the Clifford-algebra layer, one module per part of `src/algebra`.

#[path = "../support/mod.rs"]
mod support;

mod bivector;
mod cga;
mod decompose;
mod exp_log;
mod fixed;
mod fixed_api;
mod multivector;
mod nalgebra_interop;
mod outermorphism;
mod pga;
mod product_table;
mod properties;
mod rotor;
mod typed_objects;
mod versor_general;
mod versor_reference;
mod versor_sqrt;
mod versors;
