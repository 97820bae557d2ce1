//! A cycle at one speed: per-segment peaks from the laws' exact metrics, and samples; JSON keys
//! carry the cycle's unit (`stroke_m`, `peak_velocity_m_s` … or `stroke_rad`, `peak_velocity_rad_s` …).

use crate::{Cycle, CyclePoint, SegmentKind, StrokeUnit};
use loomkin_units::ShaftSpeed;
use serde::ser::{Serialize, SerializeMap, Serializer};

/// The peaks of one segment at one speed (SI: m, m/s, m/s², m/s³ or rad, rad/s, …).
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentPeaks {
    /// What the segment does.
    pub kind: SegmentKind,
    /// Start angle (deg).
    pub from_deg: f64,
    /// End angle (deg).
    pub to_deg: f64,
    /// The law's label (`None` for a dwell; `"-"` in JSON).
    pub law: Option<String>,
    /// Unsigned stroke `h` (m or rad).
    pub stroke: f64,
    /// Peak |velocity| `h·Cv·ω/β`, with `ω` the shaft speed (rad/s) and `β` the segment angle (rad).
    pub peak_velocity: f64,
    /// Peak |acceleration| `h·Ca·(ω/β)²`.
    pub peak_acceleration: f64,
    /// Peak |jerk| `h·Cj·(ω/β)³`.
    pub peak_jerk: f64,
    /// The cycle's unit (names the JSON keys).
    pub unit: StrokeUnit,
}

/// A cycle at one speed: timing, per-segment peaks and samples (`loomkin cycle --json`).
#[derive(Debug, Clone, PartialEq)]
pub struct CycleReport {
    /// Main-shaft speed (rpm).
    pub speed_rpm: f64,
    /// Cycle angle (deg).
    pub period_deg: f64,
    /// Duration of one cycle (s).
    pub cycle_time_s: f64,
    /// The cycle's unit.
    pub unit: StrokeUnit,
    /// Peaks of every segment.
    pub segments: Vec<SegmentPeaks>,
    /// Samples over the cycle.
    pub samples: Vec<CyclePoint>,
}

/// Where a cycle's velocity and acceleration reach their extremes at one speed: main-shaft angle
/// (deg) and value (SI), each at the location its law's metrics root-found (not on a grid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleExtremes {
    /// Largest |velocity|: angle and signed value.
    pub velocity: (f64, f64),
    /// Largest acceleration: angle and value.
    pub acceleration_max: (f64, f64),
    /// Smallest (most negative) acceleration: angle and value.
    pub acceleration_min: (f64, f64),
}

impl Cycle {
    /// The extremes of velocity and acceleration over the cycle at `speed`, `None` for a cycle of
    /// dwells only. Each moving segment is evaluated at its law's `x_cv`, `x_ca_pos`, `x_ca_neg`.
    pub fn extremes(&self, speed: ShaftSpeed) -> Option<CycleExtremes> {
        let omega = speed.rpm() * std::f64::consts::TAU / 60.0;
        let mut out: Option<CycleExtremes> = None;
        for seg in &self.segments {
            let Some((_, law)) = &seg.law else { continue };
            let m = law.metrics();
            let r = omega / seg.length_rad;
            let h = seg.stroke_si;
            let at = |x: f64| {
                let k = law.eval(x);
                ((seg.start_rad + x * seg.length_rad).to_degrees(), h * k.v * r, h * k.a * r * r)
            };
            let (dv, v, _) = at(m.x_cv);
            let (dp, _, ap) = at(m.x_ca_pos);
            let (dn, _, an) = at(m.x_ca_neg);
            // A return has the stroke's sign reversed: the law's largest positive acceleration is the
            // cycle's most negative one.
            let (hi, lo) = if ap >= an { ((dp, ap), (dn, an)) } else { ((dn, an), (dp, ap)) };
            let e = out.get_or_insert(CycleExtremes { velocity: (dv, v), acceleration_max: hi, acceleration_min: lo });
            if v.abs() > e.velocity.1.abs() {
                e.velocity = (dv, v);
            }
            if hi.1 > e.acceleration_max.1 {
                e.acceleration_max = hi;
            }
            if lo.1 < e.acceleration_min.1 {
                e.acceleration_min = lo;
            }
        }
        out
    }

