//! The sensor models' parameters, each declared once.
//!
//! [`range_parameters!`](crate::range_parameters) is the one list of the
//! range model's parameters: for each, its name, doc, unit, the sonar's and
//! the laser's default, the values it may take and the bounds a fit
//! searches within (if a fit may change it). Everything that lists the
//! parameters follows from it: the [`RangeModel`](super::RangeModel) struct
//! and its serde form, its presets ([`RangeModel::SONAR`](super::RangeModel::SONAR),
//! [`RangeModel::LASER`](super::RangeModel::LASER)), the per-parameter
//! checks of [`RangeModel::validate`](super::RangeModel::validate), the
//! table [`RANGE_PARAMETERS`] (which a fit's list of parameters, a cache's
//! comparison and the Python stubs read), and, in the binding crate, the
//! Python classes' keywords and attributes (which invoke the macro with a
//! callback of their own). [`sonar_parameters!`](crate::sonar_parameters)
//! does the same for the sonar's own parameter, the cone's opening angle.
//!
//! Removing a parameter is removing its entry (and the code that reads it),
//! and naming it in [`REMOVED_PARAMETERS`] so that models stored with it
//! off still load.

/// One parameter of a sensor model, as [`range_parameters!`](crate::range_parameters)
/// declares it.
#[derive(Clone, Copy, Debug)]
pub struct Parameter {
    /// The field's name, as in the model's serde form and Python keywords.
    pub name: &'static str,
    /// What it is, in a sentence or a few (the field's documentation).
    pub doc: &'static str,
    /// Its unit: `"m"`, `"rad"`, `"1/m"` (a growth per metre) or `""`
    /// (a weight, a fraction, a coverage or a probability).
    pub unit: &'static str,
    /// Its value in the sonar model's defaults.
    pub sonar_default: f64,
    /// Its value in the laser model's defaults (NaN for a parameter the
    /// laser model does not have).
    pub laser_default: f64,
    /// Whether `value` is one the parameter may take, alone (the checks
    /// that relate two parameters are [`RangeModel::validate`](super::RangeModel::validate)'s).
    pub valid: fn(f64) -> bool,
    /// The values it may take, in words, as an error states them.
    pub expected: &'static str,
    /// The bounds `[low, high]` a fit searches within unless told
    /// otherwise; `None` for a parameter no fit changes (the maximum
    /// range: a property of the sensor, which readings mean "no echo",
    /// not of the inverse model).
    pub fit_bounds: Option<[f64; 2]>,
    /// The value a stored model that lacks the parameter takes (a model
    /// stored before the parameter existed); `None`: it must be given.
    pub absent: Option<f64>,
}

impl Parameter {
    /// Whether a fit may change it.
    pub fn fittable(&self) -> bool {
        self.fit_bounds.is_some()
    }
}

/// The largest `max_range_m`: ten kilometres, far beyond any range sensor
/// a robot carries (and any map's extent at a useful resolution).
pub(crate) const MAX_RANGE_M: f64 = 1e4;
/// The smallest `sigma_min`: a standard deviation of coverage (which spans
/// 0 to 1) a millionth wide is already a spike between the bins; far below
/// it (near 1e-308) the density's scale would overflow.
pub(crate) const MIN_SIGMA: f64 = 1e-6;
/// The largest uniform weight `xi` anywhere up to the maximum range: beyond
/// it the kernel is uniform to far below `f32` precision anyway, and the sum
/// that normalises it could overflow.
pub(crate) const MAX_XI: f64 = 1e6;

