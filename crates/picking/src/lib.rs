//! # loomkin-picking — shuttle picking dynamics of an elastic under-pick mechanism
//!
//! After M. Jederán (1959). The picking mechanism is elastic: the shuttle's actual motion x
//! differs from the cam's nominal motion s by the deflection f = B·ẍ + C·x + D, so
//!
//! B·ẍ + (C + 1)·x = s − D  (eq. 5; B in s², C dimensionless, D in m).
//!
//! The cam is designed for a compound law (ẍ = A·sin μt, then ẍ = A) that gives the shuttle the
//! velocity V over the distance X ([`Design`], eqs. 18–20). When the loom is set differently —
//! speed, strap play, strap position k, shuttle weight, checking force ([`Settings`]) — the
//! actual motion is found by the paper's closed form (corrected) or by numerical integration
//! ([`Method`]); [`simulate`] returns the end-of-pick values, [`sweep`] runs a setting over a
//! range in parallel.
//!
//! ```
//! use loomkin_picking::{Mechanism, Method, Settings, simulate};
//!
//! let mech = Mechanism::paper_default();
//! let d = mech.design();
//! assert!((d.a_m_s2 - 690.0).abs() < 0.5 && (d.t_end_s - 0.033).abs() < 1e-4);
//!
//! // At the designed setting the shuttle leaves at V = 17 m/s after X = 0.22 m.
//! let st = Settings::designed(&mech);
//! let o = simulate(&mech, &st, Method::Closed)?;
//! assert!((o.velocity_m_s - 17.0).abs() < 1e-9 && (o.distance_m - 0.22).abs() < 1e-10);
//!
//! // 15.5 mm of strap play: the paper's Fig. 3 (+3.88 m/s).
//! let played = st.with_play_mm(15.5);
//! let closed = simulate(&mech, &played, Method::Closed)?;
//! let ode = simulate(&mech, &played, Method::Ode)?;
//! assert!((closed.velocity_m_s / ode.velocity_m_s - 1.0).abs() < 1e-7);
//! assert!((closed.velocity_m_s - 17.0 - 3.88).abs() < 0.05);
//! # Ok::<(), loomkin_picking::PickError>(())
//! ```
#![deny(missing_docs)]

mod cam;
mod closed;
mod design;
mod error;
mod mechanism;
pub mod montecarlo;
mod ode;
mod params;
mod required;
mod scenario;
mod settings;
mod simulate;
mod sweep;
pub mod units;

pub use cam::Cam;
pub use closed::{CANCELLATION_LIMIT, PaperConstants, RESONANCE_GAP};
pub use design::{Design, DesignSpec, Nominal, State};
pub use error::{PickError, Result};
pub use mechanism::{DesignReport, Mechanism};
pub use montecarlo::MonteCarlo;
pub use ode::{ODE_ATOL, ODE_RTOL, integrate};
pub use params::{Constants, Params};
pub use required::RequiredVelocity;
pub use scenario::{MAX_CYCLES, MAX_NATURAL_1_S};
pub use settings::{Setting, Settings, StartRule};
pub use simulate::{History, Method, Outcome, PickEnd, Sample, closed_form_constants, history, simulate};
/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    Settings::SPEED_RPM,
    Settings::PLAY_MM,
    Settings::STRAP_CM,
    Settings::SHUTTLE_G,
    Settings::CHECKING_KGF,
    History::POINTS,
    History::PLOT_POINTS,
    Sweep::POINTS,
    Sweep::HELD_POINTS,
    DesignSpec::VELOCITY_M_S,
    DesignSpec::DISTANCE_M,
    DesignSpec::FIRST_STAGE_M,
    DesignSpec::SPEED_RPM,
    RequiredVelocity::RETARDATION_PCT,
    RequiredVelocity::PATH_M,
    RequiredVelocity::FREE_SHED_DEG,
];

pub use sweep::{
    RowReport, SettingValue, Sweep, SweepReport, SweepRow, required_velocity_crossings, sweep, sweep_items,
    sweep_observed,
};
