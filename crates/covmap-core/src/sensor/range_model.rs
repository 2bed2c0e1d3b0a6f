//! The inverse model along one direction, shared by every range sensor.

use serde::{Deserialize, Serialize};

use super::KernelTable;
use super::kernel;
use crate::error::{Result, check_parameter};

/// The parameters shared by every range sensor: the inverse model along one
/// direction (see the [module documentation](super)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeModel {
    /// Readings at or beyond this distance mean "no echo", metres.
    pub max_range_m: f64,
    /// How far behind the end point cells are updated (as covered), metres.
    pub band_m: f64,
    /// Standard deviation of the coverage mean at zero distance, outside the end band.
    pub sigma_min: f64,
    /// Growth of that standard deviation per metre of distance `s = min(d_l, d)`.
    pub sigma_per_m: f64,
    /// The constant standard deviation inside the end band (the largest of all).
    pub sigma_end: f64,
    /// Weight of the uniform component at zero distance (must be positive).
    pub xi_min: f64,
    /// Growth of the uniform weight per metre of distance `s = min(d_l, d)`.
    pub xi_per_m: f64,
    /// How far a no-echo reading clears its footprint, as a fraction of
    /// `max_range_m`, in `(0, 1]`. 1 (the default): out to the maximum range,
    /// as the paper reads it.
    #[serde(default = "one")]
    pub no_echo_reach: f64,
    /// How strongly a no-echo reading clears, in `[0, 1]`: its kernel is
    /// `no_echo_weight * k_free + (1 - no_echo_weight) / bins`, a mixture of
    /// the free-space kernel and the uniform prior. 1 (the default): the
    /// free-space kernel, as the paper reads it; 0: a no-echo reading
    /// leaves the map as it was. A specular miss (a sonar pulse that glanced
    /// off a wall and never came back) is a no-echo reading through a wall,
    /// so a weight below 1 keeps such misses from erasing walls that echoes
    /// from other angles found.
    #[serde(default = "one")]
    pub no_echo_weight: f64,
    /// How strongly an echo marks the cells at and behind its end point
    /// (the end band and the band behind it), in `[0, 1]`: their kernels
    /// are mixed with the uniform prior as no-echo kernels are. 1 (the
    /// default): the paper's kernels. A sonar's echo comes from somewhere
    /// on the arc of its cone, so most cells of the arc are not what it
    /// hit; a weight below 1 says so, where 1 marks the whole arc covered.
    #[serde(default = "one")]
    pub end_weight: f64,
    /// The least probability an update that contradicts a cell leaves any
    /// bin of its histogram, in `[0, 1/256]`: after an update whose
    /// kernel's mean coverage lies on the other side of 1/2 from the cell's
    /// mean before it, the cell's posterior is mixed with the uniform
    /// prior, `(1 - bins p) h + p`. 0 (the default): the paper's Bayes
    /// update (bins floored at 1e-30 only). Readings of one cell are not
    /// independent (a sonar sees the same wall face from the same places
    /// again and again), so the product of their kernels grows far more
    /// confident than the evidence is; where readings disagree, that
    /// confidence is likely wrong, and the floor caps what it can cost.
    /// Updates that agree with a cell (and the first of a cell at the
    /// prior) mix nothing in, so the floor fades as agreeing readings
    /// accumulate, and a cell every reading finds free keeps a mean
    /// coverage near 0.
    #[serde(default)]
    pub posterior_floor: f64,
    /// How far an echo's marks follow what the map already holds, in
    /// `[0, 1]`. A sonar's echo comes from somewhere on the arc of its
    /// cone, most likely where the map holds the most coverage: the kernels
    /// of the end band and the band behind it are mixed with the uniform
    /// prior by the weight `1 - a + a min(1, m / m_arc)`, `a` this value,
    /// `m` the cell's mean coverage before the reading and `m_arc` the
    /// largest mean coverage among the end band's cells (at least 1/2). An
    /// arc across cells the map holds free and a wall the map holds covered
    /// so marks the wall. 0 (the default): every cell of the arc alike, as
    /// the paper reads it.
    #[serde(default)]
    pub end_attribution: f64,
    /// How much a free-space update spares a cell the map holds covered,
    /// in `[0, 1]`. A surface met at a grazing angle sends no echo back, so
    /// a beam that passes a covered cell without an echo from it says
    /// little about the cell: the free kernel (of echoes and no-echo
    /// readings alike) of a cell of mean coverage `m` is mixed with the
    /// uniform prior by the weight `1 - y min(1, max(0, 2 m - 1))`, `y` this
    /// value. 0 (the default): the paper's reading.
    #[serde(default)]
    pub free_yield: f64,
}

/// The default of the no-echo parameters: the paper's reading.
fn one() -> f64 {
    1.0
}

/// The largest `posterior_floor`: one bin's share of the largest histogram.
const MAX_POSTERIOR_FLOOR: f64 = 1.0 / crate::histogram::MAX_BINS as f64;

