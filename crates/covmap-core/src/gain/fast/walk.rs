//! The walk of one beam's footprint: which cells each predicted reading
//! updates, with which kernel and weight.

use super::arith::Has;
use super::arith::weighted_gains;
use super::batch::{BATCH, Queue, Rows, pairwise_sum, weighted_gains_any};
use super::cell_terms::CellTerms;
use crate::coverage_map::CoverageMap;
use crate::footprint::{CellVisitor, ROW_BLOCK, cells_of_block, visit};
use crate::gain::GainEvaluator;
use crate::gain::reads::{Marks, Recording};
use crate::histogram::with_bins;
use crate::sensor::{KernelTable, ReadingDistribution, ReadingLookup};

impl GainEvaluator<'_> {
    /// The expected gain of one beam from `origin` along `angle`, from the
    /// `terms` of this evaluator's map's cells, with `queue`, which it leaves
    /// empty; with `marks`, marking there the tiles of the cells it reads
    /// (see [`crate::gain::reads`]).
    pub(in crate::gain) fn fast_beam(
        &self,
        terms: &CellTerms,
        origin: [f64; 2],
        angle: f64,
        queue: &mut Queue,
        mut marks: Option<&mut Marks<'_>>,
    ) -> f64 {
        let dist = match marks.as_deref_mut() {
            Some(marks) => self.distribution_with(origin, angle, |i| marks.cell(i)),
            None => self.distribution(origin, angle),
        };
        let (none_reach, _) = self.range.reach(self.range.max_range_m);
        let n = dist.probabilities.len();
        // Only echoes of non-zero probability matter.
        let possible: Vec<Hypothesis> = (0..n)
            .filter(|&j| dist.probabilities[j] > 0.0)
            .map(|j| {
                let d = j as f64 * dist.step_m;
                let (reach, echo) = self.range.reach(d);
                Hypothesis {
                    lookup: self.table.reading(d, echo),
                    reach,
                    p: dist.probabilities[j],
                }
            })
            .collect();
        // The reach of `possible`'s last echo, or of no echo if it can occur.
        let reach = self.walked_reach(&dist);
        let mut suffix = vec![0.0; possible.len() + 1];
        for j in (0..possible.len()).rev() {
            suffix[j] = suffix[j + 1] + possible[j].p;
        }
        let bucket_m = dist.step_m;
        let buckets = if possible.len() <= FEW_ECHOES {
            Vec::new()
        } else {
            echo_buckets(&possible, bucket_m, reach, self.map.grid().resolution_m())
        };
        let beam = Beam {
            origin,
            angle,
            reach,
            map: self.map,
            terms,
            table: &self.table,
            possible: &possible,
            suffix: &suffix,
            buckets: &buckets,
            inv_bucket_m: 1.0 / bucket_m,
            last_bucket: buckets.len().saturating_sub(1) as f64,
            no_echo: dist.no_echo,
            none_lookup: self.table.reading(self.range.max_range_m, false),
            none_reach,
        };
        // Fix the bin count at compile time for the common sizes, so that the
        // per-cell gain is straight vector code.
        with_bins!(self.map.bins(), |N| self.run::<N>(&beam, queue, marks))
    }

    /// How far the fast evaluator walks the footprint of a beam whose
    /// predicted readings are `dist`: the reach of the farthest reading that
    /// can occur (of non-zero probability, or no echo). No cell beyond it is
    /// updated by any (behind a wall the ML map marks as covered, none), and
    /// footprints of growing reaches are nested. The cells a beam's gain
    /// reads are its footprint out to here (and the traced axis, see
    /// [`crate::gain::reads`]).
    pub(in crate::gain) fn walked_reach(&self, dist: &ReadingDistribution) -> f64 {
        let (none_reach, _) = self.range.reach(self.range.max_range_m);
        let echo_reach = dist
            .probabilities
            .iter()
            .rposition(|&p| p > 0.0)
            .map_or(0.0, |j| self.range.reach(j as f64 * dist.step_m).0);
        if dist.no_echo > 0.0 {
            echo_reach.max(none_reach)
        } else {
            echo_reach
        }
    }

    /// One beam's sum with `N` bins and the arithmetic `A`, which `has`
    /// shows the processor to have; with `marks`, marking the tiles of the
    /// cells its walk reads.
    #[inline(always)]
    pub(super) fn run_with<const N: usize, const A: u8>(
        &self,
        has: Has<A>,
        beam: &Beam<'_>,
        queue: &mut Queue,
        marks: Option<&mut Marks<'_>>,
    ) -> f64 {
        let rows = Rows::new(
            self.map.histograms(),
            &beam.terms.h_ln_h,
            &beam.terms.entropy,
            self.table.values_f64(),
            self.table.k_ln_k(),
        );
        debug_assert_eq!(queue.len, 0);
        let mut sweep = FastBeam::<N, A> {
            has,
            beam,
            rows,
            total: 0.0,
            queue,
        };
        let (grid, footprint) = (self.map.grid(), self.footprint);
        let (origin, angle, reach) = (beam.origin, beam.angle, beam.reach);
        match marks {
            Some(marks) => {
                let mut recording = Recording {
                    marks,
                    inner: &mut sweep,
                };
                visit(grid, origin, angle, reach, footprint, &mut recording);
            }
            None => visit(grid, origin, angle, reach, footprint, &mut sweep),
        }
        sweep.flush();
        sweep.total
    }
}

