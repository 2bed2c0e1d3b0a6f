//! The forward model of readings, `p(d | map)`: which readings a beam is
//! predicted to give on a map (see the [module documentation](super)).

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result, check_parameter};
use crate::footprint::{CellVisitor, visit};
use crate::grid::Grid;
use crate::pose::{Pose, check_pose};
use crate::sensor::{Footprint, RangeModel};

/// Which coverage value of a cell stops a predicted beam.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopCoverage {
    /// The most probable coverage (the paper's choice). A cell still at the
    /// uniform prior reads 0: unknown space is predicted to let beams through,
    /// which makes looking into it worth a lot.
    #[default]
    MaximumLikelihood,
    /// The expected coverage: unknown space (0.5) stops beams quickly.
    Mean,
}

/// The predicted readings of one beam: `probabilities[j]` is the probability of
/// reading `j * step_m` (all below the maximum range), `no_echo` that of no echo.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadingDistribution {
    /// Spacing of the readings, metres.
    pub step_m: f64,
    /// Probability of each reading.
    pub probabilities: Vec<f64>,
    /// Probability of no echo.
    pub no_echo: f64,
}

/// Predict the readings of a beam from `origin` along `angle_rad` by tracing
/// its axis through `stop` (one coverage value per cell); see the
/// [module documentation](crate::sensor). Readings past the map's far corner
/// cannot occur and get no slot.
///
/// Errors if `stop` does not hold one value per cell, the origin is not
/// finite or lies outside the grid, the angle is not finite, the range model
/// is invalid, or `step_m` is not a step between [`MIN_STEP_FRACTION`] of
/// the grid resolution and the resolution.
pub fn reading_distribution(
    grid: &Grid,
    stop: &[f32],
    origin: [f64; 2],
    angle_rad: f64,
    range: &RangeModel,
    step_m: f64,
) -> Result<ReadingDistribution> {
    if stop.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "stop coverage and grid cells",
            left: stop.len(),
            right: grid.len(),
        });
    }
    check_pose(grid, &Pose::new(origin[0], origin[1], angle_rad))?;
    range.validate()?;
    check_range_step(step_m, Some(grid.resolution_m()))?;
    Ok(trace_readings(grid, stop, origin, angle_rad, range, step_m))
}

/// The finest spacing of hypothetical readings, as a fraction of the grid
/// resolution (the kernels resolve a reading to 1/32 of a cell).
pub const MIN_STEP_FRACTION: f64 = 1.0 / 1024.0;

/// Errors unless `step_m` is a valid spacing of predicted readings: between
/// [`MIN_STEP_FRACTION`] of the grid's resolution and the resolution, or,
/// where no grid is known yet (`resolution_m` is `None`), positive and finite.
/// The one check of `range_step_m`, for the gain, the planner's settings and
/// the bindings.
pub fn check_range_step(step_m: f64, resolution_m: Option<f64>) -> Result<()> {
    let ok = match resolution_m {
        Some(resolution_m) => step_m >= MIN_STEP_FRACTION * resolution_m && step_m <= resolution_m,
        None => step_m > 0.0 && step_m.is_finite(),
    };
    check_parameter(
        ok,
        "range_step_m",
        step_m,
        "a step between 1/1024 of the grid resolution and the resolution",
    )
}

/// [`reading_distribution`] of valid inputs.
pub(crate) fn trace_readings(
    grid: &Grid,
    stop: &[f32],
    origin: [f64; 2],
    angle_rad: f64,
    range: &RangeModel,
    step_m: f64,
) -> ReadingDistribution {
    trace_readings_with(grid, stop, origin, angle_rad, range, step_m, |_| {})
}

/// [`trace_readings`], calling `read` with the row-major index of every cell
/// whose stop coverage the result depends on: each cell of the ray, in
/// order, up to and including the first that stops the beam with certainty
/// (the trace reads none after it). What the planning cache needs to know
/// of a gain's reads, found by the trace itself.
pub(crate) fn trace_readings_with(
    grid: &Grid,
    stop: &[f32],
    origin: [f64; 2],
    angle_rad: f64,
    range: &RangeModel,
    step_m: f64,
    read: impl FnMut(usize),
) -> ReadingDistribution {
    let r = grid.resolution_m();
    // A reading ends at most half a cell past the centre of a cell the beam
    // crosses, so none lies beyond the map's farthest corner plus a cell.
    let [x0, y0, x1, y1] = grid.bounds_m();
    let far = (origin[0] - x0)
        .max(x1 - origin[0])
        .hypot((origin[1] - y0).max(y1 - origin[1]));
    let limit = ((far + r) / step_m).ceil() + 1.0;
    let wanted = (range.max_range_m / step_m).ceil();
    let slots = if wanted > limit {
        // Every one of these readings lies below the maximum range.
        limit as usize
    } else {
        // The readings `j * step_m` below the maximum range.
        let n = wanted as usize;
        (0..=n)
            .rev()
            .find(|&j| (j as f64) * step_m < range.max_range_m)
            .map_or(0, |j| j + 1)
    };
    let mut trace = Trace {
        stop,
        resolution_m: r,
        step_m,
        probabilities: vec![0.0; slots],
        through: 1.0,
        read,
    };
    visit(
        grid,
        origin,
        angle_rad,
        range.max_range_m,
        Footprint::Ray,
        &mut trace,
    );
    let Trace {
        probabilities,
        through,
        ..
    } = trace;
    ReadingDistribution {
        step_m,
        probabilities,
        no_echo: through,
    }
}

