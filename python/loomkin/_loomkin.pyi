# Type stubs of the extension module `loomkin._loomkin` (built from python/src/*.rs).
# Units: laws are dimensionless (per unit stroke and unit motion angle); cycles and the servo drive
# are in SI units, named in the keys (_m, _m_s, _m_s2, _deg, _nm, _w, _rpm, _s).
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

from ._table import Table

__version__: str
__all__ = [
    "__version__", "LoomkinError", "OutOfRangeError", "FIELDS", "SERVO_DEFAULT_SPEEDS", "Law", "law_catalogue",
    "servo_spline_law", "servo_law", "servo_torque", "servo_torque_curve", "servo_optimize", "servo_export",
    "servo_check", "Cycle", "pick_design", "pick_simulate", "pick_history", "pick_sweep", "pick_montecarlo",
    "dobby_analyze", "dobby_synthesize", "dobby_tolerance", "dobby_sweep", "shed_presets", "shed_law", "shed_table",
    "shed_pareto", "shed_best", "shed_window", "loom_check", "loom_torque", "loom_stagger", "loom_servo", "loom_sley", "loom_sley_synthesize",
    "drive_inertia", "drive_ripple", "drive_correct", "dyn_response",
    "dyn_sweep", "dyn_spectrum", "dyn_compensate", "dyn_optimize", "dyn_two_mass", "dyn_default_ratios",
    "cam_table", "cam_profile", "rise_return_cycle", "insert_budget", "insert_rapier", "insert_projectile",
    "insert_airjet",
]
# The libraries' field descriptors by the path of their const ("ShaftSpeed::SPEED"): name, range,
# default, count, doc. Stubs write defaults as `...`: their values are the descriptors' (loomkin._fields).
FIELDS: Dict[str, Dict[str, Any]]
# The servo commands' default speeds (rpm) by use: TORQUE, DESIGN.
SERVO_DEFAULT_SPEEDS: Dict[str, List[float]]

class LoomkinError(ValueError):
    """Bad input: `field` names the input at fault, `allowed` says what is accepted."""

    field: Optional[str]
    allowed: Optional[str]

class OutOfRangeError(LoomkinError):
    """A number outside its allowed range [low, high] (None: unbounded side), in `unit`."""

    value: float
    unit: str
    low: Optional[float]
    high: Optional[float]
    low_inclusive: bool
    high_inclusive: bool

_Columns = Dict[str, npt.NDArray[np.float64]]
# A table of columns: loomkin.Table, a dict of name to float64 array.
_TableLike = Table
# Shard I of N of a sweep's or study's rows (the CLI's --shard I/N): (I, N) or "I/N".
_ShardArg = Union[Tuple[int, int], str, None]
# A finished Monte-Carlo run's per-draw tables in shard order, or paths as --from-draws takes.
_FromDraws = Union[Sequence[Any], str, None]
_DefPoints = Union[str, Sequence[Sequence[float]], None]

@final
class Law:
    """A normalised rise law, exact in closed form (x, s, v, a, j dimensionless)."""

    def __new__(cls, name: str, **params: Union[float, str]) -> "Law": ...
    @property
    def name(self) -> str: ...
    @property
    def label(self) -> str: ...
    @property
    def params(self) -> Dict[str, Union[float, str]]: ...
    @property
    def segments(self) -> int: ...
    @property
    def joints(self) -> List[float]: ...
    def metrics(self) -> Dict[str, float]: ...
    def continuity(self) -> Dict[str, Any]: ...
    def info(self) -> Dict[str, Any]: ...
    def sample(self, points: int, shard: _ShardArg = None) -> _TableLike: ...
    def __call__(self, x: npt.ArrayLike) -> _TableLike:
        """x, s, v, a, j at x: floats for a number, arrays of x's shape otherwise."""

