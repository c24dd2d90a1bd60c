//! How the sensor is mounted in the body: one of the 24 signed axis permutations
//! ([`AxisRemap`]) or an arbitrary rotation ([`Mounting`]).
//!
//! # Convention
//! Both map a vector from sensor axes to body axes, `v_body = R_bs · v_sensor`. An
//! [`AxisRemap`] says, for each body axis, which sensor axis it is and with which sign: the remap
//! written `x,-z,y` is `body x = sensor x`, `body y = −sensor z`, `body z = sensor y`, so
//! `R_bs` has one `±1` per row. Only proper rotations (`det R_bs = +1`) are accepted: of the 48
//! signed permutation matrices, the 24 with determinant −1 are reflections, which would turn a
//! right-handed sensor frame into a left-handed body frame (every cross product, hence every
//! coning term and the attitude's handedness, would change sign) and are rejected with
//! [`Error::NotRotation`]. A sensor whose own axes are left-handed is not a mounting problem.
//!
//! Attitudes: with `q_ls` the attitude of the sensor frame (sensor → lab), the body's is
//! `q_lb = q_ls ⊗ q_bs*` ([`Mounting::body_attitude`]); rates and increments are rotated as
//! vectors ([`Mounting::to_body`], [`AxisRemap::apply`]). A remap is exact in every number format
//! (a permutation and negations; fixed point's symmetric range makes negation exact).

use crate::{Axis, Dcm, Error, Mat3, Real, Ring, UnitQuat, Vec3};

/// One of the 24 proper signed axis permutations: `body[i] = ±sensor[source[i]]` (see the
/// [module docs](self)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AxisRemap {
    source: [Axis; 3],
    negate: [bool; 3],
}

impl AxisRemap {
    /// The identity remap `x,y,z`.
    pub const IDENTITY: Self = Self {
        source: [Axis::X, Axis::Y, Axis::Z],
        negate: [false; 3],
    };

    /// The remap `body[i] = (negate[i] ? −1 : 1) · sensor[source[i]]`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `source` repeats an axis (not a permutation);
    /// [`Error::NotRotation`] for a reflection (determinant −1).
    pub fn try_new(source: [Axis; 3], negate: [bool; 3]) -> Result<Self, Error> {
        let [a, b, c] = source;
        if a == b || b == c || a == c {
            return Err(Error::InvalidArgument);
        }
        // An even permutation is a cyclic shift of x, y, z.
        let even = b == a.next();
        let negations = negate.iter().filter(|&&n| n).count();
        if even != (negations % 2 == 0) {
            return Err(Error::NotRotation);
        }
        Ok(Self { source, negate })
    }

    /// Parses the text form `x,-z,y`: three comma-separated body axes in order x, y, z, each
    /// the sensor axis it is (`x`, `y` or `z`, either case) with an optional sign `+` or `-`;
    /// blanks (spaces, tabs) anywhere are ignored.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for text not of that form or an axis given twice;
    /// [`Error::NotRotation`] for a reflection.
    pub fn try_parse(text: &str) -> Result<Self, Error> {
        // A byte scanner, not `str::split`: no slicing, so no bounds check on the firmware path.
        let mut source = [Axis::X; 3];
        let mut negate = [false; 3];
        let mut item = 0usize;
        let (mut sign, mut axis) = (None, None);
        for &b in text.as_bytes().iter().chain(core::iter::once(&b',')) {
            match b {
                b' ' | b'\t' => {}
                b'+' | b'-' if sign.is_none() && axis.is_none() => sign = Some(b == b'-'),
                b'x' | b'X' if axis.is_none() => axis = Some(Axis::X),
                b'y' | b'Y' if axis.is_none() => axis = Some(Axis::Y),
                b'z' | b'Z' if axis.is_none() => axis = Some(Axis::Z),
                b',' => {
                    let (Some(a), Some(s), Some(n)) =
                        (axis, source.get_mut(item), negate.get_mut(item))
                    else {
                        return Err(Error::InvalidArgument);
                    };
                    *s = a;
                    *n = sign.unwrap_or(false);
                    item = item.saturating_add(1);
                    (sign, axis) = (None, None);
                }
                _ => return Err(Error::InvalidArgument),
            }
        }
        if item != 3 {
            return Err(Error::InvalidArgument);
        }
        Self::try_new(source, negate)
    }