/// The smallest `sigma_min`: a standard deviation of coverage (which spans
/// 0 to 1) a millionth wide is already a spike between the bins; far below
/// it (near 1e-308) the density's scale would overflow.
const MIN_SIGMA: f64 = 1e-6;
/// The largest uniform weight `xi` anywhere up to the maximum range: beyond
/// it the kernel is uniform to far below `f32` precision anyway, and the sum
/// that normalises it could overflow.
const MAX_XI: f64 = 1e6;
/// The largest `max_range_m`: ten kilometres, far beyond any range sensor
/// a robot carries (and any map's extent at a useful resolution).
const MAX_RANGE_M: f64 = 1e4;

impl RangeModel {
    /// Errors unless every parameter lies in its valid range: the distances
    /// positive (`band_m` non-negative, `max_range_m` at most 10 km), `sigma_min` at least 1e-6,
    /// `sigma_end` no smaller than `sigma` anywhere outside the band, `xi_min`
    /// positive, the growths non-negative, and the uniform weight at most 1e6
    /// out to the maximum range.
    pub fn validate(&self) -> Result<()> {
        fn check(name: &'static str, value: f64, ok: bool, expected: &'static str) -> Result<()> {
            check_parameter(ok && value.is_finite(), name, value, expected)
        }
        check(
            "max_range_m",
            self.max_range_m,
            self.max_range_m > 0.0 && self.max_range_m <= MAX_RANGE_M,
            "a positive distance of at most 10 km",
        )?;
        check(
            "band_m",
            self.band_m,
            self.band_m >= 0.0,
            "a non-negative distance",
        )?;
        check(
            "sigma_min",
            self.sigma_min,
            self.sigma_min >= MIN_SIGMA,
            "a standard deviation of at least 1e-6 (coverage)",
        )?;
        check(
            "sigma_per_m",
            self.sigma_per_m,
            self.sigma_per_m >= 0.0,
            "a non-negative growth",
        )?;
        check(
            "xi_min",
            self.xi_min,
            self.xi_min > 0.0 && self.xi_min <= MAX_XI,
            "a positive weight of at most 1e6",
        )?;
        check(
            "xi_per_m",
            self.xi_per_m,
            self.xi_per_m >= 0.0,
            "a non-negative growth",
        )?;
        check(
            "xi_per_m",
            self.xi_per_m,
            self.xi(self.max_range_m) <= MAX_XI,
            "a growth that keeps xi_min + xi_per_m * max_range_m at most 1e6",
        )?;
        check(
            "no_echo_reach",
            self.no_echo_reach,
            self.no_echo_reach > 0.0 && self.no_echo_reach <= 1.0,
            "a fraction of the maximum range in (0, 1]",
        )?;
        check(
            "no_echo_weight",
            self.no_echo_weight,
            (0.0..=1.0).contains(&self.no_echo_weight),
            "a weight in [0, 1]",
        )?;
        check(
            "posterior_floor",
            self.posterior_floor,
            (0.0..=MAX_POSTERIOR_FLOOR).contains(&self.posterior_floor),
            "a probability in [0, 1/256]",
        )?;
        check(
            "end_attribution",
            self.end_attribution,
            (0.0..=1.0).contains(&self.end_attribution),
            "a weight in [0, 1]",
        )?;
        check(
            "free_yield",
            self.free_yield,
            (0.0..=1.0).contains(&self.free_yield),
            "a weight in [0, 1]",
        )?;
        check(
            "end_weight",
            self.end_weight,
            (0.0..=1.0).contains(&self.end_weight),
            "a weight in [0, 1]",
        )?;
        let widest = self.sigma(self.max_range_m);
        check(
            "sigma_end",
            self.sigma_end,
            self.sigma_end >= widest,
            "a standard deviation no smaller than sigma anywhere outside the band (sigma_min + sigma_per_m * max_range_m)",
        )
    }

    /// `sigma` outside the end band at distance `s_m = min(d_l, d)`.
    pub fn sigma(&self, s_m: f64) -> f64 {
        self.sigma_min + self.sigma_per_m * s_m
    }

    /// The uniform weight at distance `s_m = min(d_l, d)`.
    pub fn xi(&self, s_m: f64) -> f64 {
        self.xi_min + self.xi_per_m * s_m
    }

    /// How far along the beam a reading of `range_m` reaches, and whether it is
    /// an echo (`false`: no echo, clear up to `no_echo_reach` of the maximum
    /// range).
    pub fn reach(&self, range_m: f64) -> (f64, bool) {
        if range_m >= self.max_range_m {
            (self.no_echo_reach_m(), false)
        } else {
            (range_m + self.band_m, true)
        }
    }

    /// How far a no-echo reading clears, metres: `no_echo_reach * max_range_m`.
    pub fn no_echo_reach_m(&self) -> f64 {
        if self.no_echo_reach >= 1.0 {
            self.max_range_m
        } else {
            self.no_echo_reach * self.max_range_m
        }
    }

