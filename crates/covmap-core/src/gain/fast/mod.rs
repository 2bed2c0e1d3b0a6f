//! The fast evaluator, [`GainMethod::Fast`](super::GainMethod::Fast): the
//! exact evaluator's sums (to rounding), much faster, from these facts:
//! - a cell in front of the end point gets a kernel that depends on the cell's
//!   distance, not on the reading (see [`crate::sensor`]), so the readings that
//!   leave it in free space contribute `I_free * (sum of their p(d))`: a suffix
//!   sum of `p(d)`; only the few readings that end near the cell need a kernel
//!   of their own;
//! - readings of probability 0 contribute nothing and are skipped, and a
//!   beam's footprint is walked only out to the reach of its farthest
//!   possible reading: a cell the ML map holds as fully covered stops every
//!   predicted beam, so the cells behind it (out of reach of every reading
//!   that can occur) are not visited at all;
//! - every cell still at the uniform prior gains the same under a given
//!   kernel, so those gains are computed once per kernel of the table and
//!   looked up (in unexplored space a pair costs a table read);
//! - with `h ln h` of every bin computed once per evaluator, the entropy of an
//!   updated histogram costs three dot products and one logarithm:
//!   `H(h k / Z) = ln Z - A / Z`, `Z = sum h k`, `A = sum k (h ln h) + h (k ln k)`;
//! - the gains are computed in batches, the logarithms of a batch together as
//!   vector code; the whole walk of a beam is compiled for the widest
//!   arithmetic the processor has (detected at run time): AVX-512, where
//!   eight gains go through the sums, the logarithm and the weighting
//!   together (a 16-bin row in two registers), or AVX2 and FMA, or the
//!   target's baseline; every path agrees with the others to rounding and is
//!   tested against the exact evaluator; the cache lines a queued gain will
//!   read are requested when it is queued, so that they have arrived when the
//!   batch is computed;
//! - a cone is walked in blocks of a row's neighbouring cells, and a block
//!   that lies wholly in front of the nearest echo it could meet (most of
//!   them) queues its free-space gains at once, without testing echoes cell
//!   by cell.
//!
//! The parts: [`walk`] follows a beam's footprint and sends each cell's gains
//! to the queue of [`batch`] (or adds them at once from [`cell_terms`] for
//! cells at the prior); [`arith`] picks the widest arithmetic the processor
//! has and compiles the walk and the batches for it ([`avx2`], [`avx512`]).

mod arith;
#[cfg(target_arch = "x86_64")]
mod avx2;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod batch;
mod cell_terms;
#[cfg(test)]
mod tests;
mod walk;

pub(super) use arith::Arith;
pub(super) use batch::Queue;
pub(super) use cell_terms::{CellTerms, Piece};
