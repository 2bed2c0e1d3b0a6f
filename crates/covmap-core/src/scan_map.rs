//! The maps scans are integrated into, behind one interface: the coverage
//! map, the occupancy grid and the scan counts each take a checked scan in
//! their own way ([`ScanMap::integrate_checked`]); checking a scan first,
//! clipping no-echo readings and taking in a whole log are written once,
//! here.

use crate::echo_sources::EchoSources;
use crate::error::Result;
use crate::grid::Grid;
use crate::log::Log;
use crate::pose::{Pose, validate_scan};
use crate::sensor::SensorModel;
use crate::sight::NoEchoSight;

/// One scan as a map takes it: from `pose`, reading `ranges[i]` (metres)
/// along `pose.theta_rad + bearings[i]`; no-echo reading `k` clearing its
/// footprint only up to `no_echo_reach_m[k]` metres, where given.
#[derive(Clone, Copy, Debug)]
pub struct ScanBeams<'a> {
    /// Where the scan was taken from.
    pub pose: &'a Pose,
    /// The readings, metres.
    pub ranges: &'a [f64],
    /// Their bearings relative to the heading, radians.
    pub bearings: &'a [f64],
    /// How far each no-echo reading clears, metres (`None`: the model's
    /// no-echo reach).
    pub no_echo_reach_m: Option<&'a [f64]>,
    /// Which cells each no-echo reading clears within that reach: those in
    /// no covered cell's shadow ([`NoEchoSight`]; `None`: all of them).
    pub no_echo_sight: Option<&'a NoEchoSight>,
    /// Which cells at and past its end point each echo reading marks: all
    /// but those its sources withhold ([`EchoSources`]; `None`: all of
    /// them).
    pub echo_sources: Option<&'a EchoSources>,
}

impl<'a> ScanBeams<'a> {
    /// The scan from `pose` of `ranges` along `bearings`, read as the
    /// sensor model has it: no reach, sight or echo sources of its own.
    pub fn new(pose: &'a Pose, ranges: &'a [f64], bearings: &'a [f64]) -> Self {
        Self {
            pose,
            ranges,
            bearings,
            no_echo_reach_m: None,
            no_echo_sight: None,
            echo_sources: None,
        }
    }
}

/// A map that range scans are integrated into, every scan checked before
/// anything changes: [`CoverageMap`](crate::CoverageMap),
/// [`OccupancyGrid`](crate::OccupancyGrid) and
/// [`ScanCounts`](crate::ScanCounts), fed the very same beams.
///
/// # Example
/// ```
/// use covmap_core::{CoverageMap, Grid, OccupancyGrid, Pose, ScanMap, SonarModel};
/// let grid = Grid::new([0.0, 0.0], 0.05, 80, 80).unwrap();
/// let (mut map, mut occupancy) = (CoverageMap::new(grid), OccupancyGrid::new(grid));
/// let pose = Pose::new(2.0, 2.0, 0.0);
/// let sonar = SonarModel::default();
/// // The same beams, each map's cell updates (a coverage map's reach the
/// // band behind an end point too).
/// let updated = map.integrate(&pose, &[1.0, 1.5], &[0.0, 1.6], &sonar).unwrap();
/// let counted = occupancy.integrate(&pose, &[1.0, 1.5], &[0.0, 1.6], &sonar).unwrap();
/// assert!(0 < counted && counted < updated);
/// assert!(map.integrate(&pose, &[f64::NAN], &[0.0], &sonar).is_err());
/// ```
pub trait ScanMap {
    /// The grid.
    fn grid(&self) -> &Grid;

    /// Integrate `scan`, already checked against the grid and `model`
    /// (see [`ScanMap::integrate`]); the number of cell updates. It fails
    /// only before it changes anything (a model whose kernels cannot be
    /// computed).
    ///
    /// # Errors
    /// As [`ScanMap::integrate`], past the scan's checks.
    fn integrate_checked<M: SensorModel + ?Sized>(
        &mut self,
        scan: ScanBeams<'_>,
        model: &M,
    ) -> Result<usize>;

