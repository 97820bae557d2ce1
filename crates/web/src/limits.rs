//! Bounds on what one request may ask for.

/// Largest request body accepted, in bytes (256 KiB); larger bodies get 413.
pub const MAX_BODY_BYTES: usize = 256 * 1024;

/// Fewest samples of a law a request may ask for.
pub const MIN_SAMPLES: usize = 2;

/// Most samples of a law a request may ask for (a sample count above this gets 422).
pub const MAX_SAMPLES: usize = 5000;

/// Samples used when a request does not say.
pub const DEFAULT_SAMPLES: usize = 1000;

/// Samples over one turn when a request does not say: every half degree, ends included.
pub const DEFAULT_CYCLE_SAMPLES: usize = 721;

/// Samples over one pick when a request does not say.
pub const DEFAULT_PICK_SAMPLES: usize = 400;

/// Fewest rows of a servo cam table over a turn (a 90° step).
pub const MIN_CAM_ROWS: usize = 5;

/// Rows of a servo cam table when a request does not say: a 1° step over the turn.
pub const DEFAULT_CAM_ROWS: usize = 361;

/// Most laws compared at once in the catalogue view.
pub const MAX_COMPARE: usize = 8;

/// Most main-shaft speeds and definition points of a servo design: the servo crate's bounds.
pub use loomkin_servo::{MAX_DEF_POINTS, MAX_SPEEDS};

/// Most rows of an exported cam table.
pub const MAX_CAM_ROWS: usize = 100_000;
