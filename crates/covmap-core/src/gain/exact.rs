//! The exact evaluator: the equation as written, the reference of every
//! faster path.

use super::GainEvaluator;
use crate::footprint::visit;
use crate::histogram::entropy_f64;
use crate::numeric::x_ln_x;

/// `I(h | k) = H(h) - H(h')`, `h'` the normalised product of `h` and kernel
/// `k`, straight from the definitions (eq. 11-12).
pub fn information_gain(h: &[f32], k: &[f32]) -> f64 {
    let z: f64 = h
        .iter()
        .zip(k)
        .map(|(&a, &b)| f64::from(a) * f64::from(b))
        .sum();
    let posterior_entropy = -h
        .iter()
        .zip(k)
        .map(|(&a, &b)| x_ln_x(f64::from(a) * f64::from(b) / z))
        .sum::<f64>();
    entropy_f64(h) - posterior_entropy
}

impl GainEvaluator<'_> {
    /// Sum of the gains of the cells a reading `d` would update.
    fn exact_reading(&self, origin: [f64; 2], angle: f64, d: f64) -> f64 {
        let (reach, echo) = self.range.reach(d);
        let lookup = self.table.reading(d.min(self.range.max_range_m), echo);
        let (data, bins) = (self.map.histograms(), self.map.bins());
        let mut sum = 0.0;
        visit(
            self.map.grid(),
            origin,
            angle,
            reach,
            self.footprint,
            &mut |i, d_l| {
                sum += information_gain(
                    &data[i * bins..(i + 1) * bins],
                    self.table.at(lookup.offset(d_l)),
                );
            },
        );
        sum
    }

    pub(super) fn exact_beam(&self, origin: [f64; 2], angle: f64) -> f64 {
        let dist = self.distribution(origin, angle);
        let mut total = 0.0;
        for (j, &p) in dist.probabilities.iter().enumerate() {
            total += p * self.exact_reading(origin, angle, j as f64 * dist.step_m);
        }
        total + dist.no_echo * self.exact_reading(origin, angle, self.range.max_range_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn information_gain_of_uniform_kernel_is_zero() {
        let h = [0.1, 0.2, 0.3, 0.4];
        assert!(information_gain(&h, &[0.25; 4]).abs() < 1e-7);
        // From the prior, any informative kernel gains.
        assert!(information_gain(&[0.25; 4], &[0.7, 0.1, 0.1, 0.1]) > 0.0);
    }
}
