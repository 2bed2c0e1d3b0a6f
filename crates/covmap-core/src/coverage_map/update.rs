//! Bayes' rule for a scan: each beam's kernels multiplied into the cells of
//! its footprint.

use std::borrow::Cow;

use super::CoverageMap;
use super::changes::Stamper;
use super::history::History;
use super::storage::cached_or_new;
use crate::error::Result;
use crate::footprint::CellVisitor;
use crate::grid::Grid;
use crate::histogram::{self, with_bins};
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::{KernelTable, ReadingLookup, SensorModel};
use crate::sight::visit_reading;

impl ScanMap for CoverageMap {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Multiply each beam's kernels into the cells of its footprint.
    fn integrate_checked<M: SensorModel + ?Sized>(
        &mut self,
        scan: ScanBeams<'_>,
        model: &M,
    ) -> Result<usize> {
        let table = cached_or_new(
            self.table.as_deref(),
            model.range_model(),
            &self.grid,
            self.bins,
        )?;
        // The changed cells are marked as the update visits them, for the
        // change feed and the history.
        let mut touches = Touches {
            stamper: self.changes.begin_watched(self.history.is_some()),
            touched: self.history.as_deref_mut().map(History::begin_scan),
        };
        // Pick the update once per scan, so the per-cell loop is straight code.
        let updates = with_bins!(self.bins, |N| apply::<N, M>(
            &self.grid,
            (&mut self.data, &mut self.log),
            &table,
            scan,
            model,
            &mut touches,
        ));
        if let Cow::Owned(table) = table {
            // The table of the model the next scans most likely come from.
            self.table = Some(Box::new(table));
        }
        self.record_history();
        Ok(updates)
    }
}

/// Errors unless there is one reach, not NaN and non-negative, a reading.
pub(crate) fn check_reaches(ranges: &[f64], no_echo_reach_m: &[f64]) -> Result<()> {
    if no_echo_reach_m.len() != ranges.len() {
        return Err(crate::CovmapError::LengthMismatch {
            what: "ranges and no-echo reaches",
            left: ranges.len(),
            right: no_echo_reach_m.len(),
        });
    }
    match no_echo_reach_m.iter().find(|r| !(**r >= 0.0)) {
        Some(&value) => Err(crate::CovmapError::InvalidParameter {
            name: "no_echo_reach_m",
            value,
            expected: "a non-negative distance (metres)",
        }),
        None => Ok(()),
    }
}

/// Errors unless a scan's sight or echo sources are for `len` readings,
/// as many as `ranges`.
pub(crate) fn check_sight(ranges: &[f64], len: usize) -> Result<()> {
    if len == ranges.len() {
        Ok(())
    } else {
        Err(crate::CovmapError::LengthMismatch {
            what: "ranges and no-echo sights or echo sources",
            left: ranges.len(),
            right: len,
        })
    }
}

/// How far reading `k` of `r` metres reaches along its beam, and whether it
/// is an echo: [`RangeModel::reach`](crate::RangeModel::reach), a no-echo
/// reading cut to its entry of `no_echo_reach_m`, if any.
pub(super) fn beam_reach(
    range: &crate::RangeModel,
    r: f64,
    k: usize,
    no_echo_reach_m: Option<&[f64]>,
) -> (f64, bool) {
    let (reach, echo) = range.reach(r);
    match no_echo_reach_m {
        Some(clip) if !echo => (reach.min(clip[k]), echo),
        _ => (reach, echo),
    }
}

/// The cells a scan changes, marked as its update visits them: stamped for
/// the change feed and, the first time, put on the history's list.
struct Touches<'a> {
    /// `None` when no reader watches the map and it keeps no history.
    stamper: Option<Stamper<'a>>,
    touched: Option<&'a mut Vec<usize>>,
}

impl Touches<'_> {
    /// Mark the cell at row-major `index` as changed by the scan.
    #[inline(always)]
    fn mark(&mut self, index: usize) {
        match (&mut self.stamper, self.touched.as_deref_mut()) {
            (None, _) => {}
            (Some(stamper), None) => stamper.set(index),
            (Some(stamper), Some(touched)) => {
                if stamper.mark(index) {
                    touched.push(index);
                }
            }
        }
    }
}

