//! The three coordinate axes.

use core::ops::{Index, IndexMut};

use crate::{Ring, Vec3};

/// A coordinate axis: the axes of an Euler sequence, a body or principal axis of a rigid body.
///
/// `Vec3` components are read and written by axis (`v[Axis::Y]`), and [`Vec3::unit`] gives the
/// unit vector along one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The x axis (index 0).
    X,
    /// The y axis (index 1).
    Y,
    /// The z axis (index 2).
    Z,
}

impl Axis {
    /// The three axes in order.
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// 0 for x, 1 for y, 2 for z.
    #[inline]
    pub const fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// The axis with index `i` (0, 1, anything else → z).
    #[inline]
    pub const fn from_index(i: usize) -> Self {
        match i {
            0 => Axis::X,
            1 => Axis::Y,
            _ => Axis::Z,
        }
    }

    /// The next axis in cyclic order: x → y → z → x. `(a, a.next(), a.next().next())` is a
    /// right-handed triple.
    #[inline]
    pub const fn next(self) -> Self {
        match self {
            Axis::X => Axis::Y,
            Axis::Y => Axis::Z,
            Axis::Z => Axis::X,
        }
    }

    /// The axis that is neither `self` nor `other` (for distinct axes; for equal ones, the next
    /// after them).
    #[inline]
    pub const fn remaining(self, other: Axis) -> Self {
        match (self, other) {
            (Axis::X, Axis::Y) | (Axis::Y, Axis::X) => Axis::Z,
            (Axis::X, Axis::Z) | (Axis::Z, Axis::X) => Axis::Y,
            (Axis::Y, Axis::Z) | (Axis::Z, Axis::Y) => Axis::X,
            (a, _) => a.next(),
        }
    }
}

/// Component access by axis.
impl<T> Index<Axis> for Vec3<T> {
    type Output = T;
    #[inline]
    fn index(&self, axis: Axis) -> &T {
        match axis {
            Axis::X => &self.x,
            Axis::Y => &self.y,
            Axis::Z => &self.z,
        }
    }
}

/// Component access by axis.
impl<T> IndexMut<Axis> for Vec3<T> {
    #[inline]
    fn index_mut(&mut self, axis: Axis) -> &mut T {
        match axis {
            Axis::X => &mut self.x,
            Axis::Y => &mut self.y,
            Axis::Z => &mut self.z,
        }
    }
}

impl<T: Ring> Vec3<T> {
    /// The unit vector along `axis`.
    #[inline]
    pub fn unit(axis: Axis) -> Self {
        match axis {
            Axis::X => Self::X,
            Axis::Y => Self::Y,
            Axis::Z => Self::Z,
        }
    }
}
