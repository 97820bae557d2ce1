//! # loomkin-dynamics — elastic follower dynamics at speed
//!
//! A follower train (a heald frame on its drive) as a mass on a spring and damper, driven through
//! a law (base excitation), solved **exactly**: every law segment is a polynomial plus a sinusoid in
//! time, so the forced response of a linear oscillator is closed form per segment (particular plus
//! damped free vibration, matched at the joints), for any number of cycles or directly in the
//! periodic steady state. From it: the dynamic error, the residual vibration in every dwell, peak
//! acceleration and force located by root finding, the VDI 2149 rigidity ratio, speed sweeps,
//! residual-vibration spectra of laws, compensated (polydyne) input laws and laws shaped for quiet
//! dwells over a speed band.
//!
//! ```
//! use loomkin_dynamics::{Follower, Response, Start};
//! use loomkin_laws::Cycle;
//! use loomkin_units::ShaftSpeed;
//!
//! let cycle = Cycle::from_toml(r#"
//!     unit = "mm"
//!     stroke = 100
//!     [[segment]]
//!     kind = "rise"
//!     to_deg = 120
//!     law = "cycloidal"
//!     [[segment]]
//!     kind = "dwell"
//!     to_deg = 180
//!     [[segment]]
//!     kind = "return"
//!     to_deg = 300
//!     law = "cycloidal"
//!     [[segment]]
//!     kind = "dwell"
//!     to_deg = 360
//! "#)?;
//! // 600 rpm: the rise lasts 1/30 s; at f_n = 60 Hz that is exactly 2 natural periods, where the
//! // cycloidal law leaves no residual vibration (undamped).
//! let follower = Follower::new(60.0, 0.0)?;
//! let r = Response::new(&cycle, ShaftSpeed::from_rpm(600.0)?, &follower, Start::Rest, 1)?;
//! let first_dwell = r.dwell_residuals()[0];
//! assert!(first_dwell.amplitude_si < 1e-12);
//! assert!(r.summary().rigidity_warning); // 60 Hz < 10 × 10 Hz
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

mod compensate;
mod complex;
mod error;
mod excitation;
mod follower;
mod optimize;
mod oscillator;
mod peaks;
mod report;
mod response;
mod spectrum;
mod sweep;
mod trajectory;
mod twomass;

pub use compensate::{Compensation, InputPiece, compensate, input_excitation};
pub use error::{DynError, Result};
pub use excitation::{Excitation, TimePiece};
pub use follower::{Follower, STANDARD_GRAVITY};
pub use optimize::{
    CA_LIMIT_OF_MODIFIED_SINE, Optimized, PIECES, SMOOTHING, SegmentFigures, optimize_cycle, optimize_cycle_with,
    quiet_law,
};
pub use oscillator::{Forcing, Harmonic, NCOEF, NSERIES, Oscillator, PieceSolution, free_roots, series_below};
pub use peaks::{Extremes, grid_size};
pub use report::{
    OptimizeReport, ResponseReport, SweepEntry, SweepReport, TwoMassReport, Units, start_name, sweep_columns, sweep_row,
};
pub use response::{DwellResidual, Located, Response, Summary, VDI_2149_MIN_RATIO};
pub use spectrum::{DEFAULT_RATIOS, RATIO, RATIOS, cycloidal_undamped, default_ratios, residual_ratio, spectrum};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    Follower::NATURAL_HZ,
    Follower::DAMPING_RATIO,
    Follower::MASS_KG,
    Follower::RETURN_SPRING_N_M,
    Follower::CLOSING_FORCE_N,
    Follower::PRELOAD_N,
    Follower::FORCE_N,
    Response::CYCLES,
    Response::POINTS,
    Compensation::POINTS,
    Optimized::BAND_PCT,
    SweepPoint::SPEEDS,
    SweepPoint::RESIDUAL_LIMIT_PCT,
    RATIO,
    RATIOS,
];
pub use sweep::{SweepPoint, speeds_above, sweep, sweep_point};
pub use trajectory::{Channel, Solved, Start, steady_state, trajectory};
pub use twomass::TwoMass;
