"""Type stubs of the Rust extension module (python/src/). The public API is the package's
``__init__.py``, which documents the conventions; these functions take C-contiguous float64
rows of the stated width and, where an attitude is expected, unit quaternions ``w, x, y, z``."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]
Bool = npt.NDArray[np.bool_]

class GyrostatError(ValueError):
    row: Optional[int]

def quat_from_quat(quat: F64, scalar_first: bool) -> F64: ...
def quat_as_quat(quat: F64, scalar_first: bool, canonical: bool) -> F64: ...
def quat_from_euler(seq: str, angles: F64, degrees: bool) -> F64: ...
def quat_as_euler(quat: F64, seq: str, degrees: bool) -> Tuple[F64, Bool]: ...
def quat_from_rotvec(rotvec: F64, degrees: bool) -> F64: ...
def quat_as_rotvec(quat: F64, degrees: bool) -> F64: ...
def quat_from_mrp(mrp: F64) -> F64: ...
def quat_as_mrp(quat: F64) -> F64: ...
def quat_from_matrix(matrix: F64) -> F64: ...
def quat_as_matrix(quat: F64) -> F64: ...
def quat_compose(a: F64, b: F64) -> F64: ...
def quat_apply(quat: F64, vectors: F64, inverse: bool) -> F64: ...
def quat_magnitude(quat: F64) -> F64: ...
def propagate_increments(
    increments: F64, rule: str, q0: Sequence[float], precision: str, compensated: bool
) -> npt.NDArray[Any]: ...
def propagate_rates(
    rates: F64, dt: float, method: str, q0: Sequence[float], precision: str, compensated: bool
) -> npt.NDArray[Any]: ...
def simulate(
    *,
    inertia: Optional[Sequence[float]] = None,
    inertia_offdiag: Optional[Sequence[float]] = None,
    omega: Optional[Sequence[float]] = None,
    momentum: Optional[Sequence[float]] = None,
    spin: Optional[Sequence[float]] = None,
    quartic: Optional[Tuple[str, float]] = None,
    semi_rigid: Optional[Tuple[str, float, float, float]] = None,
    q0: Optional[Sequence[float]] = None,
    wheels: List[List[float]] = ...,
    wheel_torque: Optional[Sequence[float]] = None,
    wheel_speed: Optional[Sequence[float]] = None,
    torque: Optional[Sequence[float]] = None,
    torque_schedule: Optional[F64] = None,
    dt: Optional[float] = None,
    steps: Optional[int] = None,
    every: Optional[int] = None,
    integrator: Optional[str] = None,
    f32: bool = False,
    compensated: bool = False,
) -> Dict[str, Any]: ...
def default_scenario() -> Dict[str, Any]: ...
def estimate(
    t: F64,
    gyro: F64,
    accel: F64,
    mag: Optional[F64],
    frame: str,
    precision: str,
    mode: str,
    rate_rule: Optional[str],
    heading_time_constant: Optional[float],
    params_text: Optional[str],
    params: List[Tuple[str, float]],
    skip_errors: bool,
) -> Dict[str, Any]: ...
def estimator_defaults(mode: str = ...) -> Dict[str, Union[float, str]]: ...
def synthesize(
    *,
    motion: str = ...,
    motion_t: Optional[F64] = None,
    motion_q: Optional[F64] = None,
    motion_omega: Optional[F64] = None,
    sensor: str = ...,
    rate: Optional[float] = None,
    duration: Optional[float] = None,
    rest: Optional[float] = None,
    phases: Optional[int] = None,
    ramp: Optional[float] = None,
    q0: Optional[List[float]] = None,
    translation: Optional[float] = None,
    vibration: Optional[List[float]] = None,
    taps: Optional[float] = None,
    magnet_pass: Optional[List[float]] = None,
    magnet_fixed: Optional[List[float]] = None,
    steel: Optional[List[float]] = None,
    seed: int = 0,
) -> Dict[str, Any]: ...
def sensor_text(sensor: str) -> str: ...
def allan_deviation(
    x: F64,
    rate: float,
    factors: Optional[List[int]] = None,
    per_decade: Optional[int] = None,
) -> Tuple[F64, F64, npt.NDArray[np.uint64], F64]: ...
def allan_characterize(
    x: F64,
    rate: float,
    fit_from: float = 0.0,
    per_decade: Optional[int] = None,
) -> Dict[str, Any]: ...
