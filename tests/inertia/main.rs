//! Tests of the inertia layer: the body catalogue against independent integrations, the
//! paper's tensor views and its stated values (errata), and the inertia map.

#[path = "../support/mod.rs"]
#[macro_use]
mod support;
#[macro_use]
mod common;

mod api;
mod bad_input;
mod catalogue;
mod invariance;
mod map;
mod mesh;
mod monte_carlo;
mod paper_errata;
mod tensor_views;
