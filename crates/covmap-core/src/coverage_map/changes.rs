//! Which cells changed since a reader last looked: the map's one change
//! feed.
//!
//! Every change of a map's histograms (a scan's cells, a contact's, a
//! pinned cell's) stamps the cells it changed with the map's next version.
//! A reader keeps a [`ChangeCursor`] (which map, which version it has read
//! up to) and asks [`CoverageMap::changes_since`] for the cells stamped
//! after it: the planning cache, the exploration loop's bookkeeping and the
//! strategies' kept masks all read this one feed, each with its cursor, so
//! no reader keeps a copy of the histograms to compare with, and none takes
//! a caller's word for what changed.
//!
//! A map's identity is part of the cursor: a map made, loaded or cloned
//! anew has an identity of its own, so that a cursor of another map (even
//! one with the same grid and the same number of changes) reads as "every
//! cell changed". The stamps cost four bytes a cell; reading the feed is
//! one pass over them. A map that no reader watches (no cursor was ever
//! taken of it, and it keeps no history) does not stamp its scans' cells:
//! plain mapping pays nothing for the feed.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use super::CoverageMap;
use crate::error::Result;
use crate::memory;

/// Where a reader of a map's changes has read up to: the map's identity
/// and its version then. See [`CoverageMap::changes_since`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ChangeCursor {
    /// The identity of the map read (0: none yet).
    map: u64,
    /// The map's version when it was read.
    version: u32,
}

/// The cells of a map that changed since a [`ChangeCursor`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Changes {
    /// The cursor is of another map (or of none): take every cell as changed.
    All,
    /// The cells changed since, row-major indices, ascending, each once.
    Cells(Vec<usize>),
}

/// The identities of maps, each taken once.
static NEXT_IDENTITY: AtomicU64 = AtomicU64::new(1);

/// A map's identity: a clone takes a new one (the two maps go their own
/// ways from there).
#[derive(Debug)]
struct Identity(u64);

impl Identity {
    fn new() -> Self {
        Self(NEXT_IDENTITY.fetch_add(1, Ordering::Relaxed))
    }
}

impl Clone for Identity {
    fn clone(&self) -> Self {
        Self::new()
    }
}

/// Whether a cursor of the map was ever taken; a clone starts unwatched
/// (it has an identity of its own, so no cursor of it exists yet).
#[derive(Debug, Default)]
struct Watched(AtomicBool);

impl Clone for Watched {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// The change stamps of a map's cells.
#[derive(Clone, Debug)]
pub(super) struct ChangeStamps {
    identity: Identity,
    watched: Watched,
    /// The version of the last change (0: none yet).
    version: u32,
    /// The version of each cell's last change, row-major.
    stamps: Vec<u32>,
}

impl ChangeStamps {
    /// The stamps of a new map of `cells` cells (nothing changed yet), or
    /// [`CovmapError::OutOfMemory`](crate::CovmapError::OutOfMemory).
    pub(super) fn new(cells: usize) -> Result<Self> {
        let mut stamps = memory::try_with_capacity::<u32>(cells, "the map's change stamps")?;
        stamps.resize(cells, 0);
        Ok(Self {
            identity: Identity::new(),
            watched: Watched::default(),
            version: 0,
            stamps,
        })
    }

    /// Begin a scan's change: the stamper its cells are marked with, or
    /// `None` (the version moves on all the same) if no reader watches the
    /// map and the caller needs no stamps of its own (`needed`: the
    /// history's first-visit marks).
    pub(super) fn begin_watched(&mut self, needed: bool) -> Option<Stamper<'_>> {
        if needed || *self.watched.0.get_mut() {
            Some(self.begin())
        } else {
            self.version = self.version.saturating_add(1);
            None
        }
    }

    /// Begin a change: the stamper its cells are marked with.
    pub(super) fn begin(&mut self) -> Stamper<'_> {
        if self.version == u32::MAX {
            // Stamps of old versions would read as new ones: the map takes
            // a new identity, so that every reader starts over.
            self.stamps.fill(0);
            self.version = 0;
            self.identity = Identity::new();
        }
        self.version += 1;
        Stamper {
            stamps: &mut self.stamps,
            version: self.version,
        }
    }
}

/// Marks the cells of one change (one scan, one contact) as changed.
pub(super) struct Stamper<'s> {
    stamps: &'s mut [u32],
    version: u32,
}

impl Stamper<'_> {
    /// Mark the cell at row-major `index` (a store only: the update's inner
    /// loop when no one asks which cells are new).
    #[inline(always)]
    pub(super) fn set(&mut self, index: usize) {
        self.stamps[index] = self.version;
    }

    /// Mark the cell at row-major `index`; true the first time this change
    /// marks it.
    #[inline(always)]
    pub(super) fn mark(&mut self, index: usize) -> bool {
        let first = self.stamps[index] != self.version;
        self.stamps[index] = self.version;
        first
    }
}

impl CoverageMap {
    /// Where the map stands now, for [`CoverageMap::changes_since`] to tell
    /// later what changed since.
    pub fn change_cursor(&self) -> ChangeCursor {
        self.changes.watched.0.store(true, Ordering::Relaxed);
        ChangeCursor {
            map: self.changes.identity.0,
            version: self.changes.version,
        }
    }

    /// The cells whose histograms changed since `cursor` was taken (by
    /// [`CoverageMap::change_cursor`]), ascending; [`Changes::All`] for a
    /// cursor of another map. A cell is named if a change touched it, even
    /// if its histogram came out with the same bits.
    ///
    /// # Example
    /// ```
    /// use covmap_core::{Changes, CoverageMap, Grid, LaserModel, Pose, ScanMap};
    /// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 10, 10).unwrap());
    /// assert_eq!(map.changes_since(&Default::default()), Changes::All);
    /// let cursor = map.change_cursor();
    /// assert_eq!(map.changes_since(&cursor), Changes::Cells(vec![]));
    /// map.integrate(&Pose::new(0.05, 0.55, 0.0), &[0.3], &[0.0], &LaserModel::default()).unwrap();
    /// let Changes::Cells(cells) = map.changes_since(&cursor) else { panic!() };
    /// assert_eq!(cells, vec![50, 51, 52, 53, 54]); // row 5, out to the end band
    /// assert_eq!(map.clone().changes_since(&cursor), Changes::All);
    /// ```
    pub fn changes_since(&self, cursor: &ChangeCursor) -> Changes {
        if cursor.map != self.changes.identity.0 {
            return Changes::All;
        }
        let after = cursor.version;
        Changes::Cells(
            self.changes
                .stamps
                .iter()
                .enumerate()
                .filter(|&(_, &s)| s > after)
                .map(|(i, _)| i)
                .collect(),
        )
    }
}
