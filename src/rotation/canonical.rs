//! The double cover: sign canonicalisation, distances, similarity transforms.

use crate::{Quat, Real, UnitQuat};

impl<T: Real> UnitQuat<T> {
    /// The SO(3) representative of `±q`: `w > 0`; if `w = 0` (a half-turn), the first non-zero
    /// of `x, y, z` is made positive. `−0.0` counts as zero.
    ///
    /// This is a choice for SO(3) uses (storage, comparisons, hashing, the MRP/axis-angle views).
    /// It throws away the spinor sign that SU(2) keeps (a 2π rotation is `−1`, (6.6.6c)); never
    /// apply it to a value whose sign is physical, such as a continuously propagated attitude
    /// that is differentiated or interpolated.
    ///
    /// ```
    /// use gyrostat::{Quat, UnitQuat};
    /// let q = UnitQuat::new_unchecked(Quat::new(0.0f64, 0.0, -1.0, 0.0));
    /// assert_eq!(q.canonical().to_array(), [0.0, 0.0, 1.0, 0.0]);
    /// ```
    pub fn canonical(self) -> Self {
        let q = *self.as_quat();
        let flip = if q.w != T::ZERO {
            q.w < T::ZERO
        } else if q.x != T::ZERO {
            q.x < T::ZERO
        } else if q.y != T::ZERO {
            q.y < T::ZERO
        } else {
            q.z < T::ZERO
        };
        if flip { -self } else { self }
    }

    /// `true` if `self` and `o` are the same rotation of vectors (`q ≡ ±o`) to within `tol` on
    /// the geodesic angle ([`UnitQuat::angle_to`]).
    #[inline]
    pub fn same_rotation(self, o: Self, tol: T) -> bool {
        self.angle_to(o) <= tol
    }

    /// The geodesic distance on SO(3) between two attitudes: the angle in `[0, π]` of the
    /// relative rotation `self⁻¹·o`, as `2·atan2(|v|, |w|)` of that product.
    ///
    /// Accurate for tiny angles (the vector part of the product is computed directly, unlike
    /// `2·acos(|q₁·q₂|)`, which loses everything below about `√ε`) and near π.
    #[inline]
    pub fn angle_to(self, o: Self) -> T {
        (self.inverse() * o).angle()
    }

    /// The similarity transform of the rotation `self` by `g`: `g·self·g⁻¹`, the rotation by the
    /// same angle about the axis `g·n̂` (seed (6.6.8): `R Θ·σ R†` rotates the whirl vector). In
    /// matrices, `R(g) R(self) R(g)ᵀ`.
    #[inline]
    pub fn similarity_transform(self, g: Self) -> Self {
        g * self * g.inverse()
    }

    /// `self` with the sign of `o`'s hemisphere: `self` or `−self`, whichever has `dot ≥ 0` with
    /// `o` (ties keep `self`). The same rotation; used to take the short way between attitudes.
    #[inline]
    pub fn closest_sign_to(self, o: Self) -> Self {
        if self.dot(o) < T::ZERO { -self } else { self }
    }

    /// Spherical linear interpolation on SO(3) along the shortest path:
    /// `self·exp(t·log(self⁻¹·o))`, with the relative rotation's sign chosen `w ≥ 0`.
    ///
    /// Exact for tiny steps: the relative rotation is a quaternion product and its log uses a
    /// series near zero, so two attitudes 1e-6 rad apart interpolate to the right intermediate
    /// point (never snapped to an endpoint because a dot product rounded to 1). `t` outside
    /// `[0, 1]` extrapolates along the same geodesic. At exactly 180° apart the shortest path is
    /// not unique; the one through the relative rotation's axis (sign per
    /// [`UnitQuat::canonical`]) is taken.
    ///
    /// Domain: any finite `t` (a NaN or infinite `t` gives a NaN result). Where `t` times the
    /// angle between the attitudes overflows (`|t|` beyond about `MAX/π`), the step's angle is
    /// reduced modulo the spinor period `4π` first; the result is then a unit quaternion whose
    /// angle has no correct digit (as it has none once `|t|·angle` exceeds `1/ε`).
    ///
    /// ```
    /// use gyrostat::{UnitQuat, Vec3};
    /// let a = UnitQuat::try_exp(Vec3::new(0.0f32, 0.0, 0.0))?;
    /// let b = UnitQuat::try_exp(Vec3::new(0.0f32, 0.0, 1e-6))?;
    /// let m = a.slerp(b, 0.5);
    /// assert!((m.angle_to(a) - 5e-7).abs() < 1e-12);
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    pub fn slerp(self, o: Self, t: T) -> Self {
        let rel = (self.inverse() * o).canonical();
        let phi = rel.log();
        let v = phi.scale(t);
        // The angle |t·φ| is representable (the square is tried first, the hypot only if it
        // overflows).
        let v = if v.norm_squared().is_finite() || v.norm().is_finite() {
            v
        } else {
            // |t|·θ overflowed (θ = |φ| ≤ π, so |t| > MAX/π): reduce the spinor angle t·θ
            // modulo 4π through the number of turns t·θ/(4π), which is finite (θ ≤ π).
            let four_pi = T::from_f64(4.0) * T::PI;
            let theta = phi.norm();
            let turns = t * (theta / four_pi);
            let frac = turns - turns.floor();
            phi.scale(frac * four_pi / theta)
        };
        self * UnitQuat::exp_unchecked(v)
    }

    /// Normalised linear interpolation: `normalize((1 − t)·self + t·o')` with `o' = ±o` on
    /// `self`'s hemisphere. Cheaper than [`UnitQuat::slerp`]; same endpoints and path, but not
    /// constant angular rate (the angle error peaks at `t = 1/2`, about `θ³/32` rad for
    /// attitudes `θ` apart). For `t` in `[0, 1]` the unnormalised sum has norm `≥ 1/√2`, so the
    /// normalisation is safe.
    pub fn nlerp(self, o: Self, t: T) -> Self {
        let o = o.closest_sign_to(self);
        let a: Quat<T> = self.into();
        let b: Quat<T> = o.into();
        let q = a.scale(T::ONE - t) + b.scale(t);
        let n = q.norm();
        if n > T::ZERO && n.is_finite() {
            UnitQuat::new_unchecked(q.scale(T::ONE / n))
        } else {
            // Only for t far outside [0, 1] (or non-finite t): fall back to the nearer endpoint.
            if t < T::HALF { self } else { o }
        }
    }
}