    /// Whether a no-echo reading's kernel is the free-space kernel itself
    /// (`no_echo_weight` 1), rather than a mixture with the prior.
    pub fn no_echo_is_free(&self) -> bool {
        self.no_echo_weight >= 1.0
    }

    /// The kernel the map multiplies in for a cell at `cell_distance_m` and a
    /// reading of `measured_distance_m`, on a grid of `resolution_m` with `bins`
    /// bins, or `None` where the cell is not updated. It comes from the same
    /// precomputed table the update uses (built anew on every call: for
    /// looking at kernels, not for loops).
    ///
    /// Errors if the model is invalid, the resolution is not finite or below
    /// [`crate::MIN_RESOLUTION_M`], the bin count is not supported, or a
    /// distance is NaN, infinite or negative.
    pub fn kernel(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Result<Option<Vec<f32>>> {
        check_distances(cell_distance_m, measured_distance_m)?;
        let table = KernelTable::new(self, resolution_m, bins)?;
        Ok(table.kernel_at(cell_distance_m, measured_distance_m))
    }

    /// The exact (unquantised) kernel for a cell at `cell_distance_m` and a
    /// reading of `measured_distance_m`, on a grid of `resolution_m` with `bins`
    /// bins: the histogram the update multiplies in, normalised to sum 1, or
    /// `None` where the cell is not updated (further than the band behind the
    /// end point). This is the reference the kernel table is tested against.
    ///
    /// Errors as [`Self::kernel`] does.
    pub fn kernel_exact(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Result<Option<Vec<f64>>> {
        check_distances(cell_distance_m, measured_distance_m)?;
        self.validate()?;
        kernel::check_resolution(resolution_m)?;
        crate::histogram::check_bins(bins)?;
        Ok(self.exact_kernel(cell_distance_m, measured_distance_m, resolution_m, bins))
    }

    /// [`Self::kernel_exact`] of valid inputs.
    fn exact_kernel(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Option<Vec<f64>> {
        let (reach, echo) = self.reach(measured_distance_m);
        if cell_distance_m > reach {
            return None;
        }
        let d = measured_distance_m.min(self.max_range_m);
        let s = cell_distance_m.max(0.0).min(d);
        let o = cell_distance_m - d;
        let half = 0.5 * resolution_m;
        let (mu, sigma) = if !echo || o < -half {
            (0.0, self.sigma(s))
        } else if o <= half {
            (0.5 + o / resolution_m, self.sigma_end)
        } else {
            (1.0, self.sigma(s))
        };
        let k = kernel_values(mu, sigma, self.xi(s), bins);
        Some(if !echo {
            self.no_echo_mixture(k)
        } else if o >= -half {
            self.end_mixture(k)
        } else {
            k
        })
    }

    /// A kernel of the end band or behind it as an echo gives it: mixed
    /// with the uniform prior by `end_weight` (unchanged at weight 1).
    pub(crate) fn end_mixture(&self, k: Vec<f64>) -> Vec<f64> {
        mixture(k, self.end_weight)
    }

    /// A free-space kernel `k` as a no-echo reading gives it: mixed with the
    /// uniform prior by `no_echo_weight` (unchanged at weight 1).
    pub(crate) fn no_echo_mixture(&self, k: Vec<f64>) -> Vec<f64> {
        mixture(k, self.no_echo_weight)
    }
}

/// `w k + (1 - w) / bins`: kernel `k` mixed with the uniform prior by the
/// weight `w` (`k` itself at weight 1).
fn mixture(mut k: Vec<f64>, w: f64) -> Vec<f64> {
    if w < 1.0 {
        let uniform = 1.0 / k.len() as f64;
        k.iter_mut().for_each(|v| *v = w * *v + (1.0 - w) * uniform);
    }
    k
}

/// Errors unless both distances of a kernel query are finite and
/// non-negative.
fn check_distances(cell_distance_m: f64, measured_distance_m: f64) -> Result<()> {
    for (name, value) in [
        ("cell_distance_m", cell_distance_m),
        ("measured_distance_m", measured_distance_m),
    ] {
        check_parameter(
            value.is_finite() && value >= 0.0,
            name,
            value,
            "a finite, non-negative distance",
        )?;
    }
    Ok(())
}

/// `xi + N(x_b; mu, sigma)` at the bin values `x_b = b / (bins - 1)`, normalised.
pub(crate) fn kernel_values(mu: f64, sigma: f64, xi: f64, bins: usize) -> Vec<f64> {
    let norm = 1.0 / (sigma * (2.0 * std::f64::consts::PI).sqrt());
    let mut k: Vec<f64> = (0..bins)
        .map(|b| {
            let z = (crate::histogram::bin_value(b, bins) - mu) / sigma;
            xi + norm * (-0.5 * z * z).exp()
        })
        .collect();
    let sum: f64 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= sum);
    k
}
