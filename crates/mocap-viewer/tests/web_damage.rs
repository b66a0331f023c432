//! The web painter's damage tracking (`vendor/eframe/src/web/damage.rs`: which
//! parts of the window a frame redraws) is compiled into eframe for wasm32
//! only; this runs its unit tests natively, where `cargo test --workspace`
//! reaches them.

#[allow(dead_code)]
#[path = "../../../vendor/eframe/src/web/damage.rs"]
mod damage;