/// Up to this many echoes of non-zero probability, a cell tests each of them
/// rather than looking up its bucket.
const FEW_ECHOES: usize = 8;

/// For each distance bucket of `bucket_m` along a beam's footprint (out to
/// `reach`), the run `possible[lo..hi]` of echoes a cell reached in it must
/// test; see [`Beam::buckets`]. Reach and freeness grow with the echo's
/// distance, so the echoes before the run cannot reach the bucket's cells and
/// those after it leave them all in free space.
fn echo_buckets(
    possible: &[Hypothesis],
    bucket_m: f64,
    reach: f64,
    resolution_m: f64,
) -> Vec<(usize, usize)> {
    // A cell's centre distance lies within half a cell diagonal of where the
    // footprint reaches it (they are equal for a cone).
    let margin = resolution_m + 1e-6 * bucket_m;
    let count = (reach / bucket_m) as usize + 2;
    let (mut lo, mut hi) = (0, 0);
    let mut buckets = Vec::with_capacity(count);
    for b in 0..count {
        let enter_lo = b as f64 * bucket_m - 1e-6 * bucket_m;
        let d_l_hi = (b + 1) as f64 * bucket_m + margin;
        while lo < possible.len() && possible[lo].reach < enter_lo {
            lo += 1;
        }
        hi = hi.max(lo);
        while hi < possible.len() && !possible[hi].lookup.is_free(d_l_hi) {
            hi += 1;
        }
        buckets.push((lo, hi));
    }
    buckets
}

/// One hypothetical echo of a beam.
#[derive(Clone, Copy)]
struct Hypothesis {
    lookup: ReadingLookup,
    reach: f64,
    p: f64,
}

/// What every cell of one beam's widest footprint needs to know.
pub(super) struct Beam<'a> {
    /// Where the beam starts, metres.
    origin: [f64; 2],
    /// Its direction, radians.
    angle: f64,
    /// How far its footprint is walked, metres.
    reach: f64,
    pub(super) map: &'a CoverageMap,
    /// What every cell of the map gains from.
    pub(super) terms: &'a CellTerms,
    pub(super) table: &'a KernelTable,
    /// The echoes of non-zero probability, nearest first.
    possible: &'a [Hypothesis],
    /// `suffix[j]`: the probability of the echoes `possible[j..]`.
    suffix: &'a [f64],
    /// For cells reached at `enter` in bucket `b = enter / bucket`: the
    /// echoes `possible[..lo]` do not reach them, `possible[hi..]` leave them
    /// in free space, and `possible[lo..hi]` need a test. Empty when there
    /// are so few echoes that testing each beats the lookup.
    buckets: &'a [(usize, usize)],
    inv_bucket_m: f64,
    /// The index of the last bucket.
    last_bucket: f64,
    no_echo: f64,
    /// The kernels of no echo.
    none_lookup: ReadingLookup,
    none_reach: f64,
}

impl Beam<'_> {
    /// The bucket of cells the footprint reaches at `enter` metres.
    #[inline(always)]
    fn bucket(&self, enter: f64) -> usize {
        // Clamped in floating point, so that the conversion is a plain truncation.
        (enter * self.inv_bucket_m).min(self.last_bucket) as i32 as usize
    }
}

