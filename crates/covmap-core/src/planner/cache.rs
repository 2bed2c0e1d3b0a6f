//! Planning again after a scan without recomputing what the scan did not
//! change: [`PlanningCache`] and [`Planner::next_viewpoint_cached`].
//!
//! # What is kept, and when it is recomputed
//! - **The evaluator's per-map work** (the coverage that stops predicted
//!   beams, `h ln h`, entropies and prior flags of every cell): kept, with
//!   where the cache last read the map's change feed
//!   ([`CoverageMap::changes_since`]). Each call recomputes the terms of the
//!   cells the feed names, and only those. The cache does not take the
//!   caller's word for what changed: a map changed in any way (scans,
//!   contacts, pinned cells) is seen, and another map in its place (a
//!   clone, a map loaded, even of the same grid) is taken in whole.
//! - **Every candidate's expected gain**, keyed by the candidate's cell and
//!   heading (bit for bit), beam by beam: the gain of each of its beams, with
//!   the tiles of 8 x 8 cells holding every cell that beam's computation
//!   read (its traced axis up to the first cell that stops it with
//!   certainty, and its footprint out to the reach of its farthest possible
//!   reading: walls the map holds as covered end both; see `gain::reads`).
//!   A beam's gain is recomputed when one of its tiles holds a changed cell.
//!   Otherwise nothing it read changed (a cell's terms are functions of its
//!   histogram; the kernels and the prior's gains of the sensor model
//!   alone), so it is the gain a full computation gives, bit for bit; and a
//!   candidate's gain is its beams' summed in the order the evaluator sums
//!   them, so it is too. A scan a few metres off changes what only the
//!   candidate's beams towards it read.
//! - **Everything**, when the sensor model (every parameter of its range
//!   model, [`RangeModel::bits`], and its footprint, bit for bit), the
//!   bearings, the gain options or the grid change.
//! - **Nothing else**: free space, reachability, path costs, the candidate
//!   lattice and eq. 14's normalisation depend on the whole map and are
//!   computed anew on every call, as [`Planner::next_viewpoint`] does.
//!
//! So [`Planner::next_viewpoint_cached`] returns exactly what
//! [`Planner::next_viewpoint`] returns for the same inputs, the same plan
//! (every candidate's gain, bit for bit) or the same error, whatever the
//! cache held before. Reuse needs the candidates' headings to repeat: the
//! default headings are fixed angles, kept across any motion; with
//! `candidate_headings = Some(1)` a candidate has the robot's heading, so
//! gains are kept only while the robot plans with the same heading (the
//! others are dropped).

use std::borrow::Cow;
use std::collections::HashMap;

use crate::coverage_map::{ChangeCursor, Changes, CoverageMap};
use crate::error::Result;
use crate::gain::{
    GainEvaluator, GainMethod, GainOptions, MapTerms, TileSet, Tiles, beam_sum, stop_coverage_of,
    validate_candidates,
};
use crate::grid::Grid;
use crate::histogram;
use crate::planner::path::Reachability;
use crate::planner::viewpoint::{Plan, Planner};
use crate::pose::{Pose, check_pose};
use crate::sensor::{
    Footprint, KernelTable, RANGE_PARAMETERS, RangeModel, SensorModel, StopCoverage,
};

/// What [`Planner::next_viewpoint_cached`] keeps between calls: the map as it
/// last saw it, the gain evaluator's per-map work and every candidate's
/// expected gain (see the [module documentation](self)). Owns all it holds:
/// the map may be changed freely between calls.
///
/// # Example
/// ```
/// use covmap_core::planner::{Planner, PlannerConfig, PlanningCache};
/// use covmap_core::{CoverageMap, Grid, Pose, ScanMap, SonarModel};
/// let sonar = SonarModel::default();
/// let bearings: Vec<f64> = (0..24).map(|i| i as f64 * std::f64::consts::TAU / 24.0).collect();
/// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 40, 300).unwrap());
/// let planner = Planner::new(PlannerConfig::default()).unwrap();
/// let mut cache = PlanningCache::new();
/// // Down a long hall, 2 m wide: a scan every metre, a plan after each.
/// for x in 1..29 {
///     let pose = Pose::new(x as f64, 2.0, 0.0);
///     let ranges: Vec<f64> = bearings
///         .iter()
///         .map(|b| (1.0 / b.sin().abs()).min(6.0))
///         .collect();
///     map.integrate(&pose, &ranges, &bearings, &sonar).unwrap();
///     let plan = planner.next_viewpoint_cached(&mut cache, &map, &pose, &bearings, &sonar).unwrap();
///     assert_eq!(plan, planner.next_viewpoint(&map, &pose, &bearings, &sonar).unwrap());
/// }
/// // The candidates far behind the robot kept their gains.
/// let stats = cache.stats();
/// assert!(stats.recomputed < stats.candidates / 2, "{stats:?}");
/// ```
#[derive(Clone, Default)]
pub struct PlanningCache {
    /// The map as the last call saw it.
    readouts: Option<MapReadouts>,
    /// The gains and what they were computed from.
    gains: Option<GainState>,
    /// Cells changed since `gains` was last brought up to date (by calls
    /// that returned an error before it).
    unapplied: Vec<usize>,
    stats: CacheStats,
}

