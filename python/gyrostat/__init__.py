"""gyrostat: attitude conversions, propagation, gyrostat simulation, attitude estimation and
sensor noise characterisation (Allan deviation) on numpy arrays, computed by the Rust crate ``gyrostat`` (no_std, panic-free).

Conventions (the crate's, stated once):

* An attitude maps body-frame vectors to the lab frame, ``v_lab = R v_body``; ``R`` has the body
  axes as columns. This is the active rotation of ``scipy.spatial.transform.Rotation``:
  ``Rotation.as_matrix()`` and ``Rotation.apply()`` mean the same in both packages.
* Quaternions are Hamilton. :class:`Rotation` takes and gives them in scipy's order
  (``x, y, z, w``) unless ``scalar_first=True``; every other function of this package returns
  them scalar first, ``w, x, y, z``.
* Body rates and gyro increments are in the body frame, rad/s and rad; angles in rad unless a
  ``degrees`` argument says otherwise.
* Euler sequences are scipy's strings: three letters from ``xyz``, uppercase intrinsic
  (``"ZYX"``: ``R = R_Z(a) R_Y(b) R_X(c)``), lowercase extrinsic.

Every batch call runs in Rust with the GIL released, so a thread pool spreads independent
calls over cores. A bad row raises :class:`GyrostatError` (a ``ValueError``): its message starts
with ``row N:`` and its ``row`` attribute is ``N`` (0-based), or ``None`` for a problem of the
arguments as a whole.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _gyrostat
from ._gyrostat import GyrostatError

__all__ = [
    "GyrostatError",
    "Rotation",
    "propagate_increments",
    "propagate_rates",
    "Simulation",
    "simulate",
    "default_scenario",
    "Estimate",
    "estimate",
    "estimator_defaults",
    "SyntheticLog",
    "synthesize",
    "sensor_text",
    "allan_deviation",
    "characterize",
]

ArrayLike = npt.ArrayLike
Array = npt.NDArray[np.float64]


def _error(message: str) -> GyrostatError:
    err = GyrostatError(message)
    err.row = None
    return err


def _rows(x: ArrayLike, width: int, name: str) -> Tuple[Array, bool]:
    """``x`` as C-contiguous float64 rows of ``width`` numbers, and whether it was one row."""
    a = np.asarray(x, dtype=np.float64)
    if a.ndim == 1 and a.shape[0] == width:
        return np.ascontiguousarray(a.reshape(1, width)), True
    if a.ndim == 2 and a.shape[1] == width:
        return np.ascontiguousarray(a), False
    raise _error(f"{name}: expected shape ({width},) or (N, {width}), got {a.shape}")


def _matrices(x: ArrayLike) -> Tuple[Array, bool]:
    a = np.asarray(x, dtype=np.float64)
    if a.shape == (3, 3):
        return np.ascontiguousarray(a.reshape(1, 9)), True
    if a.ndim == 3 and a.shape[1:] == (3, 3):
        return np.ascontiguousarray(a.reshape(a.shape[0], 9)), False
    raise _error(f"matrix: expected shape (3, 3) or (N, 3, 3), got {a.shape}")


class Rotation:
    """Attitudes, one or many, with the names and conventions of scipy's ``Rotation``.

    Held as unit quaternions (``w, x, y, z``, float64). Build one with a ``from_*`` class method
    and convert with the ``as_*`` methods; every conversion loops in Rust over all rows with the
    GIL released. Differences from scipy: a bad row raises :class:`GyrostatError` naming the row
    (scipy raises without the row or returns NaN), :meth:`as_euler` reports gimbal lock per row
    (``return_gimbal_lock=True``) instead of a warning, and only three-axis Euler sequences are
    taken.
    """

    __slots__ = ("_q", "_single")

    def __init__(self, quat_wxyz: Array, single: bool = False) -> None:
        """Wraps unit quaternions ``w, x, y, z`` (N, 4) as they are; use the ``from_*`` methods
        for data (they check and normalise)."""
        self._q = np.ascontiguousarray(quat_wxyz, dtype=np.float64).reshape(-1, 4)
        self._single = bool(single)

    def _out(self, a: np.ndarray) -> np.ndarray:
        return a[0] if self._single else a

    # -- quaternions -------------------------------------------------------------------------
    @classmethod
    def from_quat(cls, quat: ArrayLike, *, scalar_first: bool = False) -> "Rotation":
        """Quaternions of any finite norm, (4,) or (N, 4), each normalised; ``x, y, z, w``
        unless ``scalar_first``. A non-finite row, or one of norm at or below machine epsilon
        (2.2e-16: no attitude computation makes one, its direction is noise), raises."""
        q, single = _rows(quat, 4, "quat")
        return cls(_gyrostat.quat_from_quat(q, bool(scalar_first)), single)

    def as_quat(self, canonical: bool = False, *, scalar_first: bool = False) -> Array:
        """The unit quaternions, ``x, y, z, w`` unless ``scalar_first``; with ``canonical`` each
        is the representative with ``w >= 0`` (ties: first non-zero of x, y, z positive)."""
        return self._out(_gyrostat.quat_as_quat(self._q, bool(scalar_first), bool(canonical)))

    # -- Euler angles -----------------------------------------------------------------------------
    @classmethod
    def from_euler(cls, seq: str, angles: ArrayLike, degrees: bool = False) -> "Rotation":
        """Euler angles (3,) or (N, 3) in ``seq`` (three letters from xyz: uppercase intrinsic,
        lowercase extrinsic)."""
        a, single = _rows(angles, 3, "angles")
        return cls(_gyrostat.quat_from_euler(seq, a, bool(degrees)), single)

    def as_euler(
        self, seq: str, degrees: bool = False, *, return_gimbal_lock: bool = False
    ) -> Union[Array, Tuple[Array, npt.NDArray[np.bool_]]]:
        """Euler angles in ``seq``: first and third in (-pi, pi], the middle one in
        [-pi/2, pi/2] (Tait-Bryan) or [0, pi] (proper). At a gimbal lock (the middle angle
        within 2 eps of its pole) only a combination of the outer angles is determined: the
        third is set to 0, as scipy does, and no warning is given; with
        ``return_gimbal_lock=True`` a boolean array marks those rows."""
        angles, lock = _gyrostat.quat_as_euler(self._q, seq, bool(degrees))
        if return_gimbal_lock:
            return self._out(angles), self._out(lock)
        return self._out(angles)

    # -- rotation vectors and MRPs ---------------------------------------------------------------
    @classmethod
    def from_rotvec(cls, rotvec: ArrayLike, degrees: bool = False) -> "Rotation":
        """Rotation vectors (angle times unit axis), (3,) or (N, 3); in degrees the whole vector
        is scaled, as in scipy."""
        v, single = _rows(rotvec, 3, "rotvec")
        return cls(_gyrostat.quat_from_rotvec(v, bool(degrees)), single)

    def as_rotvec(self, degrees: bool = False) -> Array:
        """Rotation vectors, angle in [0, pi]."""
        return self._out(_gyrostat.quat_as_rotvec(self._q, bool(degrees)))

    @classmethod
    def from_mrp(cls, mrp: ArrayLike) -> "Rotation":
        """Modified Rodrigues parameters ``axis * tan(angle / 4)``, (3,) or (N, 3)."""
        p, single = _rows(mrp, 3, "mrp")
        return cls(_gyrostat.quat_from_mrp(p), single)

    def as_mrp(self) -> Array:
        """Modified Rodrigues parameters with norm at most 1 (angle at most pi)."""
        return self._out(_gyrostat.quat_as_mrp(self._q))

    # -- matrices ---------------------------------------------------------------------------------
    @classmethod
    def from_matrix(cls, matrix: ArrayLike) -> "Rotation":
        """Rotation matrices (3, 3) or (N, 3, 3); a matrix that is not orthonormal (beyond
        1000 eps) is replaced by its nearest rotation (the orthogonal polar factor). A matrix
        with determinant <= 0 raises."""
        m, single = _matrices(matrix)
        return cls(_gyrostat.quat_from_matrix(m), single)

    def as_matrix(self) -> Array:
        """Rotation matrices (N, 3, 3): the body axes as columns (``v_lab = R v_body``)."""
        m = _gyrostat.quat_as_matrix(self._q).reshape(-1, 3, 3)
        return self._out(m)

    # -- the rest of the group --------------------------------------------------------------------
    @classmethod
    def identity(cls, num: Optional[int] = None) -> "Rotation":
        """The identity, one (``num=None``) or ``num`` of them."""
        n = 1 if num is None else int(num)
        q = np.zeros((n, 4))
        q[:, 0] = 1.0
        return cls(q, num is None)

    @property
    def single(self) -> bool:
        """Whether this holds one rotation (not a stack of them)."""
        return self._single

    def __len__(self) -> int:
        if self._single:
            raise TypeError("a single rotation has no len()")
        return self._q.shape[0]

    def __getitem__(self, index: Any) -> "Rotation":
        if self._single:
            raise TypeError("a single rotation is not subscriptable")
        q = self._q[index]
        return Rotation(q, q.ndim == 1)

    def __mul__(self, other: "Rotation") -> "Rotation":
        """Composition: ``(a * b).apply(v) == a.apply(b.apply(v))``."""
        if not isinstance(other, Rotation):
            return NotImplemented
        q = _gyrostat.quat_compose(self._q, other._q)
        return Rotation(q, self._single and other._single)

    def inv(self) -> "Rotation":
        """The inverse rotations."""
        q = self._q.copy()
        q[:, 1:] *= -1.0
        return Rotation(q, self._single)

    def apply(self, vectors: ArrayLike, inverse: bool = False) -> Array:
        """``R v`` (or ``R^T v``) for vectors (3,) or (N, 3), one rotation or vector broadcast
        against many."""
        v, single_v = _rows(vectors, 3, "vectors")
        out = _gyrostat.quat_apply(self._q, v, bool(inverse))
        return out[0] if (self._single and single_v) else out

    def magnitude(self) -> Union[float, Array]:
        """The rotation angles, in [0, pi]."""
        m = _gyrostat.quat_magnitude(self._q)
        return float(m[0]) if self._single else m

    def __repr__(self) -> str:
        return f"Rotation.from_quat({self.as_quat(scalar_first=True).tolist()!r}, scalar_first=True)"


# -- propagation -------------------------------------------------------------------------------


def propagate_increments(
    increments: ArrayLike,
    *,
    rule: str = "coning2",
    q0: Sequence[float] = (1.0, 0.0, 0.0, 0.0),
    precision: str = "f64",
    compensated: bool = False,
) -> np.ndarray:
    """Attitudes from gyro increments (N, 3) (rad, body frame, each the integral of the rate
    over one sample interval), as the ``propagate --input increments`` tool computes them.

    Row ``k`` of the result (N, 4; ``w, x, y, z``, body -> lab) is the attitude after increments
    ``0..=k``. ``rule``: ``exp`` (no coning correction), ``coning1`` (previous-interval
    correction), ``coning2``/``coning3``/``coning4`` (one update per 2/3/4 increments; a row
    inside a group applies the pending increments with the highest-order rule that fits them).
    ``precision``: ``f64``, ``f32`` (float32 rows) or ``q30`` (Q1.30 fixed point, the firmware's
    integer code, bit for bit: every number an exact multiple of 2**-30). ``compensated`` carries
    the attitude's rounding error (f64 and f32). ``q0`` is scalar first, its norm within 1e-3 of
    1. A non-finite sample, one beyond half a turn, or (q30) beyond 2 rad raises, naming the row.
    """
    v, _ = _rows(increments, 3, "increments")
    return _gyrostat.propagate_increments(
        v, rule, [float(x) for x in q0], precision, bool(compensated)
    )


def propagate_rates(
    rates: ArrayLike,
    dt: float,
    *,
    method: str = "magnus4",
    q0: Sequence[float] = (1.0, 0.0, 0.0, 0.0),
    precision: str = "f64",
    compensated: bool = False,
) -> np.ndarray:
    """Attitudes from body-rate samples (N, 3) (rad/s, sample ``k`` at time ``k*dt``), as the
    ``propagate --input rates`` tool computes them: row ``k`` (``w, x, y, z``) is the attitude at
    time ``k*dt`` (row 0 is ``q0``). ``method``: ``magnus4``, ``cf4`` or ``rk4`` (fourth order
    between the samples' cubic interpolant). ``precision``: ``f64`` or ``f32``."""
    v, _ = _rows(rates, 3, "rates")
    return _gyrostat.propagate_rates(
        v, float(dt), method, [float(x) for x in q0], precision, bool(compensated)
    )


# -- simulation ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Simulation:
    """The rows of a ``simulate`` run: step 0 and every ``every``-th step.

    ``t`` (s), ``q`` (N, 4; ``w, x, y, z``, body -> lab), ``omega`` (N, 3; body rate dH/dJ,
    rad/s), ``momentum`` (N, 3; total body angular momentum J, body plus wheels), ``energy``
    (N,; H(J)), ``wheel_speeds`` (N, wheels; relative to the body, rad/s); ``monitors``: the
    lab-frame momentum at the start and the end, its largest relative drift, that of ``|J|``,
    the energy at the start and the end, the integrated external torque. With ``f32=True`` the
    numbers are the f32 run's, widened exactly.
    """

    t: Array
    q: Array
    omega: Array
    momentum: Array
    energy: Array
    wheel_speeds: Array
    integrator: str
    monitors: Optional[Dict[str, Any]]


def simulate(
    *,
    dt: float,
    steps: int,
    integrator: str,
    inertia: Optional[Sequence[float]] = None,
    inertia_offdiag: Optional[Sequence[float]] = None,
    omega: Optional[Sequence[float]] = None,
    momentum: Optional[Sequence[float]] = None,
    spin: Optional[Sequence[float]] = None,
    quartic: Optional[Tuple[str, float]] = None,
    semi_rigid: Optional[Tuple[str, float, float, float]] = None,
    q0: Optional[Sequence[float]] = None,
    wheels: Iterable[Sequence[float]] = (),
    wheel_torque: Optional[Sequence[float]] = None,
    wheel_speed: Optional[Sequence[float]] = None,
    torque: Optional[Sequence[float]] = None,
    torque_schedule: Optional[ArrayLike] = None,
    every: int = 1,
    f32: bool = False,
    compensated: bool = False,
) -> Simulation:
    """A rigid-body or gyrostat run, the scenarios of the ``simulate`` tool (its flags as keywords,
    the same checks and the same numbers; ``simulate --help`` describes each).

    ``inertia`` (I1, I2, I3) with ``inertia_offdiag`` (I12, I13, I23), or ``semi_rigid`` =
    (kind, mass, omega_v, r0) with kind ``octahedral``, ``cubic`` or ``tetrahedral``; ``omega``
    or ``momentum``; ``spin`` (gyro-rotor momentum); ``quartic`` = (``octahedral`` or ``cubic``,
    coefficient); ``q0`` (w, x, y, z); ``wheels``: up to four (ax, ay, az, inertia[, speed0]),
    with ``wheel_torque`` or ``wheel_speed`` (one number per wheel); ``torque`` (body frame, N m)
    or ``torque_schedule`` (rows t, tx, ty, tz, zero-order hold); ``integrator``: ``rk4``,
    ``strang``, ``yoshida4``, ``suzuki4`` or ``exact``; ``f32`` runs the core in f32;
    ``compensated`` steps a compensated state (each component's rounding error carried into the
    next step; every integrator but ``exact``), the arrays holding its rounded part.

    Invalid arguments raise :class:`GyrostatError` before the run. A step the library rejects
    (too long for the rates, a state no longer finite) raises it too, with the rows before it
    in the exception's ``partial`` attribute (a :class:`Simulation`).
    """
    schedule = None
    if torque_schedule is not None:
        schedule, _ = _rows(torque_schedule, 4, "torque_schedule")
    d = _gyrostat.simulate(
        inertia=inertia,
        inertia_offdiag=inertia_offdiag,
        omega=omega,
        momentum=momentum,
        spin=spin,
        quartic=quartic,
        semi_rigid=semi_rigid,
        q0=q0,
        wheels=[[float(x) for x in w] for w in wheels],
        wheel_torque=wheel_torque,
        wheel_speed=wheel_speed,
        torque=torque,
        torque_schedule=schedule,
        dt=dt,
        steps=steps,
        every=every,
        integrator=integrator,
        f32=f32,
        compensated=compensated,
    )
    sim = Simulation(
        t=d["t"],
        q=d["q"],
        omega=d["omega"],
        momentum=d["momentum"],
        energy=d["energy"],
        wheel_speeds=d["wheel_speeds"],
        integrator=d["integrator"],
        monitors=d["monitors"],
    )
    if d["error"] is not None:
        err = _error(d["error"])
        err.partial = sim  # type: ignore[attr-defined]
        raise err
    return sim


def default_scenario() -> Dict[str, Any]:
    """The built-in scenario of ``simulate``: the body (6, 4, 3) kg m^2 spun at (0.05, 1, 0.01)
    rad/s near its intermediate axis, 20000 steps of 0.01 s with yoshida4 in f32 (plain and
    compensated) and in f64,
    and the closed form (exact free rigid body). Keys: ``dt``, ``steps``, ``every``,
    ``inertia``, ``omega0``, ``integrator``, ``t`` (sample times, every 10 steps from step 10),
    ``flip_interval_closed_form`` (2K(m)/lambda, s), ``q_exact``, and ``f32``, ``f32_compensated``
    and ``f64``: dicts
    with ``flips`` (times), ``flip_interval`` (mean), the largest drifts, the largest attitude
    error against the closed form (degrees), and per sample ``q``, ``omega``, ``momentum``,
    ``drift`` (relative energy, |J| and lab-momentum drift)."""
    return _gyrostat.default_scenario()


# -- estimation ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Estimate:
    """The estimator's output per sample: ``q`` (N, 4; ``w, x, y, z``, sensor -> earth),
    ``bias`` (N, 3; gyroscope bias, rad/s), ``accel_used``/``mag_used`` (whether the sample
    corrected the estimate), ``at_rest``, ``attitude_std`` (N, 2; heading and inclination
    standard deviation, rad), ``initialized`` (the attitude is initialised after the sample;
    before, ``q`` is the identity, where the ``estimate`` tool prints ``nan``), ``skipped``
    (a bad sample turned into a gap with ``skip_errors``)."""

    q: Array
    bias: Array
    accel_used: npt.NDArray[np.bool_]
    mag_used: npt.NDArray[np.bool_]
    at_rest: npt.NDArray[np.bool_]
    attitude_std: Array
    initialized: npt.NDArray[np.bool_]
    skipped: npt.NDArray[np.bool_]


def estimator_defaults(mode: str = "full") -> Dict[str, Union[float, str]]:
    """The estimator's default parameters by name (SI units, angles in rad): the keywords
    :func:`estimate` takes, what it starts from in ``mode`` (``full`` or ``light``), with the
    mode's default rate rule under ``rate_rule`` (its name, as :func:`estimate`'s
    ``rate_rule`` takes it); an unknown mode raises :class:`GyrostatError`."""
    return dict(_gyrostat.estimator_defaults(str(mode)))


def estimate(
    t: ArrayLike,
    gyro: ArrayLike,
    accel: ArrayLike,
    mag: Optional[ArrayLike] = None,
    *,
    frame: str = "enu",
    precision: str = "f64",
    mode: str = "full",
    rate_rule: Optional[str] = None,
    heading_time_constant: Optional[float] = None,
    params_file: Optional[str] = None,
    skip_errors: bool = False,
    **params: float,
) -> Estimate:
    """Attitude and gyroscope bias from an IMU record: time stamps ``t`` (N,) in s, ``gyro``
    (N, 3) rad/s, ``accel`` (N, 3) m/s^2 and, for 9D, ``mag`` (N, 3) in any unit, all in the
    sensor frame. Sample ``k`` is propagated over ``t[k] - t[k-1]``; the first usable sample
    initialises the attitude, and no sample propagates before that or at it, so their steps
    are not used or checked (the first-sample rule of the library; a record may start while
    the sensor turns fast). ``frame``: ``enu`` (x east,
    y magnetic north, z up) or ``ned``. ``mode``: ``full`` (every part of the filter on every
    sample) or ``light`` (the covariance and the corrections every 25 ms, a fixed magnetometer
    delay: about a fifth of the cost; ``gyrostat::estimation::Mode``). ``rate_rule``: how rate
    samples become a step's rotation in the full mode, ``trapezoid`` (the mean of the step's two
    end samples, order 2), ``magnus4`` or ``cf4`` (order 4, on the Gauss-node rates of the
    interpolant through the last four samples; ``gyrostat::estimation::RateRule``, the
    parameter file's ``rate_rule = NAME``, the C struct's ``GYRO_RATE_RULE_*``); ``None`` keeps
    the parameter file's rule, or else the library's default for the mode (``Params``'
    documentation names it); an unknown name raises :class:`GyrostatError` (a ``ValueError``).
    ``heading_time_constant`` switches to fixed
    (complementary) gains. ``params_file``: a parameter file (``name = value  # comment`` per
    line, the library's names such as ``field.norm``, SI units, and ``rate_rule = NAME``; the
    format of ``gyrostat::estimation::params_text``, read by the library's one parser; a bad
    line raises naming it), applied to the defaults before the keywords. Any other keyword overrides a
    parameter of :func:`estimator_defaults`. The loop is the ``estimate`` tool's (one code
    path, ``gyrostat_pipeline::estimate``): a time stamp not after the previous one, a step
    over 1000 s, a rate turning more than half a turn in its step or a non-finite time stamp or
    gyroscope value raises naming the row; with ``skip_errors`` (the tool's
    ``--skip-bad-rows``) a non-finite time stamp or gyroscope value is skipped instead (the
    state unchanged, its row repeats the attitude, ``skipped`` is set) and the next good sample
    propagates over the whole interval since the last good one. A bad accelerometer or
    magnetometer sample is never an error (``accel_used``/``mag_used`` say so)."""
    tt = np.ascontiguousarray(np.asarray(t, dtype=np.float64).reshape(-1))
    g, _ = _rows(gyro, 3, "gyro")
    a, _ = _rows(accel, 3, "accel")
    m = None if mag is None else _rows(mag, 3, "mag")[0]
    text = None
    if params_file is not None:
        with open(params_file, encoding="utf-8") as f:
            text = f.read()
    d = _gyrostat.estimate(
        tt,
        g,
        a,
        m,
        frame,
        precision,
        mode,
        None if rate_rule is None else str(rate_rule),
        heading_time_constant,
        text,
        [(str(k), float(v)) for k, v in params.items()],
        bool(skip_errors),
    )
    return Estimate(
        q=d["q"],
        bias=d["bias"],
        accel_used=d["accel_used"],
        mag_used=d["mag_used"],
        at_rest=d["at_rest"],
        attitude_std=d["attitude_std"],
        initialized=d["initialized"],
        skipped=d["skipped"],
    )


# -- synthetic logs -------------------------------------------------------------------------------


@dataclass(frozen=True)
class SyntheticLog:
    """A synthetic IMU log with its exact truth, the rows of ``synthesize``'s CSV as arrays.

    ``t`` (N,; the time stamps, with the clock jitter), ``gyr`` (N, 3; rad/s), ``acc`` (N, 3;
    m/s^2, the specific force: +g up at rest), ``mag`` (N, 3; uT, NaN rows between the samples
    of a slower magnetometer), ``q`` (N, 4; the true attitude at ``t_true``, ``w, x, y, z``,
    sensor -> earth, ENU), ``movement`` (N,; bool, inside a movement phase), and the true motion:
    ``t_true`` (the nominal sample instants), ``rate`` (N, 3; body rate), ``pos`` (N, 3; m,
    earth frame), ``lin_acc`` (N, 3; earth frame, without gravity), ``body_acc`` (N, 3;
    vibration and taps, sensor frame).
    """

    t: Array
    gyr: Array
    acc: Array
    mag: Array
    q: Array
    movement: npt.NDArray[np.bool_]
    t_true: Array
    rate: Array
    pos: Array
    lin_acc: Array
    body_acc: Array


def synthesize(
    *,
    motion: str = "handheld",
    sensor: str = "ideal",
    rate: Optional[float] = None,
    duration: Optional[float] = None,
    rest: Optional[float] = None,
    phases: Optional[int] = None,
    ramp: Optional[float] = None,
    q0: Optional[Sequence[float]] = None,
    translation: Optional[float] = None,
    vibration: Optional[Tuple[float, float]] = None,
    taps: Optional[float] = None,
    magnet_pass: Optional[Tuple[float, float, float]] = None,
    magnet_fixed: Optional[Sequence[float]] = None,
    steel: Optional[Sequence[float]] = None,
    seed: int = 0,
    motion_rows: Optional[Any] = None,
) -> SyntheticLog:
    """A synthetic IMU log: the ``synthesize`` tool's flags as keywords (the same checks and
    the same numbers, byte for byte; ``synthesize --help`` describes each).

    ``motion``: ``handheld``, ``axes``, ``rest`` or ``spin:WX,WY,WZ``; or give ``motion_rows``,
    a :class:`Simulation` (or any object with uniformly spaced ``t``, ``q`` and ``omega``
    arrays) to use its rows as the samples, as ``simulate ... | synthesize --motion -`` does.
    ``sensor``: a preset (``ideal``, ``consumer``, ``industrial``, ``tactical``) or the path of a
    sensor spec file (:func:`sensor_text` prints a preset). ``vibration`` = (A m/s^2, F Hz),
    ``magnet_pass`` = (M A m^2, D m, V m/s), ``magnet_fixed`` = (HX, HY, HZ[, T]) uT, ``steel`` =
    (DX, DY, DZ) uT. Invalid arguments raise :class:`GyrostatError`.
    """
    kw: Dict[str, Any] = {}
    if motion_rows is not None:
        kw = dict(
            motion="rows",
            motion_t=np.ascontiguousarray(motion_rows.t, dtype=np.float64),
            motion_q=_rows(motion_rows.q, 4, "motion_rows.q")[0],
            motion_omega=_rows(motion_rows.omega, 3, "motion_rows.omega")[0],
        )
    else:
        kw = dict(motion=motion)
    d = _gyrostat.synthesize(
        sensor=sensor,
        rate=rate,
        duration=duration,
        rest=rest,
        phases=phases,
        ramp=ramp,
        q0=None if q0 is None else [float(x) for x in q0],
        translation=translation,
        vibration=None if vibration is None else [float(x) for x in vibration],
        taps=taps,
        magnet_pass=None if magnet_pass is None else [float(x) for x in magnet_pass],
        magnet_fixed=None if magnet_fixed is None else [float(x) for x in magnet_fixed],
        steel=None if steel is None else [float(x) for x in steel],
        seed=seed,
        **kw,
    )
    return SyntheticLog(**d)


def sensor_text(sensor: str) -> str:
    """The text of a sensor preset (with its datasheet sources) or spec file."""
    return _gyrostat.sensor_text(sensor)
# -- noise characterisation ----------------------------------------------------------------------


def _samples(x: ArrayLike, name: str) -> Array:
    a = np.ascontiguousarray(np.asarray(x, dtype=np.float64))
    if a.ndim not in (1, 2):
        raise _error(f"{name}: expected shape (N,) or (N, k), got {a.shape}")
    return a


def allan_deviation(
    x: ArrayLike, rate: float, taus: Union[None, str, ArrayLike] = None
) -> Tuple[Array, Array, npt.NDArray[np.uint64]]:
    """The overlapping Allan deviation of rate samples ``x`` (N,) at ``rate`` Hz, as the
    ``characterize`` tool computes it: ``(taus, adev, n)``, with ``n`` the number of overlapping
    terms of each point (``N + 1 - 2m`` for the averaging factor ``m = tau * rate``; allantools'
    ``ns``).

    The same numbers as ``allantools.oadev(x, rate, data_type="freq", taus=...)``: the samples
    are integrated (after subtracting their mean) into ``N + 1`` phase points ``x_0 = 0``, and
    ``sigma^2(tau) = sum (x[k+2m] - 2 x[k+m] + x[k])^2 / (2 tau^2 (N + 1 - 2m))``.
    ``taus``: ``None`` or ``"octave"`` (m = 1, 2, 4, ... while two terms remain),
    ``"decade"`` (about 10 per decade), or averaging times in s, each rounded to the nearest
    factor ``m`` (duplicates merged); a time whose ``m`` is 0 or leaves fewer than two terms
    raises :class:`GyrostatError` (allantools drops it silently)."""
    y = _samples(x, "x")
    if y.ndim != 1:
        raise _error(f"x: expected shape (N,), got {y.shape}")
    if taus is None or (isinstance(taus, str) and taus == "octave"):
        t, a, n, _ = _gyrostat.allan_deviation(y, float(rate))
    elif isinstance(taus, str) and taus == "decade":
        t, a, n, _ = _gyrostat.allan_deviation(y, float(rate), per_decade=10)
    elif isinstance(taus, str):
        raise _error(f"taus: 'octave', 'decade' or averaging times, got {taus!r}")
    else:
        tt = np.asarray(taus, dtype=np.float64).reshape(-1)
        if not np.all(np.isfinite(tt)):
            raise _error("taus: not finite")
        m = np.unique(np.round(tt * float(rate)))
        if m.size and m[0] < 1:
            raise _error(f"taus: {tt.min()} s is shorter than half a sample at {rate} Hz")
        t, a, n, _ = _gyrostat.allan_deviation(y, float(rate), factors=[int(v) for v in m])
    return t, a, n


def characterize(
    x: ArrayLike,
    rate: float,
    *,
    fit_from: float = 0.0,
    taus: Optional[str] = None,
) -> Dict[str, Any]:
    """White noise N, bias instability B and rate random walk K of rest samples ``x`` (N,) or
    (N, k) (one column per axis) at ``rate`` Hz, as the ``characterize`` tool fits them:
    ``sigma^2(tau) = N^2/tau + (0.664 B)^2 + K^2 tau/3``, all three terms at once by weighted
    least squares of the Allan variance (weights from each point's equivalent degrees of freedom,
    NIST SP 1065 Table 5; every coefficient >= 0), over the points with ``tau >= fit_from`` s.
    N is the fitted -1/2 line at tau = 1 s (unit/sqrt(Hz)), B the floor / 0.664 (unit), K the
    +1/2 line at tau = 3 s (unit/sqrt(s)).

    Returns a dict of arrays with one entry per axis (floats for a 1-D ``x``):
    ``noise_density``, ``bias_instability``, ``rate_random_walk``, ``floor_bound`` (the lowest
    point of the curve / 0.664: the classical reading of B, an upper bound), ``floor_tau``,
    ``chi2_per_dof`` (tens or more: the curve has a shape the three terms cannot take, such as
    the correlated noise of a sensor's low-pass filter at short tau: raise ``fit_from``), and the
    curves ``taus`` (M,), ``adev`` (k, M) or (M,), ``edf`` (the same shape). ``taus``: ``None``
    or ``"octave"``, or ``"decade"`` (about 10 per decade)."""
    y = _samples(x, "x")
    single = y.ndim == 1
    cols = y.reshape(-1, 1) if single else y
    if taus not in (None, "octave", "decade"):
        raise _error(f"taus: 'octave' or 'decade', got {taus!r}")
    per_decade = 10 if taus == "decade" else None
    fits = [
        _gyrostat.allan_characterize(
            np.ascontiguousarray(cols[:, i]), float(rate), float(fit_from), per_decade
        )
        for i in range(cols.shape[1])
    ]
    keys = (
        "noise_density",
        "bias_instability",
        "rate_random_walk",
        "floor_bound",
        "floor_tau",
        "chi2_per_dof",
    )
    out: Dict[str, Any] = {}
    for k in keys:
        v = np.array([f[k] for f in fits])
        out[k] = float(v[0]) if single else v
    out["taus"] = fits[0]["taus"]
    for k in ("adev", "edf"):
        v = np.array([f[k] for f in fits])
        out[k] = v[0] if single else v
    return out
