//! Python numbers as arguments: [`Float`], [`Int`] and [`Seed`] take any
//! Python number of their kind and refuse every other value with covmap's
//! error, which quotes the value (at most [`QUOTED_CHARS`] characters of
//! it, [`quoted`]) and states the range the argument really takes.
//!
//! Only numbers are converted here, because only their errors need more
//! than Python's: an integer beyond what a Rust integer holds would
//! otherwise raise a bare `OverflowError` stating the Rust type's range, not
//! the argument's, and a bool would pass for the integer 1. Arguments of
//! other types (a class instance, a string, a path, a bool flag) are
//! converted by pyo3, whose `TypeError` for a value of the wrong type, like
//! that of a call whose arguments do not bind to the signature, is Python's
//! own, as numpy's and polars' are.
//!
//! pyo3 notes the argument's name on an error of its conversion ("while
//! processing 'n'"), which `CovmapError.add_note` puts into the message:
//! `argument 'n': 18446744073709551616 is out of range: expected an integer
//! from 1 to 2**32 - 1`.

use pyo3::exceptions::{PyOverflowError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyInt};

use covmap::QUOTED_CHARS;

use crate::errors::Exception;

/// `obj` as an error message quotes it: its `repr`, cut to
/// [`QUOTED_CHARS`] characters (a cut one ends in `...` and says how long it
/// was); an integer too large for Python to print by its bit length, any
/// other value whose `repr` fails by its type. (A Rust string is quoted by
/// [`covmap::quoted`], to the same length.)
pub(crate) fn quoted(obj: &Bound<'_, PyAny>) -> String {
    match obj.repr() {
        Ok(text) => shortened(&text.to_string_lossy()),
        Err(_) => match obj.call_method0(pyo3::intern!(obj.py(), "bit_length")) {
            Ok(bits) if obj.is_instance_of::<PyInt>() => format!("an integer of {bits} bits"),
            _ => format!("a {} that cannot be shown", type_name(obj)),
        },
    }
}

/// `text` cut to [`QUOTED_CHARS`] characters for a message: a longer one
/// ends in `...` and says how many characters it had.
pub(crate) fn shortened(text: &str) -> String {
    match text.char_indices().nth(QUOTED_CHARS) {
        Some((end, _)) => format!("{}... ({} characters)", &text[..end], text.chars().count()),
        None => text.to_owned(),
    }
}

/// The name of `obj`'s type, as Python spells it (`int`, `numpy.float32`).
fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map_or_else(|_| "value".to_owned(), |n| n.to_string())
}

/// A float argument: a Python `float`, `int` or anything with `__float__`
/// (a numpy float), never a bool. A value of another type raises
/// `InvalidTypeError`; a number beyond float64 (`10**400`)
/// `IntegerOverflowError`. Whether the number is a valid value of its
/// argument (finite, positive...) is for the function to check.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Float(pub(crate) f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Float {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let py = obj.py();
        if let Ok(float) = obj.cast::<PyFloat>() {
            return Ok(Self(float.value()));
        }
        if obj.is_instance_of::<PyBool>() {
            return Err(Exception::InvalidType.err(
                py,
                format!("expected a number, got the bool {}", quoted(&obj)),
            ));
        }
        obj.extract::<f64>().map(Self).map_err(|e| {
            if e.is_instance_of::<PyOverflowError>(py) {
                Exception::IntegerOverflow.err(
                    py,
                    format!(
                        "{} is out of range: expected a float64, at most about 1.8e308 in size",
                        quoted(&obj)
                    ),
                )
            } else if e.is_instance_of::<PyTypeError>(py) {
                Exception::InvalidType
                    .err(py, format!("expected a number, got {}", type_name(&obj)))
            } else {
                e
            }
        })
    }
}

/// An integer argument from `MIN` to `MAX`, as `T`: a Python `int`, a numpy
/// integer or anything with `__index__`, never a bool or a float. A value
/// of another type raises `InvalidTypeError`; one outside the range
/// `InvalidParameterError`, or `IntegerOverflowError` (also an
/// `OverflowError`) if it lies beyond a signed 64-bit integer too; both
/// state the range.
/// `T` holds the whole range (its conversion failing would raise the same
/// error).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Int<T, const MIN: i128, const MAX: i128>(pub(crate) T);

