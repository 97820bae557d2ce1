//! # loomkin-study — experiment tables, parallel evaluation, Pareto fronts
//!
//! Generic tools for studies of many variants: experiment [`Design`]s (explicit tables, stepped
//! axes, Cartesian grids and simplex grids of relative lengths `k_T1 … k_Tn` with `Σ k = 1`),
//! parallel evaluation with a progress bar that appears only on a terminal, non-dominated sorting
//! and the Pareto front, the constrained optimum, and for Monte-Carlo studies reproducible draws
//! from stated [`Distribution`]s ([`uniform`]: any draw computed alone), the [`Summary`] of a
//! result (percentiles, histogram, share failing a [`Limit`]), and the Monte-Carlo runner and
//! report every such study shares ([`run_draws`], [`tally`]); the parts of a sharded run on disk
//! ([`parts`]: manifests, the check, the merge) and the reduce of a Monte-Carlo run's per-draw
//! table at any size ([`draws`]) or of its shards' mergeable summaries ([`summary`]).
//!
//! ```
//! use loomkin_study::{Design, Progress, Sense, argmin_subject_to, evaluate_design, pareto_front};
//!
//! // Three relative lengths on a 0.1 grid, each at least 0.1, summing to one.
//! let design = Design::simplex(3, 0.1, 0.8, 0.1)?;
//! assert_eq!(design.len(), 36);
//! // Two made-up objectives per row: (k1, 1 − k1·k2).
//! let objs = evaluate_design(&design, Progress::Hidden, "toy", |k| [k[0], 1.0 - k[0] * k[1]]);
//! let front = pareto_front(&objs, &[Sense::Maximize, Sense::Minimize])?;
//! assert!(!front.is_empty());
//! // Least second objective among rows with k1 ≥ 0.3.
//! let best = argmin_subject_to(&objs, |o| o[1], |o| o[0] >= 0.3).unwrap();
//! assert!(objs[best][0] >= 0.3);
//! # Ok::<(), loomkin_study::StudyError>(())
//! ```
#![deny(missing_docs)]

mod design;
pub mod draws;
mod error;
mod eval;
mod montecarlo;
mod optimum;
mod pareto;
pub mod parts;
mod random;
mod stats;
pub mod summary;

pub use design::{Design, MAX_POINTS, simplex_rows, stepped_axis};
pub use error::{Result, StudyError};
pub use eval::{Progress, evaluate, evaluate_design, evaluate_indexed, evaluate_indexed_until};
pub use montecarlo::{
    DEFAULT_BINS, DrawEntry, DrawRow, Drawn, MAX_BINS, Named, Reported, Tally, check_plan, run_draws, tally,
};
pub use optimum::argmin_subject_to;
pub use pareto::{Sense, StreamFront, dominates, non_dominated_ranks, pareto_front};
pub use random::{DistSpec, DistTable, Distribution, MAX_VARIABLES, normal_cdf, normal_pdf, normal_quantile, uniform};
pub use stats::{DEFAULT_PERCENTILES, Histogram, Limit, Percentile, Summary, interpolate, percentile, percentile_rank};