@final
class Cycle:
    """A checked machine cycle in SI units (m or rad, per second)."""

    @staticmethod
    def from_toml(text: str) -> "Cycle": ...
    @staticmethod
    def from_json(text: str) -> "Cycle": ...
    @property
    def unit(self) -> str: ...
    @property
    def period_deg(self) -> float: ...
    @property
    def speed_rpm(self) -> Optional[float]: ...
    def laws(self) -> List["tuple[int, Law]"]:
        """The law of each rise and return (dimensionless), with the segment's index."""
    def to_toml(self) -> str:
        """The cycle as a cycle file's TOML text (from_toml reads it back to the same cycle)."""
    def report(self, speed_rpm: Optional[float] = None, points: int = ...) -> Dict[str, Any]: ...
    def sample(self, speed_rpm: Optional[float] = None, points: int = ...) -> _TableLike:
        """angle_deg, time_s (s) and s, v, a, j in SI units with the unit in the key (s_m, v_m_s,
        a_m_s2, j_m_s3 or s_rad, v_rad_s, ...), points evenly spaced over the cycle."""
    def segments(self, speed_rpm: Optional[float] = None) -> List[Dict[str, Any]]: ...
    def __call__(self, angle_deg: npt.ArrayLike, speed_rpm: Optional[float] = None) -> _TableLike: ...

def law_catalogue() -> List[Dict[str, Any]]: ...
def servo_spline_law(def_points: _DefPoints = None, end: str = "natural") -> Law: ...
def servo_law(def_points: _DefPoints = None, end: str = "natural") -> Dict[str, Any]: ...
def servo_torque(
    speed_rpm: Sequence[float] = ..., def_points: _DefPoints = None, end: str = "natural", drive_text: Optional[str] = None
) -> Dict[str, Any]: ...
def servo_torque_curve(
    speed_rpm: float = ...,
    points: int = ...,
    def_points: _DefPoints = None,
    end: str = "natural",
    drive_text: Optional[str] = None,
) -> Dict[str, Any]: ...
def servo_optimize(
    speed_rpm: Sequence[float] = ...,
    objective: str = "peak",
    starts: int = ...,
    fixed_x: bool = False,
    def_points: _DefPoints = None,
    end: str = "natural",
    drive_text: Optional[str] = None,
) -> Dict[str, Any]: ...
def servo_export(
    format: str, step_deg: float = ..., def_points: _DefPoints = None, end: str = "natural", drive_text: Optional[str] = None
) -> Dict[str, Any]: ...
def servo_check(axis_toml: str, cycle: Cycle, speed_rpm: Optional[float] = None) -> Dict[str, Any]:
    """`loomkin servo check AXIS --json`: peak and RMS torque (N·m), speeds (rpm), ratios, checks, pass."""

# picking (keywords as loomkin.picking documents them)
def pick_design(**model: Any) -> Dict[str, Any]: ...
def pick_simulate(**kw: Any) -> Dict[str, Any]: ...
def pick_history(points: int = ..., **kw: Any) -> "tuple[_Columns, Dict[str, Any]]": ...
def pick_sweep(
    setting: str, start: float, stop: float, points: int, shard: _ShardArg = None, **kw: Any
) -> Dict[str, Any]: ...

def pick_montecarlo(
    study_toml: str,
    shard: _ShardArg = None,
    from_draws: _FromDraws = None,
    summary: bool = False,
    from_summaries: Optional[Sequence[str]] = None,
    **model: Any,
) -> Union[Dict[str, Any], _TableLike]:
    """`loomkin pick montecarlo STUDY --json` (units in the keys) and `per_draw`, the `--csv` table;
    with shard: that shard's per-draw table; with from_draws: the report of the finished run."""

# dobby
def dobby_tolerance(
    study_toml: str,
    shard: _ShardArg = None,
    from_draws: _FromDraws = None,
    summary: bool = False,
    from_summaries: Optional[Sequence[str]] = None,
) -> Union[Dict[str, Any], _TableLike]:
    """`loomkin dobby tolerance STUDY --json` (m, deg in the keys) and `per_draw`, the `--csv` table;
    with shard: that shard's per-draw table; with from_draws: the report of the finished run."""
def dobby_sweep(
    alpha_deg: Sequence[float],
    dwell_deg: float = ...,
    dwell_centre_deg: float = ...,
    cycles: int = ...,
    law: str = ...,
    params: Optional[Dict[str, Any]] = None,
    roller_m: float = ...,
    step_deg: float = ...,
    l2_m: float = ...,
    l3_m: float = ...,
    l3p_m: float = ...,
    l6_m: float = ...,
    speed_rpm: Optional[float] = None,
    pressure_limit_deg: float = ...,
    cam_spec: Optional[str] = None,
    cam_points_text: Optional[str] = None,
    shard: _ShardArg = None,
) -> Dict[str, Any]:
    """`loomkin dobby sweep --json` at lever angles alpha_deg (deg): rows (m, deg, rad/s in the keys)."""
