"""The PyPI attitude filters gyrostat is compared with, run the same way on any log.

Shared by `benches/broad/run_peers.py` (BROAD), `benches/synthetic/grid.py` (the synthetic grid)
and `benches/evaluate.py` (both, in one run). Every function takes a log object with

    gyr  (n, 3) rad/s       acc  (n, 3) m/s^2 (specific force, +g up at rest)
    mag  (n, 3) uT (every row finite: a row without a new sample repeats the last one)
    ts   the nominal sample period (s)       stem  a name for messages

and returns the (n, 4) estimates, scalar first, sensor -> earth in BROAD's earth frame (ENU, y
towards magnetic north), the output after update i being the estimate for row i. Every filter
runs online from the first sample with BROAD's initialisation rule (`initial_enu`: the first
sample's accelerometer on +z and its magnetometer's horizontal part on +y; 6D: the first
accelerometer sample alone). Frames and units of each peer (verified on BROAD's rest phases by
run_peers.py and on undisturbed synthetic logs by grid.py --check-frames):

  VQF       PyPI vqf, `VQF(Ts)` defaults, `updateBatch` (checked equal to per-sample `update`
            over the first 300 samples). SI units. Output ENU; its first 9D output is BROAD's
            initial state (checked).
  Fusion    PyPI imufusion (x-io Fusion): deg/s, g, uT; output NWU (imufusion 1.3.3 ignores
            `AhrsSettings(convention=...)`; the default NWU is mapped: q_ENU = Rz(+90 deg) q_NWU).
            Initial attitude: `set_quaternion` + `skip_startup`.
  Madgwick  PyPI ahrs `Madgwick(gain=MADGWICK_GAIN)`, `updateMARG`/`updateIMU` per sample; SI
            units; output NWU (mapped).
  Mahony    PyPI ahrs `Mahony(k_P=MAHONY_KP, k_I=MAHONY_KI)`, bias integral from zero; SI units;
            output ENU.

Gains: Madgwick beta 0.12 and Mahony kP 0.74 / kI 0.0012 are BROAD's best common gains (the
values its authors found best over all trials at 285.7 Hz). They are continuous-time gains (rad/s
and 1/s), used unchanged at every rate and on every data set: not re-tuned for the decimated
trials or the synthetic grid. The ahrs filters are pure Python (about 150-350 us per update).
"""
import math
from functools import partial

import numpy as np

G = 9.81  # m/s^2 per g, for imufusion's accelerometer unit (only the direction matters to it)
MADGWICK_GAIN = 0.12
MAHONY_KP = 0.74
MAHONY_KI = 0.0012


def pkg_version(name):
    try:
        from importlib.metadata import version

        return version(name)
    except Exception:
        return "?"


# --- quaternions (scalar first, sensor -> earth: v_earth = q v q*) ------------------------------


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def qmul_rows(a, Q):
    """a * Q[i] for every row of Q."""
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = Q.T
    return np.stack(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ],
        axis=1,
    )