    /// Per-segment peaks at `speed_rpm` from each law's exact metrics (Cv, Ca, Cj) and the chain
    /// rule; dwells have zero peaks.
    pub fn segment_peaks(&self, speed: ShaftSpeed) -> Vec<SegmentPeaks> {
        // ω as `rpm·2π/60` (not `rpm·(2π/60)`): the figures stay bit for bit what the CLI printed.
        let omega = loomkin_units::rad_per_s_from_rpm(speed.rpm());
        self.segments
            .iter()
            .map(|s| {
                let (law, pv, pa, pj) = match &s.law {
                    Some((spec, law)) => {
                        let m = law.metrics();
                        let r = omega / s.length_rad;
                        let h = s.stroke_si.abs();
                        (Some(spec.label()), h * m.cv * r, h * m.ca * r * r, h * m.cj * r * r * r)
                    }
                    None => (None, 0.0, 0.0, 0.0),
                };
                SegmentPeaks {
                    kind: s.kind,
                    from_deg: s.start_rad.to_degrees(),
                    to_deg: (s.start_rad + s.length_rad).to_degrees(),
                    law,
                    stroke: s.stroke_si.abs(),
                    peak_velocity: pv,
                    peak_acceleration: pa,
                    peak_jerk: pj,
                    unit: self.unit,
                }
            })
            .collect()
    }

    /// The report at `speed` with `n` samples over the cycle.
    pub fn report(&self, speed: ShaftSpeed, n: usize) -> CycleReport {
        CycleReport {
            speed_rpm: speed.rpm(),
            period_deg: self.period_rad.to_degrees(),
            cycle_time_s: self.period_rad / loomkin_units::rad_per_s_from_rpm(speed.rpm()),
            unit: self.unit,
            segments: self.segment_peaks(speed),
            samples: self.sample(n, speed.rpm()),
        }
    }

    /// [`Cycle::report`] with its `n` samples made while it is serialised (see [`StreamedReport`]).
    pub fn report_streamed<F: Fn()>(&self, speed: ShaftSpeed, n: usize, tick: F) -> StreamedReport<'_, F> {
        StreamedReport { head: self.report(speed, 0), cycle: self, n, tick }
    }
}

impl Serialize for SegmentPeaks {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let [pu, vu, au, ju] = self.unit.key_units();
        let mut m = s.serialize_map(Some(8))?;
        m.serialize_entry("kind", &self.kind)?;
        m.serialize_entry("from_deg", &self.from_deg)?;
        m.serialize_entry("to_deg", &self.to_deg)?;
        m.serialize_entry("law", self.law.as_deref().unwrap_or("-"))?;
        m.serialize_entry(&format!("stroke_{pu}"), &self.stroke)?;
        m.serialize_entry(&format!("peak_velocity_{vu}"), &self.peak_velocity)?;
        m.serialize_entry(&format!("peak_acceleration_{au}"), &self.peak_acceleration)?;
        m.serialize_entry(&format!("peak_jerk_{ju}"), &self.peak_jerk)?;
        m.end()
    }
}

/// One sample with its keys ([`StrokeUnit::sample_keys`], made once per report).
struct UnitPoint<'k>(CyclePoint, &'k [String; 6]);

impl Serialize for UnitPoint<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (p, keys) = (&self.0, self.1);
        let mut m = s.serialize_map(Some(6))?;
        for (k, v) in keys.iter().zip([p.angle_deg, p.time_s, p.kin.s, p.kin.v, p.kin.a, p.kin.j]) {
            m.serialize_entry(k, &v)?;
        }
        m.end()
    }
}

impl Serialize for CycleReport {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serialize_report(self, self.samples.iter().copied(), s)
    }
}

/// The report's fields, then `samples` written as `points` makes them.
fn serialize_report<S: Serializer>(
    r: &CycleReport,
    points: impl Iterator<Item = CyclePoint>,
    s: S,
) -> Result<S::Ok, S::Error> {
    let mut m = s.serialize_map(Some(6))?;
    m.serialize_entry("speed_rpm", &r.speed_rpm)?;
    m.serialize_entry("period_deg", &r.period_deg)?;
    m.serialize_entry("cycle_time_s", &r.cycle_time_s)?;
    m.serialize_entry("unit", r.unit.si_units()[0])?;
    m.serialize_entry("segments", &r.segments)?;
    let keys = r.unit.sample_keys();
    m.serialize_entry("samples", &Points(std::cell::RefCell::new(Some(points.map(|p| UnitPoint(p, &keys))))))?;
    m.end()
}

/// Samples serialised as an array as they are made (once).
struct Points<I>(std::cell::RefCell<Option<I>>);