impl<'a, 'py, T: TryFrom<i128>, const MIN: i128, const MAX: i128> FromPyObject<'a, 'py>
    for Int<T, MIN, MAX>
{
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        integer(&obj, MIN, MAX)?
            .and_then(|value| T::try_from(value).ok())
            .map(Self)
            .ok_or_else(|| outside(&obj, MIN, MAX))
    }
}

/// The Python integer `obj` if it lies from `min` to `max`, `None` if it
/// lies outside. A value that is no integer (a bool, a float, a string)
/// raises `InvalidTypeError` stating the range.
pub(crate) fn integer(obj: &Bound<'_, PyAny>, min: i128, max: i128) -> PyResult<Option<i128>> {
    let py = obj.py();
    let not_an_integer = || {
        Exception::InvalidType.err(
            py,
            format!(
                "expected an integer from {} to {}, got {} {}",
                spelled(min),
                spelled(max),
                type_name(obj),
                quoted(obj)
            ),
        )
    };
    if obj.is_instance_of::<PyBool>() {
        return Err(not_an_integer());
    }
    match obj.extract::<i128>() {
        Ok(value) => Ok((min..=max).contains(&value).then_some(value)),
        Err(e) if e.is_instance_of::<PyOverflowError>(py) => Ok(None),
        Err(e) if e.is_instance_of::<PyTypeError>(py) => Err(not_an_integer()),
        Err(e) => Err(e),
    }
}

/// The error of the integer `obj`, outside `min..=max`:
/// `InvalidParameterError`, or `IntegerOverflowError` if it lies beyond a
/// signed 64-bit integer too (and beyond `max`, for a range that reaches
/// past one: a seed's).
fn outside(obj: &Bound<'_, PyAny>, min: i128, max: i128) -> PyErr {
    let beyond_64_bits = match obj.extract::<i128>() {
        Ok(value) => value < i128::from(i64::MIN) || value > max.max(i128::from(i64::MAX)),
        Err(_) => true,
    };
    let class = match beyond_64_bits {
        true => Exception::IntegerOverflow,
        false => Exception::InvalidParameter,
    };
    class.err(
        obj.py(),
        format!(
            "{} is out of range: expected an integer from {} to {}",
            quoted(obj),
            spelled(min),
            spelled(max)
        ),
    )
}

/// An integer as a message states a range's end: a power of two or one
/// less (from 2**16 on) as Python writes it, `2**32 - 1`, others in
/// decimal.
pub(crate) fn spelled(n: i128) -> String {
    let power = |m: i128| (m > 0 && m.count_ones() == 1).then(|| m.trailing_zeros());
    match (power(n.unsigned_abs() as i128), power(n.saturating_add(1))) {
        (Some(k), _) if k >= 16 && n < 0 => format!("-2**{k}"),
        (Some(k), _) if k >= 16 => format!("2**{k}"),
        (_, Some(k)) if k >= 16 => format!("2**{k} - 1"),
        _ => n.to_string(),
    }
}

/// A seed for the random generators: any Python integer from 0 to
/// 2**64 - 1 (as [`Int`] reads it).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Seed(pub(crate) u64);

impl<'a, 'py> FromPyObject<'a, 'py> for Seed {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        Int::<u64, 0, { u64::MAX as i128 }>::extract(obj).map(|seed| Self(seed.0))
    }
}

/// How a setting of type `Self` (a keyword of a class written by
/// `keyword_class!`) is read from Python: numbers by this module's types,
/// the rest by pyo3.
pub(crate) trait Setting: Sized {
    /// What Python's value is read as.
    type Arg;
    /// The setting from what was read.
    fn from_arg(arg: Self::Arg) -> Self;
}

impl Setting for f64 {
    type Arg = Float;
    fn from_arg(arg: Float) -> f64 {
        arg.0
    }
}

impl Setting for bool {
    type Arg = bool;
    fn from_arg(arg: bool) -> bool {
        arg
    }
}

impl Setting for String {
    type Arg = String;
    fn from_arg(arg: String) -> String {
        arg
    }
}

/// A histogram's bin count: from `MIN_BINS` to `MAX_BINS` (2 to 256).
pub(crate) type Bins =
    Int<usize, { covmap::histogram::MIN_BINS as i128 }, { covmap::histogram::MAX_BINS as i128 }>;
