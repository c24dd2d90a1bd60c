// The fixed rotation cases of the `fw_rotations` firmware example, shared (by `include!`) with the
// host test that checks the firmware's output against the independent f64 reference
// (host-tests/tests/rotation/firmware.rs). Each case: (axis1, angle1, axis2, angle2, vector); the
// firmware composes q = q(axis1, angle1) ⊗ q(axis2, angle2) and rotates the vector by it.
// Angles in radians. Axes need not be unit length.

/// Number of cases.
pub const N_CASES: usize = 9;

/// (axis1, angle1, axis2, angle2, vector), all f32.
#[allow(clippy::type_complexity, clippy::approx_constant)]
pub const CASES: [([f32; 3], f32, [f32; 3], f32, [f32; 3]); N_CASES] = [
    ([0.0, 0.0, 1.0], 0.0, [1.0, 0.0, 0.0], 0.0, [1.0, 0.0, 0.0]),
    ([0.0, 0.0, 1.0], 1.570_796_4, [1.0, 0.0, 0.0], 1.570_796_4, [1.0, 0.0, 0.0]),
    ([1.0, 2.0, 3.0], 0.7, [-2.0, 0.5, 1.0], -1.3, [0.3, -0.4, 0.5]),
    ([0.0, 1.0, 0.0], 3.141_592_7, [0.0, 1.0, 0.0], 3.141_592_7, [0.6, 0.0, -0.8]),
    ([1.0, 1.0, 1.0], 6.283_185_5, [0.0, 0.0, 1.0], 0.25, [0.0, 1.0, 0.0]),
    ([0.3, -0.2, 0.9], 1.0e-4, [0.1, 0.9, -0.4], 2.0e-5, [1.0, 1.0, 0.0]),
    ([-1.0, 0.2, 0.1], 2.5, [0.4, 0.4, -0.8], 2.9, [-0.2, 0.7, 0.7]),
    ([5.0, 0.0, 1.0], 9.0, [0.0, -3.0, 0.5], -7.5, [1.5, -0.5, 0.25]),
    ([0.0, 0.0, 2.0], 3.0, [2.0, 0.0, 0.0], 1.0e-3, [0.0, 0.0, 1.0]),
];