impl<'k, I: Iterator<Item = UnitPoint<'k>>> Serialize for Points<I> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.borrow_mut().take().into_iter().flatten())
    }
}

/// A [`CycleReport`] whose samples are made as it is serialised, one at a time: nothing is held
/// per sample, so `loomkin cycle --points 10000000 --json` needs a buffer, not the table. The
/// text is the [`CycleReport`]'s byte for byte. `tick` is called once per sample written (a
/// progress count).
pub struct StreamedReport<'a, F: Fn()> {
    head: CycleReport,
    cycle: &'a Cycle,
    n: usize,
    tick: F,
}

impl<F: Fn()> Serialize for StreamedReport<'_, F> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let points = self.cycle.samples(self.n, self.head.speed_rpm).inspect(|_| (self.tick)());
        serialize_report(&self.head, points, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = r#"
unit = "mm"
stroke = 80
[[segment]]
kind = "rise"
to_deg = 120
law = "cycloidal"
[[segment]]
kind = "dwell"
to_deg = 180
[[segment]]
kind = "return"
to_deg = 300
law = "poly345"
[[segment]]
kind = "dwell"
to_deg = 360
"#;

    #[test]
    fn peaks_match_the_sampled_cycle_and_name_their_units() {
        let c = Cycle::from_toml(FILE).unwrap();
        let speed = ShaftSpeed::from_rpm(400.0).unwrap();
        let r = c.report(speed, 20_001);
        assert_eq!(r.segments.len(), 4);
        // Independent route: the largest sampled |v|, |a| over each moving segment approaches
        // the closed-form peak from below.
        for p in r.segments.iter().filter(|p| p.law.is_some()) {
            let inside = r.samples.iter().filter(|s| s.angle_deg >= p.from_deg && s.angle_deg <= p.to_deg);
            let (v, a) = inside.fold((0.0f64, 0.0f64), |(v, a), s| (v.max(s.kin.v.abs()), a.max(s.kin.a.abs())));
            assert!(v <= p.peak_velocity * (1.0 + 1e-9) && v > p.peak_velocity * (1.0 - 1e-4), "{v} {p:?}");
            assert!(a <= p.peak_acceleration * (1.0 + 1e-9) && a > p.peak_acceleration * (1.0 - 1e-3), "{a} {p:?}");
        }
        // Cycloidal rise over 120° at 400 rpm: Cv = 2, so v_max = h·2·ω/β.
        let omega = 400.0 * std::f64::consts::TAU / 60.0;
        let expected = 0.08 * 2.0 * omega / 120f64.to_radians();
        assert!((r.segments[0].peak_velocity - expected).abs() < 1e-12 * expected);
        let v = serde_json::to_value(&r).unwrap();
        assert_eq!(v["unit"], "m");
        assert_eq!(v["segments"][1]["law"], "-");
        assert!(v["segments"][0]["peak_acceleration_m_s2"].is_f64());
        // The located extremes agree with the per-segment peaks and with the densest sample.
        let e = c.extremes(speed).unwrap();
        let vmax = r.segments.iter().map(|p| p.peak_velocity).fold(0.0, f64::max);
        assert!((e.velocity.1.abs() - vmax).abs() < 1e-12 * vmax);
        let amax = r.samples.iter().map(|s| s.kin.a).fold(f64::NEG_INFINITY, f64::max);
        let amin = r.samples.iter().map(|s| s.kin.a).fold(f64::INFINITY, f64::min);
        assert!(e.acceleration_max.1 >= amax && e.acceleration_max.1 < amax + 1e-3 * amax.abs());
        assert!(e.acceleration_min.1 <= amin && e.acceleration_min.1 > amin - 1e-3 * amin.abs());
        let sampled = c.eval(e.velocity.0.to_radians(), 400.0);
        assert!((sampled.v - e.velocity.1).abs() < 1e-9 * vmax, "the angle is where the value is");
        assert!(v["samples"][0]["j_m_s3"].is_f64());
        assert!((v["cycle_time_s"].as_f64().unwrap() - 0.15).abs() < 1e-15);
        // The streamed report is the same text, and counts its samples.
        let count = std::cell::Cell::new(0);
        let streamed = c.report_streamed(speed, 20_001, || count.set(count.get() + 1));
        assert_eq!(serde_json::to_string(&streamed).unwrap(), serde_json::to_string(&r).unwrap());
        assert_eq!(count.get(), 20_001);
    }
}
