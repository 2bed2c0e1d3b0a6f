//! Which arithmetic the fast evaluator runs with: the widest the processor
//! has, detected at run time, and the walk and the batches compiled for it.

#[cfg(target_arch = "x86_64")]
use super::avx2::weighted_gains_avx2;
#[cfg(target_arch = "x86_64")]
use super::avx512::weighted_gains_avx512;
use super::batch::{Queue, Rows, weighted_gains_with};
use super::walk::Beam;
use crate::gain::GainEvaluator;
use crate::gain::reads::Marks;

/// The arithmetic the fast evaluator is compiled for: what [`Arith::detect`]
/// finds decides which one runs. Each wider one includes the narrower.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(in crate::gain) enum Arith {
    /// The target's baseline (SSE2 on x86-64).
    Baseline = BASELINE,
    /// AVX2 and FMA.
    Avx2 = AVX2,
    /// AVX-512 (F, DQ, VL) with AVX2 and FMA: a 16-bin row in two registers.
    Avx512 = AVX512,
}

/// [`Arith`] as the const parameter of the compiled paths.
pub(super) const BASELINE: u8 = 0;
pub(super) const AVX2: u8 = 1;
pub(super) const AVX512: u8 = 2;

mod evidence {
    /// Evidence that the processor has the instructions the arithmetic `A`
    /// ([`super::Arith`]) names: the paths compiled for them run only with
    /// one in hand. Only the baseline's is made without `unsafe`.
    #[derive(Clone, Copy)]
    pub(in crate::gain::fast) struct Has<const A: u8>(());

    impl<const A: u8> Has<A> {
        /// # Safety
        /// The processor must have the instructions `A` names.
        pub(in crate::gain::fast) unsafe fn new() -> Self {
            Self(())
        }
    }

    impl Has<{ super::BASELINE }> {
        /// Every processor has the target's baseline.
        pub(in crate::gain::fast) fn baseline() -> Self {
            Self(())
        }
    }
}
pub(super) use evidence::Has;

impl Arith {
    /// The widest arithmetic this processor has.
    pub(in crate::gain) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            let avx2 = has!("avx2") && has!("fma");
            if avx2 && has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
                return Self::Avx512;
            }
            if avx2 {
                return Self::Avx2;
            }
        }
        Self::Baseline
    }

    /// Every arithmetic this processor can run, widest first (for tests).
    #[cfg(test)]
    pub(in crate::gain) fn available() -> Vec<Self> {
        let widest = Self::detect() as u8;
        [Self::Avx512, Self::Avx2, Self::Baseline]
            .into_iter()
            .filter(|&a| a as u8 <= widest)
            .collect()
    }
}

impl GainEvaluator<'_> {
    /// One beam's sum with `N` bins, the whole walk compiled for the widest
    /// arithmetic the processor has.
    pub(super) fn run<const N: usize>(
        &self,
        beam: &Beam<'_>,
        queue: &mut Queue,
        marks: Option<&mut Marks<'_>>,
    ) -> f64 {
        #[cfg(target_arch = "x86_64")]
        match self.arith {
            // SAFETY: `arith` is `Avx512` or `Avx2` only where the processor
            // has those instructions (`Arith::detect`).
            Arith::Avx512 => return unsafe { self.run_avx512::<N>(beam, queue, marks) },
            Arith::Avx2 => return unsafe { self.run_avx2::<N>(beam, queue, marks) },
            Arith::Baseline => {}
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = self.arith;
        self.run_with::<N, BASELINE>(Has::baseline(), beam, queue, marks)
    }

    /// [`Self::run_with`] compiled for AVX-512 (F, DQ, VL), AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
    fn run_avx512<const N: usize>(
        &self,
        beam: &Beam<'_>,
        queue: &mut Queue,
        marks: Option<&mut Marks<'_>>,
    ) -> f64 {
        // SAFETY: this function is compiled for AVX-512, so it may only be
        // called where the processor has it.
        let has = unsafe { Has::<AVX512>::new() };
        self.run_with::<N, AVX512>(has, beam, queue, marks)
    }

    /// [`Self::run_with`] compiled for AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn run_avx2<const N: usize>(
        &self,
        beam: &Beam<'_>,
        queue: &mut Queue,
        marks: Option<&mut Marks<'_>>,
    ) -> f64 {
        // SAFETY: this function is compiled for AVX2 and FMA, so it may only
        // be called where the processor has them.
        let has = unsafe { Has::<AVX2>::new() };
        self.run_with::<N, AVX2>(has, beam, queue, marks)
    }
}

/// [`weighted_gains_with`] compiled for the arithmetic `A` (`N > 0`), which
/// `has` shows the processor to have. (`inline`: in the walk's file it was
/// inlined into the flush of a batch; the hint keeps it so across files.)
#[inline]
pub(super) fn weighted_gains<const N: usize, const A: u8>(
    has: Has<A>,
    rows: &Rows<'_, N>,
    jobs: &Queue,
) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: `has` shows that the processor has the instructions `A`
        // names.
        if A == AVX512 {
            return unsafe { weighted_gains_avx512::<N>(rows, jobs) };
        }
        if A == AVX2 {
            return unsafe { weighted_gains_avx2::<N>(rows, jobs) };
        }
    }
    let _ = has;
    weighted_gains_with::<N, BASELINE>(Has::baseline(), rows, jobs)
}
