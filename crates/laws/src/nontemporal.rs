//! Stores of sampled records that bypass the caches, for tables far larger than the caches.
//!
//! An ordinary store to a cache line that is not in the cache first reads that line from memory
//! (read-for-ownership), so writing a large table once costs twice its size in memory traffic. A
//! non-temporal store (`movntpd`, part of SSE2 and so of every x86-64 CPU) writes the line without
//! reading it and without displacing the caches. On the 2-core machine of issue 15 a loop storing
//! 10⁷ 32-byte records reached 213–223 M records/s with ordinary stores and 436–478 M/s with
//! non-temporal ones (idle, 25 alternated calls each; `memset` of the same 320 MB: 299–326 M/s).
//! For a table that stays in the cache (and is read right after) ordinary stores are faster, hence
//! the size threshold [`MIN_BYTES`].
//!
//! This module is the one place in the workspace that uses `unsafe`: the intrinsics take raw
//! pointers. Everything here is sound for every input — the functions check the alignment the
//! instruction needs themselves and fall back to ordinary stores — and on other architectures
//! they are ordinary stores.
#![allow(unsafe_code)]

use crate::Kinematics;

/// Tables of at least this many bytes are written with non-temporal stores: a core's level-2 cache
/// (4 MiB on the issue-15 machine, 1–2 MiB on most desktop cores), beyond which the table cannot
/// still be in the nearest caches when the caller reads it. Measured on the issue-15 machine
/// (cycloidal, `sample_grid_sizes` bench, medians): 10⁵ points (3.2 MB) 650 M points/s with
/// ordinary stores against 615 non-temporal; 3·10⁵ (9.6 MB) 480 against 610; 10⁶ 470 against
/// 610; 3·10⁶ 193 against 525.
pub(crate) const MIN_BYTES: usize = 4 << 20;

/// Whether `out` is large enough for non-temporal stores to pay, on an architecture that has them.
pub(crate) fn worth_it(out: &[Kinematics]) -> bool {
    cfg!(target_arch = "x86_64") && std::mem::size_of_val(out) >= MIN_BYTES
}

/// Four records given lane by lane (`s[l]`, `v[l]`, `a[l]`, `j[l]` is record `l`) into `quad`
/// (four records) with non-temporal stores where the target and the alignment allow, else with
/// ordinary stores. Call [`fence`] after the last of a table's non-temporal stores.
#[inline(always)]
pub(crate) fn put4(quad: &mut [Kinematics], s: [f64; 4], v: [f64; 4], a: [f64; 4], j: [f64; 4]) {
    let quad: &mut [Kinematics; 4] = quad.try_into().expect("four records");
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_set_pd, _mm_stream_pd};
        let p = quad.as_mut_ptr().cast::<f64>();
        if (p as usize).is_multiple_of(16) {
            for l in 0..4 {
                // SAFETY: `p` points to four `Kinematics` (`quad`, borrowed mutably, so nothing else
                // reads or writes them meanwhile), each four `f64` in the order s, v, a, j
                // (`repr(C)`), so `p.add(4l)` and `p.add(4l + 2)` stay within the 128 bytes of `quad`,
                // and both are 16-byte aligned since `p` is (checked above) and `Kinematics` is
                // 32 bytes. SSE2, which `_mm_stream_pd` needs, is part of every x86-64 target.
                unsafe {
                    _mm_stream_pd(p.add(4 * l), _mm_set_pd(v[l], s[l]));
                    _mm_stream_pd(p.add(4 * l + 2), _mm_set_pd(j[l], a[l]));
                }
            }
            return;
        }
    }
    for l in 0..4 {
        quad[l] = Kinematics { s: s[l], v: v[l], a: a[l], j: j[l] };
    }
}

/// Orders the non-temporal stores made so far before any later store of this thread (`sfence`),
/// so that a table handed to another thread afterwards is seen complete. A no-op elsewhere.
#[inline]
pub(crate) fn fence() {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `sfence` has no operands and no preconditions (SSE, part of every x86-64 target).
    unsafe {
        std::arch::x86_64::_mm_sfence();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_are_laid_out_s_v_a_j() {
        assert_eq!(std::mem::size_of::<Kinematics>(), 32);
        assert_eq!(std::mem::offset_of!(Kinematics, s), 0);
        assert_eq!(std::mem::offset_of!(Kinematics, v), 8);
        assert_eq!(std::mem::offset_of!(Kinematics, a), 16);
        assert_eq!(std::mem::offset_of!(Kinematics, j), 24);
    }

    /// `put4` writes the lanes as records both where it stores non-temporally (a 16-byte aligned quad) and where
    /// it falls back to ordinary stores (a quad 8 bytes past a 16-byte boundary).
    #[test]
    fn put4_writes_the_lanes_as_records_at_either_alignment() {
        #[repr(C, align(16))]
        struct Aligned {
            k: [Kinematics; 4],
        }
        #[repr(C, align(16))]
        struct Shifted {
            pad: f64,
            k: [Kinematics; 4],
        }
        let lanes = |k: usize| std::array::from_fn::<f64, 4, _>(|l| (10 * k + l) as f64 + 0.5);
        let (s, v, a, j) = (lanes(1), lanes(2), lanes(3), lanes(4));
        let want: [Kinematics; 4] = std::array::from_fn(|l| Kinematics { s: s[l], v: v[l], a: a[l], j: j[l] });

        let mut aligned = Aligned { k: [Kinematics::default(); 4] };
        assert_eq!(aligned.k.as_ptr() as usize % 16, 0);
        put4(&mut aligned.k, s, v, a, j);
        fence();
        assert_eq!(aligned.k, want);

        let mut shifted = Shifted { pad: 0.0, k: [Kinematics::default(); 4] };
        assert_eq!(shifted.k.as_ptr() as usize % 16, 8);
        put4(&mut shifted.k, s, v, a, j);
        fence();
        assert_eq!((shifted.pad, shifted.k), (0.0, want));
    }
}