/// The fast evaluator's work for one beam, with `N` bins per histogram (0: any
/// number).
struct FastBeam<'a, const N: usize, const A: u8> {
    /// That the processor has the arithmetic `A` the gains are computed with.
    has: Has<A>,
    beam: &'a Beam<'a>,
    rows: Rows<'a, N>,
    total: f64,
    /// Gains waiting to be computed. Computing them in batches lets the
    /// processor overlap the independent cells instead of waiting on each
    /// one's logarithm. Fewer than [`BATCH`] wait between calls, so a row
    /// block always finds room for its [`ROW_BLOCK`]. Empty between beams.
    queue: &'a mut Queue,
}

impl<const N: usize, const A: u8> FastBeam<'_, N, A> {
    /// Compute the waiting gains, in the order they were queued.
    fn flush(&mut self) {
        if self.queue.len == 0 {
            return;
        }
        let queue = &self.queue;
        self.total += if N == 0 {
            weighted_gains_any(self.beam, queue)
        } else {
            weighted_gains::<N, A>(self.has, &self.rows, queue)
        };
        self.queue.len = 0;
    }
}

impl<const N: usize, const A: u8> FastBeam<'_, N, A> {
    /// Ask for the cache lines of cell `i`'s histogram and `h ln h`: its gains
    /// are computed at the next flush, by when they have arrived.
    #[inline(always)]
    fn prefetch(&self, i: usize) {
        #[cfg(target_arch = "x86_64")]
        if N > 0 {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            // Addresses only (`wrapping_add` never reads), so no bounds
            // check: a prefetch of any address is harmless.
            let histogram = self.rows.h.as_ptr().wrapping_add(i).cast::<i8>();
            let h_ln_h = self.rows.h_ln_h.as_ptr().wrapping_add(i).cast::<i8>();
            // SAFETY: SSE is part of every x86-64 processor, and a prefetch
            // only hints at an address: it never reads or faults.
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(histogram);
                _mm_prefetch::<_MM_HINT_T0>(h_ln_h);
                _mm_prefetch::<_MM_HINT_T0>(h_ln_h.wrapping_add(64));
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = i;
    }

    /// The weight of the free kernel (the echoes' and no echo's together:
    /// one kernel since no-echo readings clear as echoes' free space does),
    /// if it is the only one every cell of a cone's row block (at distances from `near` to `far`) gets: every cell
    /// within `reach_m`, the echoes that end before the block reaching none
    /// of it, the next leaving all of it in free space, and either every cell
    /// or none within the reach of no echo. The same weight
    /// [`CellVisitor::cell`] gives each.
    #[inline(always)]
    fn block_weight(&self, [near, far]: [f64; 2], reach_m: f64) -> Option<f64> {
        let beam = self.beam;
        if !(far <= reach_m) {
            return None;
        }
        let mut j = if beam.buckets.is_empty() {
            0
        } else {
            beam.buckets[beam.bucket(near)].0
        };
        while j < beam.possible.len() && beam.possible[j].reach < near {
            j += 1;
        }
        if beam
            .possible
            .get(j)
            .is_some_and(|echo| !echo.lookup.is_free(far))
        {
            return None;
        }
        if far <= beam.none_reach {
            Some(beam.suffix[j] + beam.no_echo)
        } else if near > beam.none_reach {
            Some(beam.suffix[j])
        } else {
            None
        }
    }

    /// The index of the kernel at table `offset`.
    #[inline(always)]
    fn kernel_index(&self, offset: usize) -> usize {
        let bins = if N > 0 { N } else { self.beam.map.bins() };
        offset / bins
    }

    /// Cell `i`'s gain under the kernel at `offset`, times `weight`: added at
    /// once from the prior's gains if the cell is at the prior, else queued.
    #[inline(always)]
    fn gain(&mut self, i: usize, offset: usize, weight: f64, prior: bool) {
        if prior {
            self.total += weight * self.beam.terms.prior_gain[self.kernel_index(offset)];
        } else {
            self.push(i, offset, weight);
        }
    }

    /// Queue one gain; compute the batch when it is full.
    #[inline(always)]
    fn push(&mut self, i: usize, offset: usize, weight: f64) {
        debug_assert!(self.queue.len < BATCH);
        let j = self.queue.len.min(BATCH);
        let queue = &mut self.queue;
        (
            queue.cell[j],
            queue.offset[j],
            queue.weight[j],
            queue.entropy[j],
        ) = (i, offset, weight, self.rows.entropy[i]);
        self.queue.len = j + 1;
        if self.queue.len >= BATCH {
            self.flush();
        }
    }
}