/// The trace of a beam's axis: the recurrence of the probability of getting
/// through each cell, and the readings' probabilities it gives. Done once
/// that probability is 0: no later cell changes anything, so the walk stops
/// there (most beams end at a wall well inside the maximum range).
struct Trace<'s, R> {
    stop: &'s [f32],
    resolution_m: f64,
    step_m: f64,
    probabilities: Vec<f64>,
    /// The probability that the beam gets this far.
    through: f64,
    read: R,
}

impl<R: FnMut(usize)> CellVisitor for Trace<'_, R> {
    #[inline(always)]
    fn cell(&mut self, i: usize, d_l: f64, _enter_m: f64) {
        if self.through <= 0.0 {
            return;
        }
        (self.read)(i);
        let c = f64::from(self.stop[i]);
        if c <= 0.0 {
            return;
        }
        let r = self.resolution_m;
        let d = (d_l + 0.5 * r - c * r).max(0.0);
        let j = (d / self.step_m).round() as usize;
        if j < self.probabilities.len() {
            self.probabilities[j] += self.through * c;
            self.through *= 1.0 - c;
        }
    }

    #[inline(always)]
    fn done(&self) -> bool {
        self.through <= 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::SonarModel;

    #[test]
    fn readings_sum_to_one() {
        let grid = Grid::new([0.0, 0.0], 0.05, 100, 100).unwrap();
        let mut stop = vec![0.0; grid.len()];
        for row in 0..100 {
            stop[grid.index(crate::Cell { row, col: 60 }).unwrap()] = 0.4;
            stop[grid.index(crate::Cell { row, col: 80 }).unwrap()] = 1.0;
        }
        let range = SonarModel::default().range;
        let d = reading_distribution(&grid, &stop, [1.025, 2.525], 0.0, &range, 0.05).unwrap();
        let total: f64 = d.probabilities.iter().sum::<f64>() + d.no_echo;
        assert!((total - 1.0).abs() < 1e-12);
        assert_eq!(d.no_echo, 0.0, "the full wall stops every beam");
        // The partial cell at x in [3.0, 3.05) reflects 40 %, at 3.05 - 0.4 * 0.05 = 3.03.
        let j = ((3.03 - 1.025) / 0.05f64).round() as usize;
        assert!(
            (d.probabilities[j] - 0.4).abs() < 1e-7,
            "{:?}",
            &d.probabilities[35..45]
        );
        let open =
            reading_distribution(&grid, &vec![0.0; grid.len()], [1.0, 1.0], 0.3, &range, 0.05)
                .unwrap();
        assert_eq!(open.no_echo, 1.0);
    }

    /// The trace stops where the beam can get no farther, and gives what a
    /// walk of the whole ray gives, bit for bit, reading every cell up to
    /// that one: on random maps of partly and fully stopping cells.
    #[test]
    fn stopping_the_trace_at_certain_stop_changes_nothing() {
        let grid = Grid::new([0.0, 0.0], 0.05, 80, 120).unwrap();
        let range = SonarModel::default().range;
        let mut next = crate::test_rng::uniform(9);
        for trial in 0..300 {
            let stop: Vec<f32> = (0..grid.len())
                .map(|_| match next() {
                    u if u < 0.02 => 1.0,
                    u if u < 0.06 => (0.1 + next()) as f32 * 0.8,
                    _ => 0.0,
                })
                .collect();
            let origin = [0.1 + 5.8 * next(), 0.1 + 3.8 * next()];
            let angle = 7.0 * next();
            let mut read = Vec::new();
            let d =
                trace_readings_with(&grid, &stop, origin, angle, &range, 0.05, |i| read.push(i));
            // The whole ray, as the trace was first written.
            let (r, step_m) = (grid.resolution_m(), 0.05);
            let mut probabilities = vec![0.0; d.probabilities.len()];
            let (mut through, mut reads) = (1.0f64, Vec::new());
            visit(
                &grid,
                origin,
                angle,
                range.max_range_m,
                Footprint::Ray,
                &mut |i: usize, d_l: f64| {
                    if through <= 0.0 {
                        return;
                    }
                    reads.push(i);
                    let c = f64::from(stop[i]);
                    if c > 0.0 {
                        let j = ((d_l + 0.5 * r - c * r).max(0.0) / step_m).round() as usize;
                        if j < probabilities.len() {
                            probabilities[j] += through * c;
                            through *= 1.0 - c;
                        }
                    }
                },
            );
            let bits = |p: &[f64]| p.iter().map(|p| p.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&d.probabilities),
                bits(&probabilities),
                "trial {trial}"
            );
            assert_eq!(d.no_echo.to_bits(), through.to_bits(), "trial {trial}");
            assert_eq!(read, reads, "trial {trial}");
        }
    }
}
