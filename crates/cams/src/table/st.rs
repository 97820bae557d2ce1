//! IEC 61131-3 Structured Text: a global `ARRAY[0..N] OF SMC_CAMXYVA` initialiser to paste into
//! a CODESYS SoftMotion project (library SM3_Basic).
//!
//! `SMC_CAMXYVA` is the XYVA point of a CODESYS cam (`SMC_CAM_TYPE.XYVA`: master position `dX`,
//! slave position `dY`, slave velocity `dV` and acceleration `dA`, all with respect to the master,
//! joined by fifth-degree polynomials); an `MC_CAM_REF` with `byType := 3` points at the array
//! (`pce := ADR(…)`, `nElements := N + 1`, `xStart`, `xEnd`). The jerk is not part of the
//! structure and is written as a comment on each line.
//!
//! ```text
//! VAR_GLOBAL
//!     LoomkinCam : ARRAY[0..72] OF SMC_CAMXYVA := [
//!         (dX := 0.0, dY := 0.0000, dV := 0.000000, dA := 0.00000000), (* J = 0.004112 *)
//!         …
//!     ];
//! END_VAR
//! ```

use super::decimals::fixed;
use super::format::points_from_rows;
use super::{CamPoint, CamTable};
use crate::{CamError, Result};

/// The name of the array written.
pub const ARRAY_NAME: &str = "LoomkinCam";

/// A number as an ST real literal: fixed decimals, at least one (`0.0`, never `0`).
fn real(x: f64, d: usize) -> String {
    fixed(x, d.max(1))
}

/// Writes the source.
pub fn write(table: &CamTable, header: &[String]) -> String {
    let d = table.decimals();
    let u = table.unit_name();
    let pts = table.points();
    let n = pts.len() - 1;
    let mut s: String = header.iter().map(|l| format!("(* {} *)\n", l.replace("*)", "* )"))).collect();
    s.push_str(&format!("(* dX in deg, dY in {u}, dV in {u}/deg, dA in {u}/deg^2 (SMC_CAMXYVA, SM3_Basic) *)\n"));
    s.push_str(&format!(
        "(* use: an MC_CAM_REF with byType := 3 (XYVA), nElements := {}, xStart := {}, xEnd := {}, pce := ADR({ARRAY_NAME}) *)\n",
        n + 1,
        real(pts[0].master_deg, d.master),
        real(pts[n].master_deg, d.master)
    ));
    s.push_str("VAR_GLOBAL\n");
    s.push_str(&format!("    {ARRAY_NAME} : ARRAY[0..{n}] OF SMC_CAMXYVA := [\n"));
    for (i, p) in pts.iter().enumerate() {
        s.push_str(&format!(
            "        (dX := {}, dY := {}, dV := {}, dA := {}){} (* J = {} *)\n",
            real(p.master_deg, d.master),
            real(p.y, d.y),
            real(p.v, d.v),
            real(p.a, d.a),
            if i < n { "," } else { "" },
            real(p.j, d.j)
        ));
    }
    s.push_str("    ];\nEND_VAR\n");
    s
}

/// Reads the points back from the initialiser lines `(dX := …, dY := …, dV := …, dA := …)`,
/// the jerk from the comment after each.
pub fn read(text: &str) -> Result<Vec<CamPoint>> {
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.trim();
        if !l.starts_with("(dX") {
            continue;
        }
        let err = || CamError::Parse {
            field: format!("line {}", i + 1),
            reason: "expected (dX := …, dY := …, dV := …, dA := …) (* J = … *)".into(),
        };
        let mut v = Vec::with_capacity(5);
        for key in ["dX :=", "dY :=", "dV :=", "dA :=", "J ="] {
            let at = l.find(key).ok_or_else(err)? + key.len();
            let rest = l[at..].trim_start();
            let end = rest.find([',', ')', ' ']).unwrap_or(rest.len());
            v.push(rest[..end].parse::<f64>().map_err(|_| err())?);
        }
        rows.push(v);
    }
    points_from_rows(rows)
}
