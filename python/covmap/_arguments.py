"""Calls with the wrong arguments raise :class:`covmap.InvalidTypeError`.

A call that does not fit its callable's signature (too many arguments, a
missing one, an unknown keyword, an argument given twice) fails before
anything runs: pyo3's argument binding (for the native module) or Python's
(for the package's own functions) raises a bare :class:`TypeError`. Here it
becomes an :class:`~covmap.InvalidTypeError`, a :class:`~covmap.CovmapError`
and still a :class:`TypeError`, with the same message (which names the
callable and the argument) and the original error as its ``__cause__``.

Which errors: an exception of type exactly :class:`TypeError` (covmap's own
are :class:`~covmap.CovmapError` subclasses already) raised by a call whose
arguments do not bind to the callable's signature
(``inspect.signature(...).bind``). Such an error cannot come from anything
but the binding, since with arguments that do not bind nothing ran. A
``TypeError`` raised by code that a call runs (a progress callback, an
executor's ``submit``, even a builtin callback called with the wrong
arguments) comes from a call whose own arguments fit, and passes unchanged.
Neither the message's wording (pyo3's, or CPython's for a method without
arguments, differ and change between versions) nor the traceback's depth (a
builtin callback adds no frame) is relied on.

Where: :func:`check_native` wraps the native module's functions and its
classes' methods, static and class methods, when this module is imported
(the package imports it first); the classes'
constructors are guarded in the native module itself
(``crates/covmap-py/src/construct.rs``), since CPython refuses a Python
``__new__`` that calls a native one. :func:`check_module`, called at the end
of each public module of the package, wraps its public functions and its
classes' constructors and methods. Names starting with ``_`` (private helpers,
and the protocol methods that Python calls itself, with the right arguments:
``__len__``, ``__getitem__``, ``__reduce__``...) are left as they are, and so
are exception classes (raised, not called).

A wrapper keeps the callable's name, qualified name, module and docstring, and
``inspect.signature`` follows it to the original (``__wrapped__``), so that
``help()``, pickling by reference and the stubs see what they saw before; it
costs one Python call more per call (see BENCHMARKS.md).
"""

from __future__ import annotations

import functools
import inspect
import sys
import types
from typing import Any, Callable

from covmap import _native
from covmap._errors import InvalidTypeError

__all__ = ["binding_error", "check_module", "check_native"]

#: Marks a wrapper, so that wrapping again (a reload of the package) leaves it.
_CHECKED = "__covmap_checked__"


def binding_error(error: BaseException, target: Any, args: tuple[Any, ...], kwargs: dict[str, Any] | None) -> InvalidTypeError | None:
    """The :class:`~covmap.InvalidTypeError` that ``error``, raised by the
    call ``target(*args, **kwargs)``, becomes; ``None`` if ``error`` is to
    pass unchanged (it is no bare ``TypeError``, or the arguments fit
    ``target``'s signature, or ``target`` has none to check them against).

    Also called by the native module for its constructors (``target`` the
    class)."""
    if type(error) is not TypeError:
        return None
    try:
        signature = inspect.signature(target)
    except (TypeError, ValueError):
        return None
    try:
        signature.bind(*args, **(kwargs or {}))
    except TypeError:
        converted = InvalidTypeError(str(error))
        converted.__cause__ = error
        return converted
    return None


def _checked(function: Callable[..., Any], *, module: str | None = None) -> Callable[..., Any]:
    """``function`` wrapped: a call whose arguments do not bind raises
    :class:`~covmap.InvalidTypeError` instead of a bare ``TypeError``."""

    @functools.wraps(function)
    def checked(*args: Any, **kwargs: Any) -> Any:
        __tracebackhide__ = True  # pytest shows the caller's frame, not this one
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            converted = binding_error(error, function, args, kwargs)
            if converted is None:
                raise
            raise converted from error

    if module is not None:
        checked.__module__ = module
    text_signature = getattr(function, "__text_signature__", None)
    if text_signature is not None:  # a native callable's, for tools that read it
        checked.__text_signature__ = text_signature  # type: ignore[attr-defined]
    setattr(checked, _CHECKED, True)
    return checked


def _is_checked(member: Any) -> bool:
    inner = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
    return getattr(inner, _CHECKED, False)


def _check_member(cls: type, name: str, member: Any, module: str) -> None:
    """Wrap ``cls.name`` (``member``, as the class's ``__dict__`` holds it) if
    it is a method, a static or a class method, native or Python."""
    if _is_checked(member):
        return
    if isinstance(member, (types.FunctionType, types.MethodDescriptorType)):
        setattr(cls, name, _checked(member, module=module))
    elif isinstance(member, staticmethod):
        setattr(cls, name, staticmethod(_checked(member.__func__, module=module)))
    elif isinstance(member, classmethod):
        setattr(cls, name, classmethod(_checked(member.__func__, module=module)))
    elif isinstance(member, types.ClassMethodDescriptorType):
        # Called with the class first, as the descriptor takes it.
        setattr(cls, name, classmethod(_checked(member, module=module)))


def _check_class(cls: type, *, constructor: bool) -> None:
    """Wrap the public methods of ``cls`` and, if ``constructor``, its
    ``__init__`` (a Python class's; a native class's constructor is guarded
    natively)."""
    for name, member in list(vars(cls).items()):
        if name.startswith("_") and not (constructor and name == "__init__"):
            continue
        _check_member(cls, name, member, cls.__module__)


def check_native(native: types.ModuleType) -> None:
    """Wrap the public functions of the native module and the public methods
    of its classes, in place (the module's attributes and the classes')."""
    for name, value in list(vars(native).items()):
        if name.startswith("_"):
            continue
        if isinstance(value, type):
            _check_class(value, constructor=False)
        elif isinstance(value, types.BuiltinFunctionType) and not _is_checked(value):
            setattr(native, name, _checked(value, module=native.__name__))


def check_module(name: str) -> None:
    """Wrap the public functions and classes that module ``name`` defines
    (those of its ``__all__``, or its names without a leading ``_``): the
    module's attributes are replaced, so that importing them from it gives
    the wrapped ones. Called at the end of the module."""
    module = sys.modules[name]
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n in vars(module) if not n.startswith("_")]
    for attribute in names:
        value = getattr(module, attribute)
        if getattr(value, "__module__", None) != name:
            continue  # imported from elsewhere, and wrapped there
        if isinstance(value, type):
            if not issubclass(value, BaseException):
                _check_class(value, constructor=True)
        elif isinstance(value, types.FunctionType) and not _is_checked(value):
            setattr(module, attribute, _checked(value))


check_native(_native)