def dobby_analyze(
    alpha_deg: Optional[float] = None,
    theta_deg: Optional[float] = None,
    l2_m: float = ...,
    l3_m: float = ...,
    l3p_m: float = ...,
    l6_m: float = ...,
    speed_rpm: Optional[float] = None,
    pressure_limit_deg: float = ...,
    cam_spec: Optional[str] = None,
    cam_points_text: Optional[str] = None,
    step_deg: float = ...,
    roller_m: Optional[float] = None,
) -> Dict[str, Any]: ...
def dobby_synthesize(
    dwell_deg: float = ...,
    dwell_centre_deg: float = ...,
    cycles: int = ...,
    law: str = ...,
    params: Optional[Dict[str, Any]] = None,
    roller_m: float = ...,
    step_deg: float = ...,
    alpha_deg: Optional[float] = None,
    theta_deg: Optional[float] = None,
    l2_m: float = ...,
    l3_m: float = ...,
    l3p_m: float = ...,
    l6_m: float = ...,
    speed_rpm: Optional[float] = None,
    pressure_limit_deg: float = ...,
) -> Dict[str, Any]: ...

# shedding
def shed_presets() -> List[Dict[str, Any]]: ...
def shed_law(
    name: Optional[str] = None,
    spec_toml: Optional[str] = None,
    motion_deg: Optional[float] = None,
    threshold: float = ...,
    stroke_mm: float = ...,
    speed_rpm: float = ...,
    label: Optional[str] = None,
) -> Dict[str, Any]: ...
def shed_table(
    design: str = "presets",
    family: Optional[str] = None,
    shapes: Optional[str] = None,
    step: Optional[float] = None,
    min_k: Optional[float] = None,
    max_k: Optional[float] = None,
    motion_deg: Optional[str] = None,
    threshold: float = ...,
    stroke_mm: float = ...,
    speed_rpm: float = ...,
    shard: _ShardArg = None,
) -> Dict[str, Any]: ...
def shed_pareto(
    design: str = "grid",
    family: Optional[str] = None,
    shapes: Optional[str] = None,
    step: Optional[float] = None,
    min_k: Optional[float] = None,
    max_k: Optional[float] = None,
    motion_deg: Optional[str] = None,
    threshold: float = ...,
    stroke_mm: float = ...,
    speed_rpm: float = ...,
) -> Dict[str, Any]: ...
def shed_best(
    window_deg: float,
    threshold: float = ...,
    max_jerk_m_s3: Optional[float] = None,
    design: str = "grid",
    family: Optional[str] = None,
    shapes: Optional[str] = None,
    step: Optional[float] = None,
    min_k: Optional[float] = None,
    max_k: Optional[float] = None,
    motion_deg: Optional[str] = None,
    stroke_mm: float = ...,
    speed_rpm: float = ...,
) -> Dict[str, Any]: ...
def shed_window(
    carrier_speed_m_s: float,
    reed_width_m: float,
    cloth_width_m: Optional[float] = None,
    carrier_length_m: float = ...,
    crossing_range_deg: float = ...,
    shed_excess: float = ...,
    speed_rpm: float = ...,
) -> Dict[str, Any]:
    """`loomkin shed window --json`: the loom data, flight_deg, required_window_deg (deg), thresholds."""

# the loom (texts of the loom file and the weave)
def loom_check(loom_toml: str, wif: Optional[Union[str, bytes]] = None, lift_plan: Optional[str] = None) -> Dict[str, Any]: ...
def loom_torque(
    loom_toml: str, wif: Optional[Union[str, bytes]] = None, lift_plan: Optional[str] = None, step_deg: float = ...
) -> Dict[str, Any]: ...
def loom_stagger(
    loom_toml: str, wif: Optional[Union[str, bytes]] = None, lift_plan: Optional[str] = None, objective: str = "peak"
) -> Dict[str, Any]: ...
def loom_servo(
    loom_toml: str,
    wif: Optional[Union[str, bytes]] = None,
    lift_plan: Optional[str] = None,
    optimize: bool = False,
    objective: str = "peak",
    min_clearance_mm: float = ...,
) -> Dict[str, Any]:
    """`loomkin loom servo --json`: the bus (W, J), the shed the carrier passes (deg, mm) and `frames`
    (N·m, rpm, W; `rise_law`, `fall_law`, `through_law`: each kind of move's law as the loom file names it)."""