/// Multiply the kernels of a validated scan into `data`, the histograms of
/// `grid`'s cells, `N` bins each (`N = 0`: any number), as many as `table`
/// serves; every cell updated marked in `touches`.
fn apply<const N: usize, M: SensorModel + ?Sized>(
    grid: &Grid,
    (data, log): (&mut [f32], &mut [f32]),
    table: &KernelTable,
    scan: ScanBeams<'_>,
    model: &M,
    touches: &mut Touches<'_>,
) -> usize {
    let ScanBeams {
        ranges,
        no_echo_reach_m,
        ..
    } = scan;
    let bins = table.bins();
    debug_assert_eq!(data.len(), grid.len() * bins);
    let range = model.range_model();
    let footprint = model.footprint();
    let mut updates = 0;
    for (k, &r) in ranges.iter().enumerate() {
        let (reach, echo) = beam_reach(range, r, k, no_echo_reach_m);
        let d = r.min(range.max_range_m);
        let mut beam = BeamUpdate::<N> {
            data,
            log,
            table,
            bins,
            floor: histogram::BIN_FLOOR,
            lookup: table.reading(d, echo),
            updates: 0,
            touches: &mut *touches,
        };
        visit_reading(grid, &scan, k, echo, reach, footprint, &mut beam);
        updates += beam.updates;
    }
    updates
}

/// The per-cell work of one beam: look the kernel up, add its logarithms to
/// the cell's log-likelihoods and read the histogram off them
/// ([`histogram::update_log`]), mark the cell for the history. Nothing of
/// the cell is read before its kernel is added in, so a map is the same
/// whatever order its scans came in (but for float rounding).
struct BeamUpdate<'a, 't, const N: usize> {
    data: &'a mut [f32],
    log: &'a mut [f32],
    table: &'a KernelTable,
    bins: usize,
    floor: f32,
    lookup: ReadingLookup,
    updates: usize,
    touches: &'a mut Touches<'t>,
}

impl<const N: usize> CellVisitor for BeamUpdate<'_, '_, N> {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, _enter_m: f64) {
        let cell = index * self.bins..(index + 1) * self.bins;
        let ln_k = self.table.ln_at(self.lookup.offset(d_l));
        histogram::update_log::<N>(
            &mut self.log[cell.clone()],
            &mut self.data[cell],
            ln_k,
            self.floor,
        );
        self.touches.mark(index);
        self.updates += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::CovmapError;
    use crate::pose::Pose;
    use crate::sensor::{LaserModel, SonarModel};

    fn grid() -> Grid {
        Grid::new([0.0, 0.0], 0.05, 60, 80).unwrap()
    }