/// What the last call of [`Planner::next_viewpoint_cached`] with a cache
/// did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CacheStats {
    /// Candidates of the plan.
    pub candidates: usize,
    /// Of those, candidates whose gain was computed again, in whole or in
    /// part (the others' were kept).
    pub recomputed: usize,
    /// Beams of the candidates (candidates times bearings).
    pub beams: usize,
    /// Of those, beams whose gain was computed (the others' were kept).
    pub recomputed_beams: usize,
    /// Cells the map's change feed named since the call before (every cell
    /// of the map on the first call, or for another map).
    pub changed_cells: usize,
    /// Whether the gain evaluator's per-map work was computed from scratch:
    /// on the first call, and when the sensor model, bearings, gain options
    /// or grid changed.
    pub rebuilt: bool,
}

impl PlanningCache {
    /// An empty cache: its first call computes everything.
    pub fn new() -> Self {
        Self::default()
    }

    /// What its last successful call did.
    pub fn stats(&self) -> CacheStats {
        self.stats
    }

    /// Forget everything held: the next call computes everything.
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

impl std::fmt::Debug for PlanningCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PlanningCache")
            .field("gains", &self.gains.as_ref().map_or(0, |s| s.gains.len()))
            .field("stats", &self.stats)
            .finish()
    }
}

/// The map as the cache last saw it: where it read the map's change feed,
/// and what the planner reads of every cell for its free space (the ML map
/// and the entropies).
#[derive(Clone)]
struct MapReadouts {
    grid: [u64; 5],
    bins: usize,
    cursor: ChangeCursor,
    ml: Vec<f32>,
    entropy: Vec<f32>,
}

impl MapReadouts {
    /// `map` as it is.
    fn new(map: &CoverageMap) -> Self {
        Self {
            grid: grid_bits(map.grid()),
            bins: map.bins(),
            cursor: map.change_cursor(),
            ml: map.ml(),
            entropy: map.entropy(),
        }
    }

    /// Take in `map`: the cells its change feed names since the map was
    /// last seen, ascending, with their ML coverage and entropy anew (as
    /// [`CoverageMap::ml`] and [`CoverageMap::entropy`] compute them); `None`
    /// for a map of another grid, or another map (its feed names every
    /// cell: the cache starts over).
    fn sync(&mut self, map: &CoverageMap) -> Option<Vec<usize>> {
        if self.grid != grid_bits(map.grid()) || self.bins != map.bins() {
            return None;
        }
        let Changes::Cells(changed) = map.changes_since(&self.cursor) else {
            return None;
        };
        let bins = self.bins;
        for &i in &changed {
            let h = &map.histograms()[i * bins..(i + 1) * bins];
            self.ml[i] = stop_coverage_of(h, StopCoverage::MaximumLikelihood);
            self.entropy[i] = histogram::entropy(h);
        }
        self.cursor = map.change_cursor();
        Some(changed)
    }
}

/// The gains kept for one sensor setting on one grid, and the evaluator's
/// per-map work they were computed with.
#[derive(Clone)]
struct GainState {
    inputs: GainInputs,
    terms: MapTerms,
    tiles: Tiles,
    /// The kept gains by candidate cell and heading (its bits).
    gains: HashMap<(usize, u64), CandidateGains>,
}

/// A candidate's kept gain: the gain of each of its beams (by bearing), the
/// tiles of the cells each was computed from and whether it is still right,
/// and their sum.
#[derive(Clone)]
struct CandidateGains {
    gain: f64,
    beams: Vec<f64>,
    reads: Vec<TileSet>,
    fresh: Vec<bool>,
}