/// The range model's parameters, the one list (see the [module
/// documentation](crate::sensor::parameters)): `$callback! { $($args)*
/// [ entries ] }`, an entry being the parameter's doc comments, its name
/// and `{ unit: .., sonar: .., laser: .., valid: .., expected: .., fit:
/// .., absent: .. }` (expressions: `valid` a closure `f64 -> bool`, `fit`
/// and `absent` options). A callback reads what it needs of an entry and
/// may ignore the rest (`$name:ident { $($spec:tt)* }`).
#[macro_export]
macro_rules! range_parameters {
    ($callback:ident ! { $($args:tt)* }) => {
        $callback! { $($args)* [
            /// Readings at or beyond this distance mean "no echo", metres.
            max_range_m {
                unit: "m", sonar: 5.0, laser: 30.0,
                valid: |v: f64| v > 0.0 && v <= $crate::sensor::parameters::MAX_RANGE_M,
                expected: "a positive distance of at most 10 km",
                fit: None, absent: None,
            }
            /// How far behind the end point cells are updated (as covered), metres.
            band_m {
                unit: "m", sonar: 0.20, laser: 0.10,
                valid: |v: f64| v >= 0.0,
                expected: "a non-negative distance",
                fit: Some([0.0, 1.0]), absent: None,
            }
            /// Standard deviation of the coverage mean at zero distance, outside the end band.
            sigma_min {
                unit: "", sonar: 0.12, laser: 0.08,
                valid: |v: f64| v >= $crate::sensor::parameters::MIN_SIGMA,
                expected: "a standard deviation of at least 1e-6 (coverage)",
                fit: Some([0.01, 0.6]), absent: None,
            }
            /// Growth of that standard deviation per metre of distance `s = min(d_l, d)`.
            sigma_per_m {
                unit: "1/m", sonar: 0.02, laser: 0.004,
                valid: |v: f64| v >= 0.0,
                expected: "a non-negative growth",
                fit: Some([0.0, 0.2]), absent: None,
            }
            /// The constant standard deviation inside the end band (the largest of all).
            sigma_end {
                unit: "", sonar: 0.30, laser: 0.25,
                valid: |v: f64| v > 0.0,
                expected: "a positive standard deviation",
                fit: Some([0.05, 1.0]), absent: None,
            }
            /// Weight of the uniform component at zero distance (must be positive).
            xi_min {
                unit: "", sonar: 0.08, laser: 0.02,
                valid: |v: f64| v > 0.0 && v <= $crate::sensor::parameters::MAX_XI,
                expected: "a positive weight of at most 1e6",
                fit: Some([0.001, 4.0]), absent: None,
            }
            /// Growth of the uniform weight per metre of distance `s = min(d_l, d)`.
            xi_per_m {
                unit: "1/m", sonar: 0.08, laser: 0.005,
                valid: |v: f64| v >= 0.0,
                expected: "a non-negative growth",
                fit: Some([0.0, 1.0]), absent: None,
            }
            /// How strongly an echo marks the cells at and behind its end point
            /// (the end band and the band behind it), in `[0, 1]`: their kernels
            /// are mixed with the uniform prior by this weight. 1 (the
            /// default): the paper's kernels. A sonar's echo comes from somewhere
            /// on the arc of its cone, so most cells of the arc are not what it
            /// hit; a weight below 1 says so, where 1 marks the whole arc covered.
            end_weight {
                unit: "", sonar: 1.0, laser: 1.0,
                valid: |v: f64| (0.0..=1.0).contains(&v),
                expected: "a weight in [0, 1]",
                fit: Some([0.0, 1.0]), absent: Some(1.0),
            }
        ] }
    };
}

/// The sonar's own parameters besides its range model's, declared as
/// [`range_parameters!`](crate::range_parameters) declares those (the
/// `laser` value unused).
#[macro_export]
macro_rules! sonar_parameters {
    ($callback:ident ! { $($args:tt)* }) => {
        $callback! { $($args)* [
            /// Full opening angle of the cone, radians, in `(0, pi)`.
            opening_angle_rad {
                unit: "rad", sonar: 0.2617993877991494, laser: f64::NAN,
                valid: |v: f64| v > 0.0 && v < ::std::f64::consts::PI,
                expected: "an angle in (0, pi) radians",
                fit: Some([::std::f64::consts::PI / 90.0, ::std::f64::consts::PI / 3.0]),
                absent: None,
            }
        ] }
    };
}

