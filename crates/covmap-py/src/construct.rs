//! Constructors called with the wrong arguments raise `InvalidTypeError`.
//!
//! pyo3 binds a constructor's arguments in the class's `tp_new` slot, before
//! any converter runs, and a call that does not fit (too many arguments, a
//! missing one, an unknown keyword, one given twice) raises a bare
//! `TypeError`. The package turns those of functions and methods into
//! `InvalidTypeError` by wrapping them in Python (`covmap/_arguments.py`, whose
//! `binding_error` decides which errors are the binding's), but it cannot wrap
//! a native constructor: a Python `__new__` set on the class would have to call
//! the native one through `Class.__new__`, which CPython refuses once the slot
//! is no longer native ("Class.__new__(Class) is not safe"). So the slot is
//! wrapped here, once, when the module is made: [`guard`] puts [`checked_new`]
//! in each class's `tp_new`, which calls the class's own and hands a
//! `TypeError` it raised to `binding_error`. A class without a constructor
//! (results such as `Plan`) gets one that raises `InvalidTypeError` with
//! CPython's words ("cannot create ... instances") instead of the bare
//! `TypeError` CPython would raise.
//!
//! Nothing else changes: the classes' `__text_signature__`, `__new__` (which
//! calls the slot), pickling and `isinstance` stay as they were. A Python
//! `__new__` assigned to the class replaces the slot as it always does.

use std::ptr;
use std::sync::OnceLock;

use pyo3::ffi;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};

use crate::errors::Exception;

/// A class whose `tp_new` is [`checked_new`], and what it was before.
struct Guarded {
    /// The class (its address: it lives as long as the module holds it).
    class: usize,
    /// Its own `tp_new`; `None` for a class that cannot be created.
    new: Option<ffi::newfunc>,
    /// Its qualified name, for the error of a class that cannot be created.
    name: String,
}

/// The guarded classes, set once: a module made again (pyo3 reuses the
/// first) guards nothing twice.
static GUARDED: OnceLock<Vec<Guarded>> = OnceLock::new();

/// Put [`checked_new`] in the `tp_new` slot of every class of the module `m`.
pub(crate) fn guard(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let mut classes = Vec::new();
    for (_, value) in m.dict().iter() {
        if let Ok(class) = value.cast_into::<PyType>() {
            classes.push(class);
        }
    }
    let mut guarded = Vec::with_capacity(classes.len());
    for class in &classes {
        let raw = class.as_type_ptr();
        // SAFETY: `raw` is a live type object (the module holds it) and the
        // GIL is held; reading a slot is what CPython does on every call.
        let new = unsafe { (*raw).tp_new };
        guarded.push(Guarded {
            class: raw as usize,
            new,
            name: class.fully_qualified_name()?.to_string(),
        });
    }
    if GUARDED.set(guarded).is_err() {
        // Guarded already (the slots read above were `checked_new`).
        return Ok(());
    }
    for class in &classes {
        let raw = class.as_type_ptr();
        // SAFETY: as above; the module is being made, so no other thread can
        // see the class yet. Setting the slot and telling CPython the type
        // changed is what `type.__setattr__` does for an assigned `__new__`.
        unsafe {
            (*raw).tp_new = Some(checked_new);
            ffi::PyType_Modified(raw);
        }
    }
    Ok(())
}

/// The `tp_new` of every class: the class's own, and a `TypeError` of its
/// argument binding raised as `InvalidTypeError`.
unsafe extern "C" fn checked_new(
    class: *mut ffi::PyTypeObject,
    args: *mut ffi::PyObject,
    kwargs: *mut ffi::PyObject,
) -> *mut ffi::PyObject {
    // SAFETY: CPython calls a type's `tp_new` with the GIL held.
    let py = unsafe { Python::assume_attached() };
    let Some(guarded) = GUARDED
        .get()
        .and_then(|all| all.iter().find(|g| g.class == class as usize))
    else {
        // Only the guarded classes have this slot, and none can be subclassed.
        pyo3::exceptions::PySystemError::new_err("covmap: constructor of an unknown class")
            .restore(py);
        return ptr::null_mut();
    };
    let Some(new) = guarded.new else {
        Exception::InvalidType
            .err(py, format!("cannot create '{}' instances", guarded.name))
            .restore(py);
        return ptr::null_mut();
    };
    // SAFETY: the class's own slot, called as CPython would have called it.
    let object = unsafe { new(class, args, kwargs) };
    // Only an exact TypeError is looked at: covmap's own errors are
    // subclasses, and taking a panic's exception would resume the panic.
    // SAFETY: the GIL is held; both are type objects, compared by address.
    let bare_type_error =
        unsafe { object.is_null() && ffi::PyErr_Occurred() == ffi::PyExc_TypeError };
    if bare_type_error && let Some(error) = PyErr::take(py) {
        // SAFETY: what CPython passed: the class, a tuple and a dict or NULL,
        // borrowed for this call.
        let (class, args, kwargs) = unsafe {
            (
                borrowed(py, class.cast::<ffi::PyObject>()),
                borrowed(py, args),
                borrowed(py, kwargs),
            )
        };
        converted(py, error, class, args, kwargs).restore(py);
    }
    object
}

/// The object behind a borrowed pointer, or `None` for NULL.
///
/// # Safety
/// `object` is NULL or a live object, borrowed for the GIL-held call.
unsafe fn borrowed<'py>(py: Python<'py>, object: *mut ffi::PyObject) -> Option<Bound<'py, PyAny>> {
    unsafe { Bound::from_borrowed_ptr_or_opt(py, object) }
}

/// `error` as `covmap._arguments.binding_error` makes it (`InvalidTypeError`
/// if the arguments do not fit the class's signature), else `error` itself,
/// as it is also if that call fails.
fn converted(
    py: Python<'_>,
    error: PyErr,
    class: Option<Bound<'_, PyAny>>,
    args: Option<Bound<'_, PyAny>>,
    kwargs: Option<Bound<'_, PyAny>>,
) -> PyErr {
    static BINDING_ERROR: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    let decide = || -> PyResult<Option<PyErr>> {
        let binding_error = BINDING_ERROR.get_or_try_init(py, || {
            py.import("covmap._arguments")?
                .getattr("binding_error")
                .map(Bound::unbind)
        })?;
        let args = match args {
            Some(args) => args.cast_into::<PyTuple>()?,
            None => PyTuple::empty(py),
        };
        let kwargs = match kwargs {
            Some(kwargs) => Some(kwargs.cast_into::<PyDict>()?),
            None => None,
        };
        let result = binding_error
            .bind(py)
            .call1((error.value(py), class, args, kwargs))?;
        Ok((!result.is_none()).then(|| PyErr::from_value(result)))
    };
    match decide() {
        Ok(Some(converted)) => converted,
        _ => error,
    }
}