/// Everything a gain depends on besides the map's cells and the candidate,
/// bit for bit: the grid, the bins, the sensor model, the kernel table's
/// model, the bearings and the gain options.
#[derive(Clone, Debug, PartialEq, Eq)]
struct GainInputs {
    grid: [u64; 5],
    bins: usize,
    /// Every parameter of the model the gains were computed with, and of
    /// the model and the resolution of the kernel table they read.
    range: [u64; RANGE_PARAMETERS.len()],
    table: ([u64; RANGE_PARAMETERS.len()], u64),
    footprint: (u8, u64),
    bearings: Vec<u64>,
    range_step: Option<u64>,
    stop_coverage: StopCoverage,
}

impl GainInputs {
    fn new(
        map: &CoverageMap,
        range: &RangeModel,
        footprint: Footprint,
        table: &KernelTable,
        options: GainOptions,
        bearings: &[f64],
    ) -> Self {
        Self {
            grid: grid_bits(map.grid()),
            bins: map.bins(),
            range: range.bits(),
            table: (table.model().bits(), table.resolution_m().to_bits()),
            footprint: match footprint {
                Footprint::Cone { half_angle_rad } => (1, half_angle_rad.to_bits()),
                Footprint::Ray => (0, 0),
            },
            bearings: bearings.iter().map(|b| b.to_bits()).collect(),
            range_step: options.range_step_m.map(f64::to_bits),
            stop_coverage: options.stop_coverage,
        }
    }
}

/// The bits of a grid's geometry.
fn grid_bits(grid: &Grid) -> [u64; 5] {
    let [ox, oy] = grid.origin_m();
    [
        ox.to_bits(),
        oy.to_bits(),
        grid.resolution_m().to_bits(),
        grid.rows() as u64,
        grid.cols() as u64,
    ]
}

impl Planner {
    /// [`Self::next_viewpoint`], keeping in `cache` what the next call can
    /// use: the map's read-outs, the gain evaluator's per-map work and every
    /// candidate's gain, recomputed only where the map changed (see the
    /// [module documentation](crate::planner::cache)). The plan (every
    /// candidate's gain, bit for bit) or the error is the one
    /// [`Self::next_viewpoint`] returns for the same inputs, whatever the
    /// cache held; after an error the cache still holds only what is right
    /// for the map.
    ///
    /// # Errors
    /// As [`Self::next_viewpoint`].
    pub fn next_viewpoint_cached<M: SensorModel + ?Sized>(
        &self,
        cache: &mut PlanningCache,
        map: &CoverageMap,
        pose: &Pose,
        bearings: &[f64],
        model: &M,
    ) -> Result<Plan> {
        let (changed_cells, free, reach) = self.see_free_and_reachable(cache, map, pose, None)?;
        let plan = self.next_viewpoint_on(cache, map, pose, bearings, model, (&free, &reach))?;
        cache.stats.changed_cells = changed_cells;
        Ok(plan)
    }

    /// [`Self::next_viewpoint_cached`] on the free space `free` and paths
    /// `reach` that [`Self::free_and_reachable_cached`] has just found for
    /// `map` and a pose in the same cell as `pose`: the same plan, without
    /// finding them again (the cache's stats count no changed cells: that
    /// call took them in).
    ///
    /// # Errors
    /// As [`Self::next_viewpoint_cached`] past the pose.
    pub(crate) fn next_viewpoint_on<M: SensorModel + ?Sized>(
        &self,
        cache: &mut PlanningCache,
        map: &CoverageMap,
        pose: &Pose,
        bearings: &[f64],
        model: &M,
        (free, reach): (&[bool], &Reachability),
    ) -> Result<Plan> {
        let (cells, poses) = self.candidates(map.grid(), pose, bearings, free, reach);
        let stats = cache.gains(map, model, self.config.gain, &cells, &poses, bearings)?;
        let gains = cache.gathered(&cells, &poses);
        cache.stats = stats;
        self.choose(reach, &cells, poses, gains, map.bins())
    }
}