def quat_from_matrix(c):
    """Unit quaternion of the rotation matrix c (Shepperd's method: the largest pivot)."""
    tr = c[0, 0] + c[1, 1] + c[2, 2]
    k = int(np.argmax([tr, c[0, 0], c[1, 1], c[2, 2]]))
    if k == 0:
        s = 2.0 * math.sqrt(1.0 + tr)
        q = [s / 4, (c[2, 1] - c[1, 2]) / s, (c[0, 2] - c[2, 0]) / s, (c[1, 0] - c[0, 1]) / s]
    elif k == 1:
        s = 2.0 * math.sqrt(1.0 + c[0, 0] - c[1, 1] - c[2, 2])
        q = [(c[2, 1] - c[1, 2]) / s, s / 4, (c[0, 1] + c[1, 0]) / s, (c[0, 2] + c[2, 0]) / s]
    elif k == 2:
        s = 2.0 * math.sqrt(1.0 - c[0, 0] + c[1, 1] - c[2, 2])
        q = [(c[0, 2] - c[2, 0]) / s, (c[0, 1] + c[1, 0]) / s, s / 4, (c[1, 2] + c[2, 1]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 - c[0, 0] - c[1, 1] + c[2, 2])
        q = [(c[1, 0] - c[0, 1]) / s, (c[0, 2] + c[2, 0]) / s, (c[1, 2] + c[2, 1]) / s, s / 4]
    q = np.array(q)
    return q / np.linalg.norm(q) * (1 if q[0] >= 0 else -1)


def initial_enu(acc, mag=None):
    """BROAD's initial state: the attitude (sensor -> ENU, y to magnetic north) that puts the
    accelerometer on +z and the magnetometer's horizontal part on +y. Without a magnetometer
    (6D), the smallest rotation that puts the accelerometer on +z."""
    up = acc / np.linalg.norm(acc)
    if mag is None:
        # Shortest arc from `up` to +z.
        q = np.array([1.0 + up[2], up[1], -up[0], 0.0])
        return q / np.linalg.norm(q)
    east = np.cross(mag, up)
    east /= np.linalg.norm(east)
    north = np.cross(up, east)
    # Rows: the earth axes in sensor coordinates, so that v_earth = C v_sensor.
    return quat_from_matrix(np.array([east, north, up]))


S = math.sqrt(0.5)
ENU_FROM_NWU = np.array([S, 0.0, 0.0, S])  # +90 deg about z: north (NWU x) -> ENU y
NWU_FROM_ENU = np.array([S, 0.0, 0.0, -S])


def hold_last(mag):
    """Rows without a magnetometer sample (NaN) repeat the last sample; the first row must have
    one."""
    out = np.array(mag, dtype=float)
    bad = ~np.all(np.isfinite(out), axis=1)
    if bad[0]:
        raise ValueError("the first row has no magnetometer sample")
    if bad.any():
        idx = np.where(bad, 0, np.arange(len(out)))
        np.maximum.accumulate(idx, out=idx)
        out = out[idx]
    return np.ascontiguousarray(out)


# --- the filters ---------------------------------------------------------------------------------


def run_vqf(tr, nine):
    from vqf import VQF

    v = VQF(tr.ts)
    if nine:
        out = v.updateBatch(tr.gyr, tr.acc, tr.mag)["quat9D"]
    else:
        out = v.updateBatch(tr.gyr, tr.acc)["quat6D"]
    # The batch call is the online filter looped in C++: check it against per-sample updates.
    w = VQF(tr.ts)
    for i in range(min(300, len(out))):
        if nine:
            w.update(tr.gyr[i].copy(), tr.acc[i].copy(), tr.mag[i].copy())
            q = w.getQuat9D()
        else:
            w.update(tr.gyr[i].copy(), tr.acc[i].copy())
            q = w.getQuat6D()
        assert np.array_equal(q, out[i]), f"VQF batch != online at {tr.stem} row {i}"
    if nine:
        q0 = initial_enu(tr.acc[0], tr.mag[0])
        err = 2 * math.degrees(math.acos(min(1.0, abs(float(np.dot(q0, out[0]))))))
        # acos near 1 resolves about sqrt(2 eps) = 2e-8 rad = 1e-6 deg.
        assert err < 1e-5, f"VQF's first output is not BROAD's initial state ({err} deg)"
    return out


def run_fusion(tr, nine, documented=False):
    """Fusion with its defaults, or (documented) the settings of its README and example."""
    import imufusion

    ahrs = imufusion.Ahrs()
    fs = 1.0 / tr.ts
    if documented:
        settings = imufusion.AhrsSettings(
            sample_rate=fs,
            gain=0.5,
            gyroscope_range=2000,
            acceleration_rejection=10,
            magnetic_rejection=10,
            rejection_timeout=5,
        )
        bias = imufusion.Bias()
        bias.set_settings(imufusion.BiasSettings(sample_rate=fs))
    else:
        settings = imufusion.AhrsSettings(sample_rate=fs)
        bias = None
    settings.convention = imufusion.CONVENTION_NWU  # the default; the property setter is what works
    ahrs.set_settings(settings)
    q0 = initial_enu(tr.acc[0], tr.mag[0] if nine else None)
    ahrs.set_quaternion(qmul(NWU_FROM_ENU, q0))
    ahrs.skip_startup()
    gyr = np.degrees(tr.gyr)
    acc = tr.acc / G
    mag = tr.mag
    out = np.empty((len(gyr), 4))
    for i in range(len(gyr)):
        g = bias.update(gyr[i]) if bias is not None else gyr[i]
        if nine:
            ahrs.update(g, acc[i], mag[i])
        else:
            ahrs.update_no_magnetometer(g, acc[i])
        out[i] = ahrs.get_quaternion()
    return qmul_rows(ENU_FROM_NWU, out)


def run_ahrs_filter(f, q, tr, nine):
    """One `ahrs` filter `f` over a trial from the quaternion `q` (in the filter's own frame):
    `updateMARG` on every row (9D) or `updateIMU` (6D); the quaternion after each row."""
    out = np.empty((len(tr.gyr), 4))
    for i in range(len(tr.gyr)):
        if nine:
            q = f.updateMARG(q, tr.gyr[i], tr.acc[i], tr.mag[i])
        else:
            q = f.updateIMU(q, tr.gyr[i], tr.acc[i])
        out[i] = q
    return out


def run_madgwick(tr, nine):
    from ahrs.filters import Madgwick

    f = Madgwick(frequency=1.0 / tr.ts, gain=MADGWICK_GAIN)
    q = qmul(NWU_FROM_ENU, initial_enu(tr.acc[0], tr.mag[0] if nine else None))
    return qmul_rows(ENU_FROM_NWU, run_ahrs_filter(f, q, tr, nine))


def run_mahony(tr, nine):
    from ahrs.filters import Mahony

    q = initial_enu(tr.acc[0], tr.mag[0] if nine else None)
    f = Mahony(frequency=1.0 / tr.ts, k_P=MAHONY_KP, k_I=MAHONY_KI, q0=q.copy())
    return run_ahrs_filter(f, q, tr, nine)


def peer_table():
    """(label, nine, description, fn(log) -> quats) of every filter above, in the tables' order
    (fn picklable: the grid runs cells in processes)."""
    vqf_v, fus_v, ahrs_v = pkg_version("vqf"), pkg_version("imufusion"), pkg_version("ahrs")
    mg = f"ahrs {ahrs_v} Madgwick gain {MADGWICK_GAIN:g}"
    mh = f"ahrs {ahrs_v} Mahony kP {MAHONY_KP:g} kI {MAHONY_KI:g}"
    fus = f"imufusion {fus_v} defaults, set_quaternion+skip_startup"
    fusd = f"imufusion {fus_v} gain .5 range 2000 rej 10/10 timeout 5 + Bias"
    return [
        ("VQF 9D", True, f"vqf {vqf_v} VQF(Ts) defaults", partial(run_vqf, nine=True)),
        ("VQF 6D", False, f"vqf {vqf_v} VQF(Ts) defaults", partial(run_vqf, nine=False)),
        ("Fusion 9D", True, fus, partial(run_fusion, nine=True)),
        ("Fusion 6D", False, fus, partial(run_fusion, nine=False)),
        ("Fusion doc. 9D", True, fusd, partial(run_fusion, nine=True, documented=True)),
        ("Fusion doc. 6D", False, fusd, partial(run_fusion, nine=False, documented=True)),
        ("Madgwick 9D", True, mg, partial(run_madgwick, nine=True)),
        ("Madgwick 6D", False, mg, partial(run_madgwick, nine=False)),
        ("Mahony 9D", True, mh, partial(run_mahony, nine=True)),
        ("Mahony 6D", False, mh, partial(run_mahony, nine=False)),
    ]
