# Type stubs of the extension module `loomkin._loomkin` (built from python/src/*.rs).
# Units: laws are dimensionless (per unit stroke and unit motion angle); cycles and the servo drive
# are in SI units, named in the keys (_m, _m_s, _m_s2, _deg, _nm, _w, _rpm, _s).
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

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

Columns = Dict[str, npt.NDArray[np.float64]]
DefPoints = Union[str, Sequence[Sequence[float]], None]

class Law:
    """A normalised rise law, exact in closed form (x, s, v, a, j dimensionless)."""

    def __init__(self, name: str, **params: Union[float, str]) -> None: ...
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
    def sample(self, points: int) -> Columns: ...
    def __call__(self, x: npt.ArrayLike) -> Columns: ...

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
    def report(self, speed_rpm: Optional[float] = None, points: int = 721) -> Dict[str, Any]: ...
    def segments(self, speed_rpm: Optional[float] = None) -> List[Dict[str, Any]]: ...
    def __call__(self, angle_deg: npt.ArrayLike, speed_rpm: Optional[float] = None) -> Columns: ...

def law_catalogue() -> List[Dict[str, Any]]: ...
def servo_spline_law(def_points: DefPoints = None, end: str = "natural") -> Law: ...
def servo_law(def_points: DefPoints = None, end: str = "natural") -> Dict[str, Any]: ...
def servo_torque(
    speed_rpm: Sequence[float] = ..., def_points: DefPoints = None, end: str = "natural", drive_text: Optional[str] = None
) -> Dict[str, Any]: ...
def servo_torque_curve(
    speed_rpm: float = 600.0,
    points: int = 721,
    def_points: DefPoints = None,
    end: str = "natural",
    drive_text: Optional[str] = None,
) -> Dict[str, Any]: ...
def servo_optimize(
    speed_rpm: Sequence[float] = ...,
    objective: str = "peak",
    starts: int = 6,
    fixed_x: bool = False,
    def_points: DefPoints = None,
    end: str = "natural",
    drive_text: Optional[str] = None,
) -> Dict[str, Any]: ...
def servo_export(
    format: str, step_deg: float = 1.0, def_points: DefPoints = None, end: str = "natural", drive_text: Optional[str] = None
) -> Dict[str, Any]: ...

# picking (keywords as loomkin.picking documents them)
def pick_design(**model: Any) -> Dict[str, Any]: ...
def pick_simulate(**kw: Any) -> Dict[str, Any]: ...
def pick_history(points: int = 201, **kw: Any) -> "tuple[Columns, Dict[str, Any]]": ...
def pick_sweep(setting: str, start: float, stop: float, points: int, **kw: Any) -> Dict[str, Any]: ...

# dobby
def dobby_analyze(
    alpha_deg: Optional[float] = None,
    theta_deg: Optional[float] = None,
    l2_m: float = 0.66,
    l3_m: float = 0.36,
    l3p_m: float = 0.36,
    l6_m: float = 0.40,
    speed_rpm: Optional[float] = None,
    pressure_limit_deg: float = 60.0,
    cam_spec: Optional[str] = None,
    cam_points_text: Optional[str] = None,
    step_deg: float = 1.0,
    roller_m: Optional[float] = None,
) -> Dict[str, Any]: ...
def dobby_synthesize(
    dwell_deg: float = 40.0,
    dwell_centre_deg: float = 90.0,
    cycles: int = 2,
    law: str = "cycloidal",
    params: Optional[Dict[str, Any]] = None,
    roller_m: float = 0.03,
    step_deg: float = 1.0,
    alpha_deg: Optional[float] = None,
    theta_deg: Optional[float] = None,
    l2_m: float = 0.66,
    l3_m: float = 0.36,
    l3p_m: float = 0.36,
    l6_m: float = 0.40,
    speed_rpm: Optional[float] = None,
    pressure_limit_deg: float = 60.0,
) -> Dict[str, Any]: ...

# shedding
def shed_presets() -> List[Dict[str, Any]]: ...
def shed_law(
    name: Optional[str] = None,
    spec_toml: Optional[str] = None,
    motion_deg: Optional[float] = None,
    threshold: float = 0.95,
    stroke_mm: float = 100.0,
    speed_rpm: float = 300.0,
    label: Optional[str] = None,
) -> Dict[str, Any]: ...
def shed_table(**kw: Any) -> Dict[str, Any]: ...
def shed_pareto(**kw: Any) -> Dict[str, Any]: ...
def shed_best(window_deg: float, **kw: Any) -> Dict[str, Any]: ...

# the loom (texts of the loom file and the weave)
def loom_check(loom_toml: str, wif: Optional[str] = None, lift_plan: Optional[str] = None) -> Dict[str, Any]: ...
def loom_torque(
    loom_toml: str, wif: Optional[str] = None, lift_plan: Optional[str] = None, step_deg: float = 0.5
) -> Dict[str, Any]: ...
def loom_stagger(
    loom_toml: str, wif: Optional[str] = None, lift_plan: Optional[str] = None, objective: str = "peak"
) -> Dict[str, Any]: ...

# dynamics
def dyn_response(
    cycle: Cycle,
    natural_hz: float,
    damping_ratio: float = 0.0,
    mass_kg: Optional[float] = None,
    return_spring_n_m: float = 0.0,
    preload_n: float = 0.0,
    weight: bool = False,
    force_n: float = 0.0,
    speed_rpm: Optional[float] = None,
    cycles: int = 1,
    steady: bool = False,
    points: int = 721,
) -> Dict[str, Any]: ...

# cam tables
def cam_table(
    cycle: Cycle, format: str, step_deg: Optional[float] = None, tolerance: Optional[float] = None, source: str = ""
) -> Dict[str, Any]: ...
def dyn_sweep(
    cycle: Cycle,
    speed_rpm: npt.ArrayLike,
    natural_hz: float,
    damping_ratio: float = 0.0,
    mass_kg: Optional[float] = None,
    return_spring_n_m: float = 0.0,
    preload_n: float = 0.0,
    weight: bool = False,
    force_n: float = 0.0,
    steady: bool = False,
) -> Dict[str, Any]: ...