    /// The 24 proper remaps, in the order: permutations `xyz, yzx, zxy, xzy, yxz, zyx`, each with
    /// its four sign patterns of even (odd, for the last three) count of negations, in binary
    /// order of `negate`.
    pub fn all() -> [Self; 24] {
        let perms = [
            [Axis::X, Axis::Y, Axis::Z],
            [Axis::Y, Axis::Z, Axis::X],
            [Axis::Z, Axis::X, Axis::Y],
            [Axis::X, Axis::Z, Axis::Y],
            [Axis::Y, Axis::X, Axis::Z],
            [Axis::Z, Axis::Y, Axis::X],
        ];
        let mut out = [Self::IDENTITY; 24];
        let mut slots = out.iter_mut();
        for source in perms {
            for bits in 0u8..8 {
                let negate = [bits & 4 != 0, bits & 2 != 0, bits & 1 != 0];
                if let Ok(r) = Self::try_new(source, negate)
                    && let Some(slot) = slots.next()
                {
                    *slot = r;
                }
            }
        }
        out
    }

    /// The sensor axis each body axis is taken from.
    pub fn source(&self) -> [Axis; 3] {
        self.source
    }

    /// Which body axes are negated.
    pub fn negate(&self) -> [bool; 3] {
        self.negate
    }

    /// `v_body = R_bs · v_sensor`, exact (a permutation and negations).
    #[inline]
    pub fn apply<T: Ring>(&self, v: Vec3<T>) -> Vec3<T> {
        let pick = |i: usize| {
            let (s, n) = match i {
                0 => (self.source[0], self.negate[0]),
                1 => (self.source[1], self.negate[1]),
                _ => (self.source[2], self.negate[2]),
            };
            if n { -v[s] } else { v[s] }
        };
        Vec3::new(pick(0), pick(1), pick(2))
    }

    /// The inverse remap (`R_bsᵀ`): `v_sensor` from `v_body`.
    pub fn inverse(&self) -> Self {
        let mut source = [Axis::X; 3];
        let mut negate = [false; 3];
        for (i, (s, n)) in self.source.iter().zip(self.negate).enumerate() {
            let j = s.index();
            if let (Some(src), Some(neg)) = (source.get_mut(j), negate.get_mut(j)) {
                *src = Axis::from_index(i);
                *neg = n;
            }
        }
        Self { source, negate }
    }

    /// The matrix `R_bs` (one `±1` per row and column).
    pub fn matrix<T: Ring>(&self) -> Mat3<T> {
        Mat3::from_cols(
            self.apply(Vec3::unit(Axis::X)),
            self.apply(Vec3::unit(Axis::Y)),
            self.apply(Vec3::unit(Axis::Z)),
        )
    }

    /// The rotation `q_bs` (sensor → body) as a unit quaternion.
    pub fn to_unit_quat<T: Real>(&self) -> UnitQuat<T> {
        Dcm::from_matrix_unchecked(self.matrix()).to_unit_quat()
    }
}

/// An arbitrary mounting rotation `q_bs`: `v_body = q_bs ⊗ v_sensor ⊗ q_bs*` (see the
/// [module docs](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mounting<T> {
    body_from_sensor: UnitQuat<T>,
}

impl<T: Ring> Mounting<T> {
    /// The mounting whose sensor-to-body rotation is `body_from_sensor`.
    pub fn new(body_from_sensor: UnitQuat<T>) -> Self {
        Self { body_from_sensor }
    }

    /// `q_bs`.
    pub fn body_from_sensor(&self) -> UnitQuat<T> {
        self.body_from_sensor
    }

    /// A rate, increment or specific force in body axes: `q_bs ⊗ v ⊗ q_bs*`.
    #[inline]
    pub fn to_body(&self, v_sensor: Vec3<T>) -> Vec3<T> {
        self.body_from_sensor.rotate(v_sensor)
    }

    /// The body attitude from the sensor frame's: `q_lb = q_ls ⊗ q_bs*`.
    #[inline]
    pub fn body_attitude(&self, sensor_attitude: UnitQuat<T>) -> UnitQuat<T> {
        sensor_attitude * self.body_from_sensor.inverse()
    }

    /// The sensor frame's attitude from the body's: `q_ls = q_lb ⊗ q_bs`.
    #[inline]
    pub fn sensor_attitude(&self, body_attitude: UnitQuat<T>) -> UnitQuat<T> {
        body_attitude * self.body_from_sensor
    }
}

impl<T: Real> From<AxisRemap> for Mounting<T> {
    fn from(r: AxisRemap) -> Self {
        Self::new(r.to_unit_quat())
    }
}
