//! The turns of a repeat grouped by what happens in them, so that a quantity of one turn (its
//! clearance, its torque's square integrated) is computed once per distinct turn, not once per pick.
//!
//! What the frames do over a span `[360p + from, 360p + to]` of the main shaft depends only on
//! which frames are up at a few picks around `p`: [`Motion::frame`] at angle θ reads the picks
//! `q − 1` and `q`, `q` the move centre nearest θ. Two picks whose lifts agree over that window
//! see the same motion over the span (shifted by whole turns), so a draft repeated many times —
//! 10⁵ picks of a 48-pick point — has 48 distinct turns or fewer. The window is wide enough for
//! every frame's centre (crossing angle plus stagger), which the tests check against a direct
//! evaluation pick by pick.

use crate::{Motion, ShedMotion};

/// Picks grouped by the lifts of the window around each (see the module's text).
#[derive(Debug, Clone)]
pub(crate) struct Turns {
    /// The first pick of each class, in order of first appearance.
    pub first: Vec<usize>,
    /// Picks in each class.
    pub count: Vec<usize>,
    /// The class of each pick.
    pub of: Vec<u32>,
}

impl Turns {
    /// The picks of `motion` grouped by what the frames do over `[360p + from_deg, 360p + to_deg]`.
    pub fn new(motion: &Motion, from_deg: f64, to_deg: f64) -> Self {
        let (cmin, cmax) = (0..motion.frames())
            .map(|i| motion.centre0_deg(i))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(c), b.max(c)));
        Self::spanning(motion, from_deg, to_deg, cmin, cmax)
    }

    /// [`Turns::new`] for every motion whose frames' move centres (into pick 0) lie within
    /// `[cmin, cmax]` deg: a wider window, so a grouping that holds while a search moves them.
    pub fn spanning(motion: &Motion, from_deg: f64, to_deg: f64, cmin: f64, cmax: f64) -> Self {
        Self::by_key(motion.picks(), |p, key| lift_key(motion, p, from_deg, to_deg, cmin, cmax, key))
    }

    /// The picks of `motion` grouped by what its frames do over `[360p + from_deg, 360p + to_deg]`,
    /// as its [`ShedMotion::turn_key`] names it.
    pub fn of<M: ShedMotion + ?Sized>(motion: &M, from_deg: f64, to_deg: f64) -> Self {
        Self::by_key(motion.picks(), |p, key| motion.turn_key(p, from_deg, to_deg, key))
    }

    /// [`Turns::new`], or `None` once more than `cap` distinct turns are found (a repeat whose
    /// picks hardly repeat, worked out from rows instead: `crate::turn_rows`).
    pub fn new_within(motion: &Motion, from_deg: f64, to_deg: f64, cap: usize) -> Option<Self> {
        let (cmin, cmax) = (0..motion.frames())
            .map(|i| motion.centre0_deg(i))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(c), b.max(c)));
        Self::by_key_within(motion.picks(), cap, |p, key| lift_key(motion, p, from_deg, to_deg, cmin, cmax, key))
    }

    /// [`Turns::of`], or `None` once more than `cap` distinct turns are found.
    pub fn of_within<M: ShedMotion + ?Sized>(motion: &M, from_deg: f64, to_deg: f64, cap: usize) -> Option<Self> {
        Self::by_key_within(motion.picks(), cap, |p, key| motion.turn_key(p, from_deg, to_deg, key))
    }

    /// `picks` grouped by equal keys (`key(p, words)` appends pick `p`'s words).
    fn by_key(picks: usize, key_of: impl FnMut(usize, &mut Vec<u64>)) -> Self {
        match Self::by_key_within(picks, usize::MAX, key_of) {
            Some(t) => t,
            None => unreachable!("no cap"),
        }
    }

    /// [`Turns::by_key`], or `None` once more than `cap` classes are found.
    fn by_key_within(picks: usize, cap: usize, mut key_of: impl FnMut(usize, &mut Vec<u64>)) -> Option<Self> {
        let mut classes: loomkin_numeric::WordMap<Vec<u64>, usize> = Default::default();
        let (mut first, mut count) = (Vec::new(), Vec::new());
        let mut of = Vec::with_capacity(picks);
        let mut key = Vec::new();
        for p in 0..picks {
            key.clear();
            key_of(p, &mut key);
            let c = match classes.get(&key) {
                Some(&c) => c,
                None => {
                    if first.len() >= cap {
                        return None;
                    }
                    classes.insert(key.clone(), first.len());
                    first.push(p);
                    count.push(0);
                    first.len() - 1
                }
            };
            count[c] += 1;
            of.push(c as u32);
        }
        Some(Self { first, count, of })
    }
}

/// The words of pick `p`'s lifts over the picks a span `[360p + from_deg, 360p + to_deg]` reads,
/// every frame's move centre (into pick 0) within `[cmin, cmax]` deg: one bit a frame and a pick.
pub(crate) fn lift_key(
    motion: &Motion,
    p: usize,
    from_deg: f64,
    to_deg: f64,
    cmin: f64,
    cmax: f64,
    key: &mut Vec<u64>,
) {
    let frames = motion.frames();
    let (lo, hi) = if frames == 0 {
        (0, 0)
    } else {
        // The nearest centre to θ lies at q = round((θ − c)/360) picks; q − 1 and q are read.
        (((from_deg - cmax) / 360.0).floor() as i64 - 2, ((to_deg - cmin) / 360.0).ceil() as i64 + 1)
    };
    let bits = frames * (hi - lo + 1) as usize;
    let at = key.len();
    key.resize(at + bits.div_ceil(64).max(1), 0);
    let mut b = 0usize;
    for d in lo..=hi {
        for i in 0..frames {
            if motion.is_up(i, p as i64 + d) {
                key[at + b / 64] |= 1 << (b % 64);
            }
            b += 1;
        }
    }
}