/// The number of a declaration's entries.
macro_rules! count_entries {
    ([ $( $(#[doc = $doc:literal])* $name:ident { $($spec:tt)* } )* ]) => {
        0 $(+ { let _ = stringify!($name); 1 })*
    };
}

/// The table of a declaration's entries, `[Parameter; N]`.
macro_rules! parameter_table {
    ([ $(
        $(#[doc = $doc:literal])*
        $name:ident {
            unit: $unit:expr, sonar: $sonar:expr, laser: $laser:expr,
            valid: $valid:expr, expected: $expected:expr,
            fit: $fit:expr, absent: $absent:expr $(,)?
        }
    )* ]) => {
        [ $(
            $crate::sensor::parameters::Parameter {
                name: stringify!($name),
                doc: concat!($($doc, "\n"),*),
                unit: $unit,
                sonar_default: $sonar,
                laser_default: $laser,
                valid: $valid,
                expected: $expected,
                fit_bounds: $fit,
                absent: $absent,
            },
        )* ]
    };
}

/// Every parameter of the range model, in the order of its fields.
pub const RANGE_PARAMETERS: [Parameter; crate::range_parameters!(count_entries! {})] =
    crate::range_parameters!(parameter_table! {});

/// The sonar model's own parameters (after the range model's).
pub const SONAR_PARAMETERS: [Parameter; 1] = crate::sonar_parameters!(parameter_table! {});

/// Every parameter of a sonar model: the range model's, then its own.
pub const SONAR_MODEL_PARAMETERS: [Parameter; RANGE_PARAMETERS.len() + SONAR_PARAMETERS.len()] =
    concat(&RANGE_PARAMETERS, &SONAR_PARAMETERS);

/// The parameters of a range model a fit may change, in the order of
/// [`RANGE_PARAMETERS`].
pub const FITTABLE_RANGE_PARAMETERS: [Parameter; fittable_count(&RANGE_PARAMETERS)] =
    fittable(&RANGE_PARAMETERS);

/// The parameters of a sonar model a fit may change, in the order of
/// [`SONAR_MODEL_PARAMETERS`].
pub const FITTABLE_SONAR_PARAMETERS: [Parameter; fittable_count(&SONAR_MODEL_PARAMETERS)] =
    fittable(&SONAR_MODEL_PARAMETERS);

/// How many parameters of `table` a fit may change.
const fn fittable_count(table: &[Parameter]) -> usize {
    let (mut count, mut i) = (0, 0);
    while i < table.len() {
        if table[i].fit_bounds.is_some() {
            count += 1;
        }
        i += 1;
    }
    count
}

/// The parameters of `table` a fit may change, in order.
const fn fittable<const N: usize, const K: usize>(table: &[Parameter; N]) -> [Parameter; K] {
    assert!(K > 0 && fittable_count(table) == K, "K counts them");
    let mut out = [table[N - 1]; K];
    let (mut k, mut i) = (0, 0);
    while i < N {
        if table[i].fit_bounds.is_some() {
            out[k] = table[i];
            k += 1;
        }
        i += 1;
    }
    out
}

/// `a` and then `b`.
const fn concat<const A: usize, const B: usize, const C: usize>(
    a: &[Parameter; A],
    b: &[Parameter; B],
) -> [Parameter; C] {
    assert!(A + B == C, "the arrays fill the result");
    let mut out = [a[0]; C];
    let mut i = 0;
    while i < B {
        out[A + i] = b[i];
        i += 1;
    }
    let mut i = 0;
    while i < A {
        out[i] = a[i];
        i += 1;
    }
    out
}

/// Errors, naming the first, unless each of `values` is finite and one
/// its parameter (the entry of `table` at the same place) may take.
///
/// # Errors
/// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter).
pub fn check_each(table: &[Parameter], values: &[f64]) -> crate::error::Result<()> {
    for (p, &v) in table.iter().zip(values) {
        crate::error::check_parameter(v.is_finite() && (p.valid)(v), p.name, v, p.expected)?;
    }
    Ok(())
}

/// A parameter the range model once had and no longer has.
#[derive(Clone, Copy, Debug)]
pub struct RemovedParameter {
    /// Its name, as stored models name it.
    pub name: &'static str,
    /// Its off value: the value at which it left the update as covmap's
    /// update is now. A stored model may still name it at this value.
    pub off: f64,
    /// What a stored model may give it, and why it was removed, as an
    /// error states it.
    pub expected: &'static str,
}

/// Why the three parameters that made the update read the map were
/// removed, as the error for a value other than 0 states it.
const READS_THE_MAP: &str = "0 or nothing: the parameter was removed (it made the update read the map, so the map depended on the order of its scans)";

/// Parameters the range model once had and no longer has. Three made the
/// update read the map as it integrated a reading (`posterior_floor`,
/// `end_attribution`, `free_yield`), so that a map depended on the order
/// of its scans; and no fit showed them better on buildings it was not
/// fitted to. Two shaped no-echo readings (`no_echo_reach`, how far one
/// clears, as a fraction of the maximum range; `no_echo_weight`, how
/// strongly): fitted alone to maps built as the exploration loop builds
/// them, each stayed at its off value (1); fitted to maps whose no-echo
/// readings clear their whole footprint, each raised the map error of a
/// drive it was not fitted to; fitted with `end_weight`, they doubled the
/// development runs' uncertain cells (docs/experiments.md). A stored model
/// may still name one at its off value, which is the update covmap has: it
/// is read and ignored.
pub const REMOVED_PARAMETERS: [RemovedParameter; 5] = [
    RemovedParameter {
        name: "posterior_floor",
        off: 0.0,
        expected: READS_THE_MAP,
    },
    RemovedParameter {
        name: "end_attribution",
        off: 0.0,
        expected: READS_THE_MAP,
    },
    RemovedParameter {
        name: "free_yield",
        off: 0.0,
        expected: READS_THE_MAP,
    },
    RemovedParameter {
        name: "no_echo_reach",
        off: 1.0,
        expected: "1 or nothing: the parameter was removed (no fit showed a no-echo reading that clears less than its whole footprint better on data it was not fitted to)",
    },
    RemovedParameter {
        name: "no_echo_weight",
        off: 1.0,
        expected: "1 or nothing: the parameter was removed (no fit showed a no-echo reading weaker than the free-space kernel better on data it was not fitted to)",
    },
];

/// Errors unless `value`, of the removed parameter `removed`, is its off
/// value: the only value whose model covmap still builds.
///
/// # Errors
/// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter)
/// naming the parameter.
pub fn check_removed(removed: &RemovedParameter, value: f64) -> crate::error::Result<()> {
    crate::error::check_parameter(value == removed.off, removed.name, value, removed.expected)
}

/// The parameter of `table` called `name`, and its index.
pub fn find(table: &'static [Parameter], name: &str) -> Option<(usize, &'static Parameter)> {
    table.iter().enumerate().find(|(_, p)| p.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tables_name_each_field_once_and_document_it() {
        for table in [&RANGE_PARAMETERS[..], &SONAR_MODEL_PARAMETERS[..]] {
            for (i, p) in table.iter().enumerate() {
                assert!(!p.doc.trim().is_empty(), "{}", p.name);
                assert_eq!(find(table, p.name).map(|(j, _)| j), Some(i), "{}", p.name);
                if let Some([low, high]) = p.fit_bounds {
                    assert!(
                        low < high && (p.valid)(low) && (p.valid)(high),
                        "{}",
                        p.name
                    );
                }
                if let Some(v) = p.absent {
                    assert!((p.valid)(v), "{}", p.name);
                }
            }
        }
        assert_eq!(SONAR_MODEL_PARAMETERS.len(), RANGE_PARAMETERS.len() + 1);
        assert_eq!(
            SONAR_MODEL_PARAMETERS.last().map(|p| p.name),
            Some("opening_angle_rad")
        );
        assert!(!RANGE_PARAMETERS[0].fittable());
        assert_eq!(SONAR_PARAMETERS[0].sonar_default, 15f64.to_radians());
        assert_eq!(RANGE_PARAMETERS[0].name, "max_range_m");
    }
}
