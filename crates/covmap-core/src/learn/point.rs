//! A point of the search space, with the arithmetic Nelder-Mead needs.

use argmin_math::{ArgminAdd, ArgminMul, ArgminSub};

/// The fitted parameters, each scaled to `[0, 1]` between its bounds.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Point(pub(super) Vec<f64>);

impl ArgminAdd<Point, Point> for Point {
    fn add(&self, other: &Point) -> Point {
        Point(self.0.iter().zip(&other.0).map(|(a, b)| a + b).collect())
    }
}

impl ArgminSub<Point, Point> for Point {
    fn sub(&self, other: &Point) -> Point {
        Point(self.0.iter().zip(&other.0).map(|(a, b)| a - b).collect())
    }
}

impl ArgminMul<f64, Point> for Point {
    fn mul(&self, factor: &f64) -> Point {
        Point(self.0.iter().map(|a| a * factor).collect())
    }
}
