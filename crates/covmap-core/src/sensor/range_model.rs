//! The inverse model along one direction, shared by every range sensor.

use serde::{Deserialize, Serialize};

use super::KernelTable;
use super::kernel;
#[cfg(doc)]
use super::parameters::Parameter;
use super::parameters::{
    MAX_XI, RANGE_PARAMETERS, REMOVED_PARAMETERS, check_each, check_removed, find,
};
use crate::error::{Result, check_parameter};

/// The struct of the range model, its presets, its serde form and its
/// per-parameter access, from the declaration's entries.
macro_rules! range_model_struct {
    // Only the presets' values are read here; the rest of an entry goes
    // to `parameter_table!`.
    ([ $( $(#[doc = $doc:literal])* $name:ident {
        unit: $unit:expr, sonar: $sonar:expr, laser: $laser:expr, $($rest:tt)*
    } )* ]) => {
        /// The parameters shared by every range sensor: the inverse model
        /// along one direction (see the [module documentation](super)).
        /// Declared once, with their defaults, checks and fit bounds, in
        /// [`range_parameters!`](crate::range_parameters); the table
        /// [`RANGE_PARAMETERS`] lists them in this order.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
        #[serde(try_from = "StoredRangeModel")]
        pub struct RangeModel {
            $( $(#[doc = $doc])* pub $name: f64, )*
        }

        /// A stored range model as read, every parameter optional: those
        /// absent take their [`Parameter::absent`] value, or are an error.
        /// The removed parameters ([`REMOVED_PARAMETERS`]) are read too, to
        /// be checked off and dropped.
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct StoredRangeModel {
            $( $name: Option<f64>, )*
            posterior_floor: Option<f64>,
            end_attribution: Option<f64>,
            free_yield: Option<f64>,
            no_echo_reach: Option<f64>,
            no_echo_weight: Option<f64>,
        }

        impl StoredRangeModel {
            /// The values read, in the order of [`RANGE_PARAMETERS`].
            fn values(&self) -> [Option<f64>; RANGE_PARAMETERS.len()] {
                [$( self.$name ),*]
            }

            /// The removed parameters read, in the order of [`REMOVED_PARAMETERS`].
            fn removed(&self) -> [Option<f64>; REMOVED_PARAMETERS.len()] {
                [
                    self.posterior_floor,
                    self.end_attribution,
                    self.free_yield,
                    self.no_echo_reach,
                    self.no_echo_weight,
                ]
            }
        }

        impl RangeModel {
            /// The sonar's defaults: the paper's reading of every term the
            /// paper has (see [`SonarModel`](super::SonarModel)'s `Default`).
            pub const SONAR: Self = Self { $( $name: $sonar, )* };
            /// The laser's defaults (see [`LaserModel`](super::LaserModel)'s `Default`).
            pub const LASER: Self = Self { $( $name: $laser, )* };

            /// Every parameter's value, in the order of [`RANGE_PARAMETERS`].
            pub fn values(&self) -> [f64; RANGE_PARAMETERS.len()] {
                [$( self.$name ),*]
            }

            /// Every parameter's field, in the order of [`RANGE_PARAMETERS`].
            fn fields_mut(&mut self) -> [&mut f64; RANGE_PARAMETERS.len()] {
                [$( &mut self.$name ),*]
            }
        }
    };
}

crate::range_parameters!(range_model_struct! {});

impl TryFrom<StoredRangeModel> for RangeModel {
    type Error = String;
    fn try_from(stored: StoredRangeModel) -> std::result::Result<Self, String> {
        for (value, removed) in stored.removed().into_iter().zip(&REMOVED_PARAMETERS) {
            if let Some(value) = value {
                check_removed(removed, value).map_err(|e| e.to_string())?;
            }
        }
        let mut model = Self::SONAR;
        let read = stored.values().into_iter().zip(&RANGE_PARAMETERS);
        for ((value, parameter), field) in read.zip(model.fields_mut()) {
            *field = value
                .or(parameter.absent)
                .ok_or_else(|| format!("missing field `{}`", parameter.name))?;
        }
        Ok(model)
    }
}

impl RangeModel {
    /// The value of the parameter called `name`, if the model has one.
    pub fn get(&self, name: &str) -> Option<f64> {
        find(&RANGE_PARAMETERS, name).map(|(i, _)| self.values()[i])
    }

    /// Set the parameter called `name` to `value` (not validated); false
    /// if the model has no such parameter.
    pub fn set(&mut self, name: &str, value: f64) -> bool {
        match find(&RANGE_PARAMETERS, name) {
            Some((i, _)) => {
                *self.fields_mut()[i] = value;
                true
            }
            None => false,
        }
    }

    /// The bits of every parameter, in the order of [`RANGE_PARAMETERS`]:
    /// two models are the same model exactly when these are equal.
    pub fn bits(&self) -> [u64; RANGE_PARAMETERS.len()] {
        self.values().map(f64::to_bits)
    }

    /// Errors unless every parameter lies in its valid range
    /// ([`Parameter::valid`], finite), the uniform weight is at most 1e6
    /// out to the maximum range, and `sigma_end` is no smaller than `sigma`
    /// anywhere outside the band.
    pub fn validate(&self) -> Result<()> {
        check_each(&RANGE_PARAMETERS, &self.values())?;
        check_parameter(
            self.xi(self.max_range_m) <= MAX_XI,
            "xi_per_m",
            self.xi_per_m,
            "a growth that keeps xi_min + xi_per_m * max_range_m at most 1e6",
        )?;
        check_parameter(
            self.sigma_end >= self.sigma(self.max_range_m),
            "sigma_end",
            self.sigma_end,
            "a standard deviation no smaller than sigma anywhere outside the band (sigma_min + sigma_per_m * max_range_m)",
        )
    }

    /// `sigma` outside the end band at distance `s_m = min(d_l, d)`.
    pub fn sigma(&self, s_m: f64) -> f64 {
        self.sigma_min + self.sigma_per_m * s_m
    }

    /// The uniform weight at distance `s_m = min(d_l, d)`.
    pub fn xi(&self, s_m: f64) -> f64 {
        self.xi_min + self.xi_per_m * s_m
    }

    /// How far along the beam a reading of `range_m` reaches, and whether it is
    /// an echo (`false`: no echo, clear up to the maximum range).
    pub fn reach(&self, range_m: f64) -> (f64, bool) {
        if range_m >= self.max_range_m {
            (self.max_range_m, false)
        } else {
            (range_m + self.band_m, true)
        }
    }

    /// The kernel the map multiplies in for a cell at `cell_distance_m` and a
    /// reading of `measured_distance_m`, on a grid of `resolution_m` with `bins`
    /// bins, or `None` where the cell is not updated. It comes from the same
    /// precomputed table the update uses (built anew on every call: for
    /// looking at kernels, not for loops).
    ///
    /// Errors if the model is invalid, the resolution is not finite or below
    /// [`crate::MIN_RESOLUTION_M`], the bin count is not supported, or a
    /// distance is NaN, infinite or negative.
    pub fn kernel(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Result<Option<Vec<f32>>> {
        check_distances(cell_distance_m, measured_distance_m)?;
        let table = KernelTable::new(self, resolution_m, bins)?;
        Ok(table.kernel_at(cell_distance_m, measured_distance_m))
    }

    /// The exact (unquantised) kernel for a cell at `cell_distance_m` and a
    /// reading of `measured_distance_m`, on a grid of `resolution_m` with `bins`
    /// bins: the histogram the update multiplies in, normalised to sum 1, or
    /// `None` where the cell is not updated (further than the band behind the
    /// end point). This is the reference the kernel table is tested against.
    ///
    /// Errors as [`Self::kernel`] does.
    pub fn kernel_exact(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Result<Option<Vec<f64>>> {
        check_distances(cell_distance_m, measured_distance_m)?;
        self.validate()?;
        kernel::check_resolution(resolution_m)?;
        crate::histogram::check_bins(bins)?;
        Ok(self.exact_kernel(cell_distance_m, measured_distance_m, resolution_m, bins))
    }

    /// [`Self::kernel_exact`] of valid inputs.
    fn exact_kernel(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Option<Vec<f64>> {
        let (reach, echo) = self.reach(measured_distance_m);
        if cell_distance_m > reach {
            return None;
        }
        let d = measured_distance_m.min(self.max_range_m);
        let s = cell_distance_m.max(0.0).min(d);
        let o = cell_distance_m - d;
        let half = 0.5 * resolution_m;
        let (mu, sigma) = if !echo || o < -half {
            (0.0, self.sigma(s))
        } else if o <= half {
            (0.5 + o / resolution_m, self.sigma_end)
        } else {
            (1.0, self.sigma(s))
        };
        let k = kernel_values(mu, sigma, self.xi(s), bins);
        Some(if echo && o >= -half {
            self.end_mixture(k)
        } else {
            k
        })
    }

    /// A kernel of the end band or behind it as an echo gives it: mixed
    /// with the uniform prior by `end_weight` (unchanged at weight 1).
    pub(crate) fn end_mixture(&self, k: Vec<f64>) -> Vec<f64> {
        mixture(k, self.end_weight)
    }
}

/// `w k + (1 - w) / bins`: kernel `k` mixed with the uniform prior by the
/// weight `w` (`k` itself at weight 1).
fn mixture(mut k: Vec<f64>, w: f64) -> Vec<f64> {
    if w < 1.0 {
        let uniform = 1.0 / k.len() as f64;
        k.iter_mut().for_each(|v| *v = w * *v + (1.0 - w) * uniform);
    }
    k
}

/// Errors unless both distances of a kernel query are finite and
/// non-negative.
fn check_distances(cell_distance_m: f64, measured_distance_m: f64) -> Result<()> {
    for (name, value) in [
        ("cell_distance_m", cell_distance_m),
        ("measured_distance_m", measured_distance_m),
    ] {
        check_parameter(
            value.is_finite() && value >= 0.0,
            name,
            value,
            "a finite, non-negative distance",
        )?;
    }
    Ok(())
}

/// `xi + N(x_b; mu, sigma)` at the bin values `x_b = b / (bins - 1)`, normalised.
pub(crate) fn kernel_values(mu: f64, sigma: f64, xi: f64, bins: usize) -> Vec<f64> {
    let norm = 1.0 / (sigma * (2.0 * std::f64::consts::PI).sqrt());
    let mut k: Vec<f64> = (0..bins)
        .map(|b| {
            let z = (crate::histogram::bin_value(b, bins) - mu) / sigma;
            xi + norm * (-0.5 * z * z).exp()
        })
        .collect();
    let sum: f64 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= sum);
    k
}

#[cfg(test)]
mod tests {
    use crate::sensor::{LaserModel, SonarModel};

    #[test]
    fn a_stored_model_may_name_a_removed_parameter_only_at_its_off_value() {
        let with = |name: &str, value: f64| {
            let mut json = serde_json::to_value(SonarModel::default()).unwrap();
            json[name] = value.into();
            json
        };
        for removed in super::REMOVED_PARAMETERS {
            let (name, off) = (removed.name, removed.off);
            // Off, as every model stored before the removal had it by default.
            let read: SonarModel = serde_json::from_value(with(name, off)).unwrap();
            assert_eq!(read, SonarModel::default(), "{name}");
            let mut laser = serde_json::to_value(LaserModel::default()).unwrap();
            laser[name] = off.into();
            assert_eq!(
                serde_json::from_value::<LaserModel>(laser).unwrap(),
                LaserModel::default()
            );
            // On: the model it describes is one covmap no longer builds.
            let err = serde_json::from_value::<SonarModel>(with(name, 0.05))
                .unwrap_err()
                .to_string();
            assert!(err.contains(name) && err.contains("removed"), "{err}");
        }
        // Any other unknown field is still an error.
        assert!(serde_json::from_value::<SonarModel>(with("nonsense", 0.0)).is_err());
    }
}
