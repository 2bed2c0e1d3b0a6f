//! Buffers that start on a cache line.
//!
//! A cell's 16 `f32` bins are 64 bytes, one cache line, but only if the
//! histograms start on a line: the allocator aligns a `Vec<f32>` to 16 bytes,
//! and then every histogram straddles two lines, so each cell update and each
//! gain reads twice the lines it needs. [`Aligned`] is a fixed-length buffer of
//! `f32` or `f64` whose first element starts a 64-byte line.

use std::fmt;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};

/// The bytes of a cache line.
const LINE: usize = 64;

/// One cache line of storage.
#[derive(Clone, Copy, Default)]
#[repr(C, align(64))]
struct Line([u64; LINE / 8]);

/// The element types an [`Aligned`] buffer may hold: plain numbers for which
/// every bit pattern (zero in particular) is a valid value.
pub(crate) trait Plain: Copy + private::Sealed {}
impl Plain for f32 {}
impl Plain for f64 {}

mod private {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A fixed-length buffer of `T` (`f32` or `f64`) starting on a cache line.
#[derive(Clone)]
pub(crate) struct Aligned<T: Plain> {
    lines: Vec<Line>,
    len: usize,
    _element: PhantomData<T>,
}

impl<T: Plain> Aligned<T> {
    /// `len` elements, all `value`, or `None` if the memory cannot be had.
    pub(crate) fn try_filled(value: T, len: usize) -> Option<Self> {
        let lines = len.checked_mul(size_of::<T>())?.div_ceil(LINE);
        let mut storage = Vec::new();
        storage.try_reserve_exact(lines).ok()?;
        storage.resize(lines, Line::default());
        let mut buffer = Self {
            lines: storage,
            len,
            _element: PhantomData,
        };
        buffer.fill(value);
        Some(buffer)
    }

    /// A copy of `values`.
    pub(crate) fn from_slice(values: &[T]) -> Self {
        let mut buffer = Self::zeroed(values.len());
        buffer.copy_from_slice(values);
        buffer
    }

    /// `len` elements whose bits are all zero (`0.0`).
    pub(crate) fn zeroed(len: usize) -> Self {
        #[allow(
            clippy::expect_used,
            reason = "the length of an existing slice, whose bytes fit in isize"
        )]
        let bytes = len
            .checked_mul(size_of::<T>())
            .expect("buffer size overflows");
        Self {
            lines: vec![Line::default(); bytes.div_ceil(LINE)],
            len,
            _element: PhantomData,
        }
    }
}

impl<T: Plain> Deref for Aligned<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        // SAFETY: `lines` holds at least `len * size_of::<T>()` initialised
        // bytes (`zeroed`, `try_filled`), aligned to 64 and so to `T`; `T` is `f32` or `f64`
        // (`Plain` is sealed), for which every bit pattern is a valid value.
        unsafe { std::slice::from_raw_parts(self.lines.as_ptr().cast::<T>(), self.len) }
    }
}

impl<T: Plain> DerefMut for Aligned<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        // SAFETY: as in `deref`; the slice borrows `self` mutably.
        unsafe { std::slice::from_raw_parts_mut(self.lines.as_mut_ptr().cast::<T>(), self.len) }
    }
}

impl<T: Plain + fmt::Debug> fmt::Debug for Aligned<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A buffer no address space holds is refused, not aborted on.
    #[test]
    fn try_filled_refuses_what_cannot_be_allocated() {
        assert!(
            Aligned::try_filled(0.0f32, usize::MAX / 2).is_none(),
            "size overflows"
        );
        assert!(
            Aligned::try_filled(0.0f64, isize::MAX as usize / 8).is_none(),
            "beyond the address space"
        );
        let a = Aligned::try_filled(0.25f32, 17).unwrap();
        assert_eq!(a.as_ptr() as usize % LINE, 0);
        assert!(a.iter().all(|&v| v == 0.25) && a.len() == 17);
    }

    #[test]
    fn starts_on_a_line_and_keeps_its_values() {
        for len in [0, 1, 15, 16, 17, 1000] {
            let values: Vec<f32> = (0..len).map(|i| i as f32 * 0.5).collect();
            let a = Aligned::from_slice(&values);
            assert_eq!(a.as_ptr() as usize % LINE, 0);
            assert_eq!(&a[..], &values[..]);
            let b = Aligned::from_slice(&(0..len).map(|i| i as f64).collect::<Vec<_>>());
            assert_eq!(b.as_ptr() as usize % LINE, 0);
            assert_eq!(b.len(), len);
            assert!(b.iter().enumerate().all(|(i, &v)| v == i as f64));
        }
        let mut c = Aligned::try_filled(0.25f32, 33).unwrap();
        c[32] = 1.0;
        assert_eq!(c.iter().sum::<f32>(), 0.25 * 32.0 + 1.0);
        assert_eq!(&c.clone()[..], &c[..]);
        assert_eq!(c.clone().as_ptr() as usize % LINE, 0);
    }
}
