//! Expected information gain of a viewpoint ([the model](crate::model),
//! section 4, paper eq. 11-13).
//!
//! For a candidate pose `l` and a sensor (bearings and an inverse model),
//!
//! ```text
//! E[I(l)] = sum over beams  sum_d p(d | c) * sum_{c_i in C(l, d)} I(h(c_i) | d)
//! ```
//!
//! with `I(h | d) = H(h) - H(h'_d)` the entropy a cell loses when reading `d` is
//! integrated, and `C(l, d)` exactly the cells [`CoverageMap::integrate`] would
//! update for that reading, with exactly the kernels it would multiply in.
//!
//! # The model of `p(d | c)`
//! Beams are independent (as the map's cells are): each beam's readings are
//! predicted on their own, by the sensor's forward model
//! ([`reading_distribution`]: the beam's axis traced through the map, each
//! cell stopping it with the probability of its coverage, [`StopCoverage`]
//! choosing which; see [`crate::sensor`]), and the gains add up. The
//! sensor's uncertainty enters through the kernels.
//!
//! # Two evaluators
//! [`GainMethod::Exact`] is the equation as written: for every discretised
//! reading, the gain of every cell it would update, each entropy from its
//! definition. It is the reference. [`GainMethod::Fast`] gives the same sums
//! (to rounding) much faster: it skips the readings and cells that cannot
//! contribute, looks up what every cell still at the prior gains, and
//! computes the rest in batches of vector code compiled for the widest
//! arithmetic the processor has (detected at run time). Every path it can
//! take is tested against the exact evaluator.
//!
//! Candidates are evaluated in parallel (feature `parallel`). Every
//! candidate's beams are summed in the order of their direction whatever the
//! other candidates are, so a result depends neither on scheduling nor on
//! the company a candidate keeps.
//!
//! [`CoverageMap::integrate`]: crate::ScanMap::integrate

mod evaluator;
mod exact;
mod fast;
mod map_terms;
mod options;
mod reads;
mod schedule;
#[cfg(test)]
mod test_maps;

pub use evaluator::GainEvaluator;
pub(crate) use evaluator::validate_candidates;
pub use exact::information_gain;
pub(crate) use map_terms::{MapTerms, stop_coverage_of};
pub use options::{GainMethod, GainOptions};
pub(crate) use reads::{TileSet, Tiles};
pub(crate) use schedule::beam_sum;
// The forward model of readings lived here before it moved beside the sensor
// model; its old paths keep working.
pub use crate::sensor::{
    MIN_STEP_FRACTION, ReadingDistribution, StopCoverage, reading_distribution,
};