impl<const N: usize, const A: u8> CellVisitor for FastBeam<'_, N, A> {
    #[inline(always)]
    fn cell(&mut self, i: usize, d_l: f64, enter: f64) {
        let beam = self.beam;
        let prior = beam.terms.prior[i] != 0;
        if !prior {
            self.prefetch(i);
        }
        let (lo, hi) = if beam.buckets.is_empty() {
            (0, beam.possible.len())
        } else {
            beam.buckets[beam.bucket(enter)]
        };
        // Echoes that end near the cell need kernels of their own. From the
        // first echo that reaches the cell and leaves it in free space on,
        // every farther one does both (reach and freeness grow with the
        // echo's distance) and gives it the kernel no echo gives: region 0 at
        // distance min(d_l, d) = d_l.
        let mut j = lo;
        while j < hi {
            let echo = &beam.possible[j];
            if enter <= echo.reach {
                if echo.lookup.is_free(d_l) {
                    break;
                }
                self.gain(i, echo.lookup.offset(d_l), echo.p, prior);
            }
            j += 1;
        }
        let echo_free = beam.suffix[j];
        let no_echo = if enter <= beam.none_reach {
            beam.no_echo
        } else {
            0.0
        };
        if echo_free + no_echo > 0.0 {
            let offset = beam.none_lookup.free_offset(d_l);
            self.gain(i, offset, echo_free + no_echo, prior);
        }
    }

    #[inline(always)]
    fn row_block(
        &mut self,
        first: usize,
        d: &[f64; ROW_BLOCK],
        n: usize,
        bounds: [f64; 2],
        reach_m: f64,
    ) {
        let Some(weight) = self.block_weight(bounds, reach_m) else {
            cells_of_block(self, first, d, n, reach_m);
            return;
        };
        self.free_block(first, d, n, weight);
    }
}

impl<const N: usize, const A: u8> FastBeam<'_, N, A> {
    /// Every cell of a row block (the `n` cells from `first`, at distances
    /// `d`) gets the free-space kernel (a no-echo reading's) with `weight`:
    /// what `cell` would do for each, done for the block at once.
    #[inline(always)]
    fn free_block(&mut self, first: usize, d: &[f64; ROW_BLOCK], n: usize, weight: f64) {
        if weight <= 0.0 {
            return;
        }
        let free = self.beam.none_lookup;
        let prior = &self.beam.terms.prior[first..first + n];
        let flags = match prior.first_chunk::<ROW_BLOCK>() {
            Some(all) => u64::from_ne_bytes(*all),
            None => u64::from(prior.iter().any(|&p| p != 0)),
        };
        if flags == u64::from_ne_bytes([1; ROW_BLOCK]) {
            // The whole block is at the prior (common in unexplored
            // space): its gains come from the table.
            let gains = &self.beam.terms.prior_gain;
            let block: [f64; ROW_BLOCK] = std::array::from_fn(|k| gains[free.free_step(d[k])]);
            self.total += weight * pairwise_sum(&block);
            return;
        }
        if flags != 0 {
            // Cells at the prior take their gains from the table, summed
            // pairwise over the block; the others are queued.
            let mut gains = [0.0f64; ROW_BLOCK];
            for k in 0..n {
                if prior[k] != 0 {
                    gains[k] = self.beam.terms.prior_gain[free.free_step(d[k])];
                } else {
                    self.prefetch(first + k);
                    self.push(first + k, free.free_offset(d[k]), weight);
                }
            }
            self.total += weight * pairwise_sum(&gains);
            return;
        }
        // Fewer than `BATCH` wait, so the block fits; the `min` only
        // tells the compiler so.
        let queue = &mut self.queue;
        let at = queue.len.min(BATCH);
        let slots = at..at + ROW_BLOCK;
        for (k, ((cell, offset), job_weight)) in queue.cell[slots.clone()]
            .iter_mut()
            .zip(&mut queue.offset[slots.clone()])
            .zip(&mut queue.weight[slots])
            .enumerate()
        {
            (*cell, *offset, *job_weight) = (first + k, free.free_offset(d[k]), weight);
        }
        let entropies = &self.rows.entropy;
        match entropies.get(first..first + ROW_BLOCK) {
            Some(block) => queue.entropy[at..at + ROW_BLOCK].copy_from_slice(block),
            None => queue.entropy[at..at + n].copy_from_slice(&entropies[first..first + n]),
        }
        queue.len = at + n;
        for k in 0..n {
            self.prefetch(first + k);
        }
        if self.queue.len >= BATCH {
            self.flush();
        }
    }
}
