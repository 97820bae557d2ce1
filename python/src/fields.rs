//! The libraries' field descriptors as `_loomkin.FIELDS`: a dict from the path of each descriptor
//! (`"ShaftSpeed::SPEED"`) to its `name`, `range` (`lo`, `hi` as `{kind, value}`, `unit`),
//! `default`, `count` and `doc`. The Python wrappers take their keyword defaults from it
//! (`loomkin._fields.default`), so a default lives once, on the library type.

use crate::convert::to_py;
use loomkin_units::{Field, FieldList};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Every library crate's descriptors.
const LISTS: [FieldList; 10] = [
    loomkin_units::FIELDS,
    loomkin_laws::FIELDS,
    loomkin_picking::FIELDS,
    loomkin_cams::FIELDS,
    loomkin_dynamics::FIELDS,
    loomkin_shed::FIELDS,
    loomkin_loom::FIELDS,
    loomkin_mech::FIELDS,
    loomkin_servo::FIELDS,
    loomkin_drive::FIELDS,
];

/// Every descriptor with the path of its `const`.
pub fn all() -> impl Iterator<Item = &'static (&'static str, Field)> {
    LISTS.into_iter().flatten()
}

/// Registers `FIELDS`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let d = PyDict::new(py);
    for (path, field) in all() {
        d.set_item(path, to_py(py, field)?)?;
    }
    m.add("FIELDS", d)?;
    let speeds = PyDict::new(py);
    use loomkin_servo::ServoInputs;
    speeds.set_item("TORQUE", ServoInputs::speeds(ServoInputs::TORQUE_SPEEDS_RPM))?;
    speeds.set_item("DESIGN", ServoInputs::speeds(ServoInputs::DESIGN_SPEEDS_RPM))?;
    m.add("SERVO_DEFAULT_SPEEDS", speeds)
}
