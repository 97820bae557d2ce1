//! A TwinCAT-style motion-function point list: the fields of Beckhoff's `MC_MotionFunctionPoint`
//! (Tc2_MC2_Camming / TF5050 NC Camming), one point a line.
//!
//! `FunctionType` is the type of the segment from this point to the next:
//! `MOTIONFUNCTYPE_POLYNOM5_MM` (5, "polynom with order 5, motion ↔ motion": the quintic through
//! position, velocity and acceleration at both ends — the interpolation the reported error is
//! computed for), `MOTIONFUNCTYPE_POLYNOM1` where the slave stands still (both ends at the same
//! position with zero velocity and acceleration, where the quintic is that constant), and
//! `MOTIONFUNCTYPE_NOTDEF` after the last point. `PointIndex` counts from 1 and
//! `RelIndexNextPoint` is 1 (0 at the last point).
//!
//! ```text
//! # loomkin cam table: …
//! PointIndex,FunctionType,RelIndexNextPoint,MasterPos,SlavePos,SlaveVelo,SlaveAcc,SlaveJerk
//! 1,MOTIONFUNCTYPE_POLYNOM5_MM,1,0,0.0000,0.000000,0.00000000,0.004112
//! ```

use super::decimals::fixed;
use super::format::{numbers, points_from_rows};
use super::{CamPoint, CamTable};
use crate::{CamError, Result};
use loomkin_io::csv::CsvText;

/// The column header.
pub const HEADER: &str = "PointIndex,FunctionType,RelIndexNextPoint,MasterPos,SlavePos,SlaveVelo,SlaveAcc,SlaveJerk";

/// The function types written.
pub const FUNCTION_TYPES: [&str; 3] =
    ["MOTIONFUNCTYPE_POLYNOM5_MM", "MOTIONFUNCTYPE_POLYNOM1", "MOTIONFUNCTYPE_NOTDEF"];

fn function_type(p: &CamPoint, next: Option<&CamPoint>) -> &'static str {
    match next {
        None => FUNCTION_TYPES[2],
        Some(q) if p.y == q.y && p.v == 0.0 && p.a == 0.0 && q.v == 0.0 && q.a == 0.0 => FUNCTION_TYPES[1],
        Some(_) => FUNCTION_TYPES[0],
    }
}

/// Writes the point list.
pub fn write(table: &CamTable, header: &[String]) -> String {
    let d = table.decimals();
    let u = table.unit_name();
    let units = format!(
        "MasterPos in deg, SlavePos in {u}, SlaveVelo in {u}/deg, SlaveAcc in {u}/deg^2, SlaveJerk in {u}/deg^3"
    );
    let comments: Vec<&str> = header.iter().map(String::as_str).chain([units.as_str()]).collect();
    let mut t = CsvText::new(&comments, &HEADER.split(',').collect::<Vec<_>>());
    let pts = table.points();
    for (i, p) in pts.iter().enumerate() {
        let next = pts.get(i + 1);
        t.push([
            (i + 1).to_string(),
            function_type(p, next).to_string(),
            usize::from(next.is_some()).to_string(),
            fixed(p.master_deg, d.master),
            fixed(p.y, d.y),
            fixed(p.v, d.v),
            fixed(p.a, d.a),
            fixed(p.j, d.j),
        ]);
    }
    t.finish()
}

/// Reads the points back (every segment type is interpolated as the quintic through the ends'
/// position, velocity and acceleration, which a POLYNOM1 dwell segment also is).
pub fn read(text: &str) -> Result<Vec<CamPoint>> {
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') || l.starts_with("PointIndex") {
            continue;
        }
        let ty = l.split(',').nth(1).unwrap_or("").trim();
        if !FUNCTION_TYPES.contains(&ty) {
            return Err(CamError::Parse {
                field: format!("line {}", i + 1),
                reason: format!("unknown FunctionType '{ty}'"),
            });
        }
        rows.push(numbers(l, 5, i, 3)?);
    }
    points_from_rows(rows)
}
