//! Integration tests of loomkin-dynamics: the closed form against numerical integration and
//! against known closed forms.

#[path = "cases/compensate.rs"]
mod compensate;
#[path = "cases/continuity.rs"]
mod continuity;
#[path = "cases/ode.rs"]
mod ode;