def loom_sley_synthesize(
    stroke_mm: float,
    back_dwell_deg: float,
    dwell_tolerance_mm: float = ...,
    reed_height_mm: float = ...,
    sword_mm: Optional[float] = None,
) -> Dict[str, Any]:
    """`loomkin sley synthesize --json`: the [sley] dimensions (mm) and what they give (mm, deg)."""
def loom_sley(
    loom_toml: str, speed_rpm: Optional[float] = None, dwell_tolerance_mm: float = ..., points: int = ...
) -> Dict[str, Any]:
    """`loomkin sley analyze LOOM.toml --json` (mm, deg, m/s, N, N·m in the keys) and `curve`, the `--csv` table."""

# the main shaft (texts of the loom file and the weave; motor keywords as the CLI's motor flags)
def drive_inertia(
    loom_toml: str, wif: Optional[Union[str, bytes]] = None, lift_plan: Optional[str] = None, step_deg: float = ...
) -> Dict[str, Any]:
    """`loomkin drive inertia --json` (kg·m², deg) and `curve`, the `--csv` columns (J, dJ/dφ per mechanism)."""
def drive_ripple(
    loom_toml: str,
    wif: Optional[Union[str, bytes]] = None,
    lift_plan: Optional[str] = None,
    flywheel_kg_m2: Optional[float] = None,
    target_ripple_pct: Optional[float] = None,
    step_deg: float = ...,
    **motor: Any,
) -> Dict[str, Any]:
    """`loomkin drive ripple --json` (rpm, %, J, N·m) and `curve`, the `--csv` columns (ω, torques, energy)."""
def drive_correct(
    loom_toml: str,
    wif: Optional[Union[str, bytes]] = None,
    lift_plan: Optional[str] = None,
    title: Optional[str] = None,
    flywheel_kg_m2: Optional[float] = None,
    step_deg: float = ...,
    natural_hz: Optional[float] = None,
    damping_ratio: float = ...,
    **motor: Any,
) -> Dict[str, Any]:
    """`loomkin drive correct --json` (deg, %, mm) and `cycles`, the cycle files' texts by file name."""

# dynamics
def dyn_response(
    cycle: Cycle,
    natural_hz: float,
    damping_ratio: float = ...,
    mass_kg: Optional[float] = None,
    return_spring_n_m: float = ...,
    preload_n: float = ...,
    weight: bool = False,
    force_n: float = ...,
    speed_rpm: Optional[float] = None,
    cycles: int = ...,
    steady: bool = False,
    points: int = ...,
) -> Dict[str, Any]: ...

# cams
def cam_table(
    cycle: Optional[Cycle],
    format: str,
    step_deg: Optional[float] = None,
    tolerance: Optional[float] = None,
    source: str = "",
    law: Optional[str] = None,
    params: Optional[Dict[str, Union[float, str]]] = None,
    stroke_mm: Optional[float] = None,
    stroke_deg: Optional[float] = None,
    motion_deg: Optional[float] = None,
) -> Dict[str, Any]:
    """`loomkin cam table --json` plus `text`; step_deg (deg) or tolerance (slave unit: mm or
    deg); a cycle, or a law's single rise of stroke_mm (mm) or stroke_deg (deg) over motion_deg (deg)."""
def rise_return_cycle(
    law: str,
    params: Optional[Dict[str, Union[float, str]]] = None,
    stroke_mm: Optional[float] = None,
    stroke_deg: Optional[float] = None,
    motion_deg: Optional[float] = None,
) -> Cycle:
    """Rise over motion_deg (deg), dwell, return, dwell over one turn; stroke in mm or deg."""
def cam_profile(
    cycle: Cycle,
    follower: str,
    prime_radius_mm: Optional[float] = None,
    max_pressure_deg: Optional[float] = None,
    roller_radius_mm: float = ...,
    offset_mm: float = ...,
    arm_mm: Optional[float] = None,
    pivot_mm: Optional[float] = None,
    closure: str = "single",
    step_deg: float = ...,
    source: str = "",
    dxf: bool = False,
    chord_tol_mm: float = ...,
    bore_mm: Optional[float] = None,
) -> Dict[str, Any]:
    """`loomkin cam profile --json`: lengths in mm, angles in deg, curvature in 1/mm; points
    (and counter_points) as _Columns; `dxf` text (mm) when dxf=True."""

