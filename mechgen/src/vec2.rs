//! Planar vectors, for tracked points.

/// A point or vector in the plane, in the mechanism's frame (x along the ground link's
/// reference direction, y counter-clockwise from it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec2<T> {
    /// The x component.
    pub x: T,
    /// The y component.
    pub y: T,
}

impl<T: crate::Real> Vec2<T> {
    /// A vector from its components.
    pub const fn new(x: T, y: T) -> Self {
        Vec2 { x, y }
    }

    /// Its length.
    pub fn norm(self) -> T {
        self.x.hypot(self.y)
    }

    /// Its direction, counter-clockwise from +x, in (-π, π].
    pub fn angle(self) -> T {
        self.y.atan2(self.x)
    }
}
