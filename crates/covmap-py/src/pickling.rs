//! Pickling through the core's serde form: a value as JSON bytes (a float32
//! held as the float64 it equals, so that every value round-trips exactly)
//! and back, with covmap's errors.

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::errors::Exception;

/// `value` as the bytes of its JSON form; `what` names it in an error.
pub(crate) fn state<'py, T: Serialize>(
    py: Python<'py>,
    value: &T,
    what: &str,
) -> PyResult<Bound<'py, PyBytes>> {
    serde_json::to_value(value)
        .and_then(|v| serde_json::to_vec(&v))
        .map(|bytes| PyBytes::new(py, &bytes))
        .map_err(|e| Exception::Base.err(py, format!("cannot save the {what}: {e}")))
}

/// What `state` saved; `InvalidValueError` naming `what` for bytes that are
/// no such state. The caller checks what the value must satisfy.
pub(crate) fn restored<T: DeserializeOwned>(
    py: Python<'_>,
    state: &[u8],
    what: &str,
) -> PyResult<T> {
    serde_json::from_slice(state)
        .map_err(|e| Exception::InvalidValue.err(py, format!("not a saved {what}: {e}")))
}

/// `__reduce__` of a class restored by its static method `_from_state`
/// from `value`'s state.
pub(crate) fn reduce<'py, C: pyo3::PyTypeInfo, T: Serialize>(
    py: Python<'py>,
    value: &T,
    what: &str,
) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
    let restore = py.get_type::<C>().getattr("_from_state")?;
    Ok((restore, (state(py, value, what)?,)))
}