def dyn_sweep(
    cycle: Cycle,
    speed_rpm: npt.ArrayLike,
    natural_hz: float,
    damping_ratio: float = ...,
    mass_kg: Optional[float] = None,
    return_spring_n_m: float = ...,
    preload_n: float = ...,
    weight: bool = False,
    force_n: float = ...,
    steady: bool = False,
    shard: _ShardArg = None,
) -> Dict[str, Any]: ...
def dyn_default_ratios() -> npt.NDArray[np.float64]: ...
def dyn_spectrum(law: Law, ratio: npt.ArrayLike, damping_ratio: float = ...) -> npt.NDArray[np.float64]:
    """Residual amplitude after a rise (% of stroke) at each ratio T·f_n (motion time / natural
    period, dimensionless); damping_ratio dimensionless, 0 <= zeta < 1."""
def dyn_compensate(
    cycle: Cycle,
    natural_hz: float,
    damping_ratio: float = ...,
    mass_kg: Optional[float] = None,
    return_spring_n_m: float = ...,
    preload_n: float = ...,
    weight: bool = False,
    force_n: float = ...,
    speed_rpm: Optional[float] = None,
    points: int = ...,
) -> Dict[str, Any]:
    """Compensated input (polydyne): classes, period_s (s), pieces (SI coefficients, t in s) and
    samples (angle_deg, x_mm, s_mm, s_velocity_m_s, s_acceleration_m_s2 or the deg/rad forms)."""
def dyn_optimize(
    cycle: Cycle,
    natural_hz: float,
    damping_ratio: float = ...,
    mass_kg: Optional[float] = None,
    return_spring_n_m: float = ...,
    preload_n: float = ...,
    weight: bool = False,
    force_n: float = ...,
    speed_rpm: Optional[float] = None,
    band_pct: float = ...,
) -> Dict[str, Any]:
    """`loomkin dyn optimize --json` (natural_hz in Hz, speed_rpm in rpm, band_pct in %, residuals
    in the cycle's unit) and cycle_toml."""
def dyn_two_mass(
    cycle: Cycle,
    drive_mass_kg: float,
    drive_stiffness_n_m: float,
    frame_mass_kg: float,
    frame_stiffness_n_m: float,
    damping_ratio: float = ...,
    speed_rpm: Optional[float] = None,
    steady: bool = False,
) -> Dict[str, Any]:
    """`loomkin dyn two-mass --json`: natural_hz (Hz), peak errors in the cycle's unit and where
    (deg), frame residual bound, rigidity ratio."""
def insert_budget(
    loom_toml: Optional[str] = None,
    wif: Optional[Union[str, bytes]] = None,
    lift_plan: Optional[str] = None,
    reed_width_mm: Optional[float] = None,
    carrier_length_mm: Optional[float] = None,
    window_deg: Optional[float] = None,
    speed_m_s: Optional[float] = None,
    speed_rpm: Optional[float] = None,
    carrier_mass_g: Optional[float] = None,
) -> Dict[str, Any]:
    """`loomkin insert budget --json`: max_picks_per_min, required_speed_m_s, energy (J) and power (W)."""
def insert_rapier(
    loom_toml: str, wif: Optional[Union[str, bytes]] = None, lift_plan: Optional[str] = None,
    speed_rpm: Optional[float] = None,
) -> Dict[str, Any]:
    """`loomkin insert rapier --json`: the transfer, the heads' peaks, the clearance over the repeat (mm, deg)."""
def insert_projectile(
    loom_toml: str, wif: Optional[Union[str, bytes]] = None, lift_plan: Optional[str] = None,
    speed_rpm: Optional[float] = None,
) -> Dict[str, Any]:
    """`loomkin insert projectile --json`: launch speed (m/s), flight (ms), arrival (deg), brake, clearance."""
def insert_airjet(loom_toml: str, speed_rpm: Optional[float] = None) -> Dict[str, Any]:
    """`loomkin insert airjet --json`: arrival (deg), flight (ms), exit speed (m/s), relay_plan."""