impl Planner {
    /// [`Self::reachability`] and the free space it runs through (what
    /// [`Self::next_viewpoint_on`] plans on), from the map's read-outs
    /// `cache` keeps (brought up to date with `map` first, as
    /// [`Self::next_viewpoint_cached`] does): the same paths, without
    /// reading the whole map out again.
    ///
    /// # Errors
    /// As [`Self::reachability`].
    pub(crate) fn free_and_reachable_cached(
        &self,
        cache: &mut PlanningCache,
        map: &CoverageMap,
        pose: &Pose,
        driven: Option<&[bool]>,
    ) -> Result<(Vec<bool>, Reachability)> {
        let (_, free, reach) = self.see_free_and_reachable(cache, map, pose, driven)?;
        Ok((free, reach))
    }

    /// Bring `cache` up to date with `map` (how many cells changed) and
    /// find the free space and the paths from `pose` on the map's read-outs
    /// it keeps (the cells `driven` passable, if given).
    fn see_free_and_reachable(
        &self,
        cache: &mut PlanningCache,
        map: &CoverageMap,
        pose: &Pose,
        driven: Option<&[bool]>,
    ) -> Result<(usize, Vec<bool>, Reachability)> {
        let start = check_pose(map.grid(), pose)?;
        let changed_cells = cache.see(map);
        #[allow(clippy::expect_used, reason = "`see` has just set it")]
        let readouts = cache.readouts.as_ref().expect("the map was seen");
        let blocked = self.blocked_of(
            map.bins(),
            &readouts.ml,
            &readouts.entropy,
            !self.config.unknown_is_free,
        );
        let (free, reach) = self.free_and_reachable_of(map.grid(), &blocked, start, driven)?;
        Ok((changed_cells, free, reach))
    }
}

impl PlanningCache {
    /// Take in `map`: its changed cells (all of them, for another map or a
    /// map of another grid) become unapplied to the gains. Returns how many
    /// changed.
    fn see(&mut self, map: &CoverageMap) -> usize {
        match self
            .readouts
            .as_mut()
            .and_then(|readouts| readouts.sync(map))
        {
            Some(changed) => {
                let count = changed.len();
                self.unapplied.extend(changed);
                count
            }
            None => {
                self.readouts = Some(MapReadouts::new(map));
                self.gains = None;
                self.unapplied.clear();
                map.grid().len()
            }
        }
    }