    #[test]
    fn bad_input_leaves_map_unchanged() {
        let mut map = CoverageMap::new(grid());
        let sonar = SonarModel::default();
        map.integrate(&Pose::new(2.0, 1.5, 0.3), &[1.0, 2.0], &[0.0, 1.0], &sonar)
            .unwrap();
        let before = map.histograms().to_vec();
        let p = Pose::new(2.0, 1.5, 0.0);
        let cases: Vec<(Pose, Vec<f64>, Vec<f64>)> = vec![
            (p, vec![1.0, f64::NAN], vec![0.0, 1.0]),
            (p, vec![1.0, -0.1], vec![0.0, 1.0]),
            (p, vec![f64::INFINITY], vec![0.0]),
            (p, vec![1.0], vec![f64::NAN]),
            (p, vec![1.0, 2.0], vec![0.0]),
            (Pose::new(f64::NAN, 1.0, 0.0), vec![1.0], vec![0.0]),
            (Pose::new(1.0, 1.0, f64::INFINITY), vec![1.0], vec![0.0]),
            (Pose::new(-0.01, 1.0, 0.0), vec![1.0], vec![0.0]),
            (Pose::new(4.0, 1.0, 0.0), vec![1.0], vec![0.0]),
            // Heading plus bearing overflows.
            (Pose::new(2.0, 1.5, 1e308), vec![1.0], vec![1e308]),
        ];
        for (pose, r, b) in cases {
            assert!(
                map.integrate(&pose, &r, &b, &sonar).is_err(),
                "{pose:?} {r:?} {b:?}"
            );
            assert_eq!(map.histograms(), &before[..]);
        }
        // Parameters of the right sign whose kernels cannot be computed: a
        // subnormal sigma overflows the density's scale, a huge uniform
        // weight the normalising sum.
        // Each error names the parameter at fault.
        type Break = (fn(&mut SonarModel), &'static str);
        let breaks: [Break; 5] = [
            (|m| m.range.sigma_min = -1.0, "sigma_min"),
            (
                |m| (m.range.sigma_min, m.range.sigma_per_m) = (1e-310, 0.0),
                "sigma_min",
            ),
            (
                |m| (m.range.xi_min, m.range.xi_per_m) = (2e6, 0.0),
                "xi_min",
            ),
            (|m| m.range.xi_min = 1e308, "xi_min"),
            (|m| m.range.xi_per_m = 1e306, "xi_per_m"),
        ];
        for (brk, at_fault) in breaks {
            let mut bad = sonar;
            brk(&mut bad);
            let err = map.integrate(&p, &[1.0], &[0.0], &bad).unwrap_err();
            assert!(
                matches!(err, CovmapError::InvalidParameter { name, .. } if name == at_fault),
                "{err}"
            );
            assert_eq!(map.histograms(), &before[..]);
        }
    }

    #[test]
    fn a_million_identical_readings_leave_no_zero_bin() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut map = CoverageMap::new(g);
        let laser = LaserModel::default();
        let pose = Pose::new(0.01, 0.1, 0.0);
        let ranges = vec![1.0; 1000];
        let bearings = vec![0.0; 1000];
        for _ in 0..1000 {
            map.integrate(&pose, &ranges, &bearings, &laser).unwrap();
        }
        for h in map.histograms().chunks_exact(16) {
            assert!(h.iter().all(|&v| v > 0.0 && v.is_finite()));
            assert!((h.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        }
        // And the evidence of a million "empty" readings is kept, not clamped
        // at the floor: a hundred contrary readings leave the cell empty,
        // where a floored histogram would have turned covered (the bins at the
        // floor hold 69 nats, less than a hundred readings bring).
        let cell = g.world_to_cell(0.5, 0.1).unwrap();
        let i = g.index(cell).unwrap();
        assert_eq!(map.ml()[i], 0.0);
        let short = vec![0.49; 100];
        let mut floored = map.histograms()[i * 16..(i + 1) * 16].to_vec();
        let table = map.kernel_table(&laser.range).unwrap();
        // The cell's centre lies 0.515 m along the beam.
        let k = table.kernel_at(0.525 - 0.01, 0.49).unwrap();
        for _ in 0..100 {
            crate::histogram::update(&mut floored, &k, crate::histogram::BIN_FLOOR);
        }
        assert!(crate::histogram::mean(&floored) > 0.5);
        map.integrate(&pose, &short, &bearings[..100], &laser)
            .unwrap();
        assert_eq!(map.ml()[i], 0.0);
        assert!(map.mean()[i] < 0.01);
    }

    #[test]
    fn model_change_rebuilds_kernels() {
        let mut a = CoverageMap::new(grid());
        let mut b = CoverageMap::new(grid());
        let p = Pose::new(2.0, 1.5, 0.0);
        let sonar = SonarModel::default();
        let mut wide = sonar;
        wide.range.xi_min = 0.5;
        a.integrate(&p, &[1.0], &[0.0], &sonar).unwrap();
        a.integrate(&p, &[1.0], &[0.0], &wide).unwrap();
        b.integrate(&p, &[1.0], &[0.0], &wide).unwrap();
        b.integrate(&p, &[1.0], &[0.0], &sonar).unwrap();
        for (x, y) in a.histograms().iter().zip(b.histograms()) {
            assert!((x - y).abs() < 1e-6);
        }
    }
}