    /// Integrate one scan taken from `pose`: reading `ranges[i]` (metres)
    /// along `pose.theta_rad + bearings[i]`. Returns the number of cell
    /// updates.
    ///
    /// # Errors
    /// Everything is checked before anything changes: a non-finite pose, a
    /// pose outside the map, a NaN, infinite or negative range, a
    /// non-finite bearing, mismatched lengths or an invalid model is an
    /// error and leaves the map exactly as it was. Beams leaving the map
    /// update the part inside.
    fn integrate<M: SensorModel + ?Sized>(
        &mut self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> Result<usize> {
        let scan = ScanBeams::new(pose, ranges, bearings);
        validate_scan(self.grid(), pose, ranges, bearings, model)?;
        self.integrate_checked(scan, model)
    }

    /// [`ScanMap::integrate`] of `scan`, no-echo readings clipped where it
    /// says: a no-echo reading that the caller takes to have missed an
    /// obstacle specularly says nothing of what lies behind it (the
    /// exploration loop stops each before the nearest obstacle its map
    /// holds in the reading's footprint).
    ///
    /// # Errors
    /// As [`ScanMap::integrate`];
    /// [`CovmapError::LengthMismatch`](crate::CovmapError::LengthMismatch)
    /// unless there is one reach a reading,
    /// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter)
    /// for a reach that is NaN or negative. The map is unchanged then.
    fn integrate_scan<M: SensorModel + ?Sized>(
        &mut self,
        scan: ScanBeams<'_>,
        model: &M,
    ) -> Result<usize> {
        if let Some(reaches) = scan.no_echo_reach_m {
            crate::coverage_map::check_reaches(scan.ranges, reaches)?;
        }
        if let Some(sight) = scan.no_echo_sight {
            crate::coverage_map::check_sight(scan.ranges, sight.len())?;
        }
        if let Some(sources) = scan.echo_sources {
            crate::coverage_map::check_sight(scan.ranges, sources.len())?;
        }
        validate_scan(self.grid(), scan.pose, scan.ranges, scan.bearings, model)?;
        self.integrate_checked(scan, model)
    }

    /// Integrate every scan of `log`, in order, with `model`; returns the
    /// number of cell updates. Each scan is taken from its sensor pose (the
    /// robot's pose composed with the log's sensor offset); dropped beams
    /// are skipped; a reading without echo clears its footprint up to the
    /// lesser of the log's and the model's maximum range.
    ///
    /// # Errors
    /// Every scan is checked before any changes:
    /// [`CovmapError::InScan`](crate::CovmapError::InScan) names the first
    /// scan whose sensor pose lies outside the map or whose bearing added
    /// to the heading overflows; an invalid model is an error of its own.
    /// The map is unchanged then.
    ///
    /// # Example
    /// ```
    /// use covmap_core::{Bearings, CoverageMap, Grid, LaserModel, Log, Pose, ScanMap};
    /// let log = Log::new(vec![Pose::new(1.0, 1.0, 0.0)], vec![0.0], vec![1.5],
    ///                    Bearings::Fixed(vec![0.0]), 30.0).unwrap();
    /// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 20, 40).unwrap());
    /// assert!(map.integrate_log(&log, &LaserModel::default()).unwrap() > 0);
    /// let far = Log::new(vec![Pose::new(9.0, 1.0, 0.0)], vec![0.0], vec![1.5],
    ///                    Bearings::Fixed(vec![0.0]), 30.0).unwrap();
    /// let before = map.histograms().to_vec();
    /// assert!(map.integrate_log(&far, &LaserModel::default()).is_err());
    /// assert_eq!(map.histograms(), &before[..]);
    /// ```
    fn integrate_log<M: SensorModel + ?Sized>(&mut self, log: &Log, model: &M) -> Result<usize> {
        self.integrate_log_with_progress(log, model, &mut |_| {})
    }

    /// [`ScanMap::integrate_log`], calling `progress` with the number of
    /// scans integrated so far after each scan.
    ///
    /// # Errors
    /// As [`ScanMap::integrate_log`].
    fn integrate_log_with_progress<M: SensorModel + ?Sized>(
        &mut self,
        log: &Log,
        model: &M,
        progress: &mut dyn FnMut(usize),
    ) -> Result<usize> {
        let grid = *self.grid();
        crate::log::integrate_scans(&grid, log, model, progress, |scan| {
            self.integrate_checked(scan, model)
        })
    }
}