    /// Bring the gains up to date with `map` for the candidates at `poses`
    /// (in `cells`): the gain of each as
    /// `GainEvaluator::new(map, model, options)?.evaluate(poses, bearings,
    /// GainMethod::Fast)` gives it, with its errors in its order, kept where
    /// no cell a gain read has changed, else computed and kept.
    fn gains<M: SensorModel + ?Sized>(
        &mut self,
        map: &CoverageMap,
        model: &M,
        options: GainOptions,
        cells: &[usize],
        poses: &[Pose],
        bearings: &[f64],
    ) -> Result<CacheStats> {
        // Everything that can fail, before the gains change.
        GainEvaluator::check(map, model, options)?;
        let range = *model.range_model();
        let table: Cow<'_, KernelTable> = map.kernel_table(&range)?;
        validate_candidates(map.grid(), poses, bearings)?;

        let inputs = GainInputs::new(map, &range, model.footprint(), &table, options, bearings);
        let mut stats = CacheStats {
            candidates: poses.len(),
            ..CacheStats::default()
        };
        let mut unapplied = std::mem::take(&mut self.unapplied);
        let state = match &mut self.gains {
            Some(state) if state.inputs == inputs => {
                unapplied.sort_unstable();
                unapplied.dedup();
                state.terms.update(map, &table, &unapplied);
                let changed = state.tiles.of_cells(&unapplied);
                // Forget the beams' gains a changed cell can have changed,
                // and the candidates of headings not asked for now (with one
                // heading, the robot's: gains of other headings are of no use
                // until it turns back exactly).
                let mut headings: Vec<u64> = poses.iter().map(|p| p.theta_rad.to_bits()).collect();
                headings.sort_unstable();
                headings.dedup();
                state
                    .gains
                    .retain(|&(_, heading), _| headings.binary_search(&heading).is_ok());
                for kept in state.gains.values_mut() {
                    for (fresh, reads) in kept.fresh.iter_mut().zip(&kept.reads) {
                        *fresh &= !reads.meets(&changed);
                    }
                }
                state
            }
            _ => {
                stats.rebuilt = true;
                self.gains.insert(GainState {
                    terms: MapTerms::new(map, &table, options.stop_coverage),
                    tiles: Tiles::new(map.grid()),
                    inputs,
                    gains: HashMap::new(),
                })
            }
        };

        // The beams whose gains are not kept, of the candidates they belong
        // to (in the candidates' order).
        let slot = |k: usize| (cells[k], poses[k].theta_rad.to_bits());
        let mut jobs: Vec<(usize, usize)> = Vec::new();
        let mut touched: Vec<usize> = Vec::new();
        for k in 0..poses.len() {
            let kept = state
                .gains
                .entry(slot(k))
                .or_insert_with(|| CandidateGains {
                    gain: 0.0,
                    beams: vec![0.0; bearings.len()],
                    reads: vec![TileSet::default(); bearings.len()],
                    fresh: vec![false; bearings.len()],
                });
            let before = jobs.len();
            jobs.extend(
                (0..bearings.len())
                    .filter(|&j| !kept.fresh[j])
                    .map(|j| (k, j)),
            );
            if jobs.len() > before {
                touched.push(k);
            }
        }
        stats.recomputed = touched.len();
        stats.beams = poses.len() * bearings.len();
        stats.recomputed_beams = jobs.len();
        if !jobs.is_empty() {
            let evaluator = GainEvaluator::with_terms(map, model, options, &table, &state.terms)?;
            let beams: Vec<(Pose, f64)> =
                jobs.iter().map(|&(k, j)| (poses[k], bearings[j])).collect();
            let gains = evaluator.beam_gains_and_reads(&beams, &state.tiles)?;
            for (&(k, j), (gain, reads)) in jobs.iter().zip(gains) {
                #[allow(
                    clippy::expect_used,
                    reason = "every touched slot was inserted before its beams were queued"
                )]
                let kept = state.gains.get_mut(&slot(k)).expect("kept above");
                (kept.beams[j], kept.reads[j], kept.fresh[j]) = (gain, reads, true);
            }
            // The candidates' gains, from their beams' as `evaluate` sums them.
            for &k in &touched {
                #[allow(
                    clippy::expect_used,
                    reason = "every touched slot was inserted before its beams were queued"
                )]
                let kept = state.gains.get_mut(&slot(k)).expect("kept above");
                kept.gain = beam_sum(&poses[k], bearings, &kept.beams);
            }
        }
        Ok(stats)
    }

    /// The expected gain of scanning from `pose` with `bearings` on `map`, as
    /// `GainEvaluator::new(map, model, options)?.evaluate(&[pose], bearings,
    /// GainMethod::Fast)` gives it, read from the per-map work the last plan
    /// on `map` brought up to date (computed anew where the map changed
    /// since, or there is none for these inputs).
    ///
    /// # Errors
    /// As [`GainEvaluator::new`] and [`GainEvaluator::evaluate`].
    pub(crate) fn gain_at<M: SensorModel + ?Sized>(
        &self,
        map: &CoverageMap,
        model: &M,
        options: GainOptions,
        pose: &Pose,
        bearings: &[f64],
    ) -> Result<f64> {
        let range = *model.range_model();
        let table: Cow<'_, KernelTable> = map.kernel_table(&range)?;
        let inputs = GainInputs::new(map, &range, model.footprint(), &table, options, bearings);
        // The kept per-map work is this map's as it is now: the map has not
        // changed since the cache last read it, and every change read
        // since has been applied to the work.
        let current = self
            .readouts
            .as_ref()
            .is_some_and(|r| r.cursor == map.change_cursor())
            && self.unapplied.is_empty();
        let gains = match &self.gains {
            Some(state) if current && state.inputs == inputs => {
                GainEvaluator::with_terms(map, model, options, &table, &state.terms)?.evaluate(
                    std::slice::from_ref(pose),
                    bearings,
                    GainMethod::Fast,
                )?
            }
            _ => GainEvaluator::new(map, model, options)?.evaluate(
                std::slice::from_ref(pose),
                bearings,
                GainMethod::Fast,
            )?,
        };
        Ok(gains[0])
    }

    /// The kept gain of each candidate at `poses` (in `cells`), after
    /// [`Self::gains`] has kept them all.
    fn gathered(&self, cells: &[usize], poses: &[Pose]) -> Vec<f64> {
        #[allow(
            clippy::expect_used,
            reason = "called only after `gains` has kept them"
        )]
        let state = self.gains.as_ref().expect("gains kept");
        (0..poses.len())
            .map(|k| state.gains[&(cells[k], poses[k].theta_rad.to_bits())].gain)
            .collect()
    }
}

#[cfg(test)]
mod tests;
