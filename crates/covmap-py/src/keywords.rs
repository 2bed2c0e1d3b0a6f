//! Classes built from keyword-only settings: `SonarModel`, `LaserModel` and
//! `Planner` take every setting as an optional keyword argument (`None` or
//! left out: the default), show each back as a read-only attribute of the
//! same name, and list them all in their `repr`.
//!
//! [`keyword_class!`] writes all of that from one table of the settings, so
//! that a setting's name, its keyword, its attribute and its place in the
//! `repr` cannot drift apart.

/// A value as it stands in a `repr` of keyword arguments, `Class(name=value)`:
/// what Python would evaluate back to the value.
pub(crate) trait PyRepr {
    /// The value's text in the `repr`.
    fn py_repr(&self) -> String;
}

impl PyRepr for f64 {
    fn py_repr(&self) -> String {
        format!("{self:?}")
    }
}

impl PyRepr for bool {
    fn py_repr(&self) -> String {
        (if *self { "True" } else { "False" }).to_owned()
    }
}

impl PyRepr for Option<f64> {
    fn py_repr(&self) -> String {
        self.map_or_else(|| "None".to_owned(), |v| v.py_repr())
    }
}

impl PyRepr for &str {
    fn py_repr(&self) -> String {
        format!("'{self}'")
    }
}

/// The `#[pymethods]` block of a class whose constructor takes keyword-only
/// settings:
///
/// ```ignore
/// keyword_class! {
///     impl PyPlanner as "Planner" {
///         keywords PlannerKeywords => PyPlanner::from_keywords;
///         settings(&self) {
///             /// Weight of information against travel, in ``[0, 1]``.
///             alpha(f64) -> f64 { self.config().alpha }
///         }
///         methods {
///             // Further #[pymethods] items.
///         }
///     }
/// }
/// ```
///
/// A setting reads `name(keyword type) -> attribute type { the attribute }`,
/// under its attribute's docs. The macro writes `struct PlannerKeywords`, an
/// `Option` of the keyword type per setting, and the methods: the constructor
/// `Planner(*, alpha=None, ...)`, which hands the keywords to
/// `PyPlanner::from_keywords(py, keywords)` (written by hand: the one place
/// where keywords become the core's settings); a getter per setting;
/// `__repr__`, `Planner(alpha=0.5, ...)` in table order ([`PyRepr`] writes
/// the values); and the further `methods` as they stand.
macro_rules! keyword_class {
    (
        impl $class:ident as $name:literal {
            keywords $keywords:ident => $build:path;
            settings(&$this:ident) {
                $(
                    $(#[doc = $doc:literal])*
                    $setting:ident($keyword:ty) -> $attribute:ty { $read:expr }
                )*
            }
            methods { $($methods:tt)* }
        }
    ) => {
        /// The keyword arguments of the constructor, `None` where left out.
        pub(crate) struct $keywords {
            $(pub(crate) $setting: Option<$keyword>,)*
        }

        #[::pyo3::pymethods]
        impl $class {
            #[new]
            #[pyo3(signature = (*, $($setting = None),*))]
            #[allow(clippy::too_many_arguments, reason = "one keyword argument per setting")]
            fn new(
                py: ::pyo3::Python<'_>,
                $($setting: Option<<$keyword as $crate::numbers::Setting>::Arg>),*
            ) -> ::pyo3::PyResult<Self> {
                use $crate::numbers::Setting;
                $build(py, $keywords { $($setting: $setting.map(<$keyword>::from_arg)),* })
            }

            $(
                $(#[doc = $doc])*
                #[getter]
                fn $setting(&$this) -> $attribute {
                    $read
                }
            )*

            fn __repr__(&$this) -> String {
                use $crate::keywords::PyRepr;
                let settings = [$(
                    format!("{}={}", stringify!($setting), $this.$setting().py_repr())
                ),*];
                format!("{}({})", $name, settings.join(", "))
            }

            $($methods)*
        }
    };
}

pub(crate) use keyword_class;
