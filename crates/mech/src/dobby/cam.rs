//! The cam Γ of task 1 (analysis): a closed roller-centre curve.

use crate::curve::{Ellipse, PlaneCurve};
use crate::planar::Vec2;
use crate::spline::ClosedSpline;
use crate::{MechError, Result};
use std::sync::Arc;

/// A cam Γ given as its roller-centre curve (the curve traced by B).
#[derive(Debug, Clone)]
pub struct Cam {
    curve: Arc<dyn PlaneCurve>,
    label: String,
}

impl Cam {
    /// The paper's ellipse, eq. (12): `a = 0.366 m`, `b = 0.577 m`.
    pub fn paper() -> Self {
        Self::from_curve(Arc::new(Ellipse::PAPER), "ellipse a=0.366 m, b=0.577 m")
    }

    /// A centred ellipse `x = a cos p`, `y = b sin p` (m).
    pub fn ellipse(a_m: f64, b_m: f64) -> Result<Self> {
        let el = Ellipse::new(a_m, b_m)?;
        Ok(Self::from_curve(Arc::new(el), &format!("ellipse a={a_m} m, b={b_m} m")))
    }

    /// A closed curve through a point table (m), fitted by a periodic cubic spline in chord length.
    pub fn from_points(points: &[Vec2]) -> Result<Self> {
        let sp = ClosedSpline::new(points)?;
        let n = sp.points().len();
        Ok(Self::from_curve(Arc::new(sp), &format!("periodic cubic spline through {n} points")))
    }

    /// Any closed curve.
    pub fn from_curve(curve: Arc<dyn PlaneCurve>, label: &str) -> Self {
        Self { curve, label: label.to_string() }
    }

    /// The curve.
    pub fn curve(&self) -> &Arc<dyn PlaneCurve> {
        &self.curve
    }

    /// A human label.
    pub fn label(&self) -> &str {
        &self.label
    }
}

/// Largest coordinate of a point table (m), the same bound as the link lengths.
const MAX_COORD_M: f64 = 100.0;

/// Reads a point table: one point per line, at least two numeric columns, separated by commas,
/// semicolons or blanks; `#` starts a comment. A first non-numeric line is a header: the columns
/// named `x_m`/`y_m` (or `x`/`y`, or `b_x_m`/`b_y_m` as written by `dobby synthesize --csv`) are
/// used, else the first two. Values are metres, each within ±100 m (the range of the link lengths);
/// a table in millimetres is refused with that hint rather than read as a cam a thousand times too big.
pub fn parse_point_table(text: &str) -> Result<Vec<Vec2>> {
    let split = |l: &str| -> Vec<String> {
        l.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .map(|s| s.trim().to_string())
            .collect()
    };
    let mut cols = (0usize, 1usize);
    let mut pts = Vec::new();
    let mut seen_data = false;
    for (ln, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let fields = split(line);
        let numeric: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        if !seen_data && numeric.iter().any(|v| v.is_none()) {
            // Header line.
            let find = |names: &[&str]| fields.iter().position(|f| names.iter().any(|n| f.eq_ignore_ascii_case(n)));
            let x = find(&["x_m", "b_x_m", "x"]);
            let y = find(&["y_m", "b_y_m", "y"]);
            if let (Some(x), Some(y)) = (x, y) {
                cols = (x, y);
            }
            seen_data = true;
            continue;
        }
        seen_data = true;
        let get = |i: usize| -> Result<f64> {
            let v = numeric.get(i).copied().flatten().ok_or_else(|| MechError::PointTable {
                location: format!("line {}", ln + 1),
                reason: format!("column {} is missing or not a number: '{}'", i + 1, raw.trim()),
            })?;
            if !v.is_finite() {
                return Err(MechError::PointTable {
                    location: format!("line {}", ln + 1),
                    reason: "not a finite number".into(),
                });
            }
            if v.abs() > MAX_COORD_M {
                return Err(MechError::PointTable {
                    location: format!("line {}", ln + 1),
                    reason: format!(
                        "coordinate {v} in column {} is out of range: allowed −{MAX_COORD_M} … {MAX_COORD_M} m \
                         (the table is read in metres)",
                        i + 1
                    ),
                });
            }
            Ok(v)
        };
        pts.push(Vec2::new(get(cols.0)?, get(cols.1)?));
    }
    Ok(pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_tables_with_and_without_headers() {
        let t = "# cam\nphi2_deg,b_x_m,b_y_m\n0,1.0,2.0\n1, 3.0 ,4.0\n";
        assert_eq!(parse_point_table(t).unwrap(), vec![Vec2::new(1.0, 2.0), Vec2::new(3.0, 4.0)]);
        let t = "1 2\n3;4\n";
        assert_eq!(parse_point_table(t).unwrap(), vec![Vec2::new(1.0, 2.0), Vec2::new(3.0, 4.0)]);
        let e = parse_point_table("x_m,y_m\n1,2\n3,zz\n").unwrap_err().to_string();
        assert!(e.contains("line 3"), "{e}");
        let e = parse_point_table("x_m,y_m\n366,0\n").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("366") && e.contains("metres"), "{e}");
    }
}
