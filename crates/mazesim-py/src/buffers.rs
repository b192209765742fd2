//! Borrowing numpy arrays as Rust slices, with shape and dtype checked and reported in the
//! package's own errors.

use mazesim_core::Error;
use numpy::{
    Element, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyReadwriteArrayDyn,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::errors::{to_py, wrong_type};

fn describe(obj: &Bound<'_, PyAny>, expected: &str) -> String {
    // Both read the object's own attributes, which may be anything: the dtype's text is cut
    // short, and a shape is shown only when it is a short sequence of sizes.
    let dtype = obj
        .getattr("dtype")
        .map(|d| d.to_string().chars().take(80).collect::<String>());
    let shape = crate::args::shape_of(obj).map(|s| shape_text(&s));
    let Ok(dtype) = dtype else {
        if !obj.hasattr("shape").unwrap_or(false) {
            // No array at all (a list): what it is says enough.
            return crate::args::type_name(obj);
        }
        let shape = shape.unwrap_or_else(|| "no usable shape".into());
        return format!(
            "{} of no dtype and shape {shape}",
            crate::args::type_name(obj)
        );
    };
    let shape = shape.unwrap_or_else(|| "no usable shape".into());
    format!(
        "{} of dtype {dtype} and shape {shape}{}",
        crate::args::type_name(obj),
        layout(obj, expected.contains("writable"))
    )
}

/// What keeps an array from being borrowed as a slice, as a clause to the description of what
/// was found (", not C-contiguous (...)"), so that a refusal of an array of the right dtype and
/// shape never reads "expected X, found X"; its being read-only counts for an output only.
fn layout(obj: &Bound<'_, PyAny>, output: bool) -> String {
    let Ok(flags) = obj.getattr("flags") else {
        return String::new();
    };
    let flag = |name: &str| {
        flags
            .getattr(name)
            .and_then(|value| value.is_truthy())
            .unwrap_or(true)
    };
    let mut notes = Vec::new();
    if !flag("c_contiguous") {
        notes.push("not C-contiguous (a slice or a transpose: pass np.ascontiguousarray(...))");
    }
    if !flag("aligned") {
        notes.push("not aligned (a view at an odd byte offset: pass a copy)");
    }
    if output && !flag("writeable") {
        notes.push("read-only");
    }
    notes.iter().map(|note| format!(", {note}")).collect()
}

fn refusal(name: &str, expected: &str, obj: &Bound<'_, PyAny>) -> String {
    format!(
        "expected {name} to be an aligned, C-contiguous numpy array of {expected}, found {}",
        describe(obj, expected)
    )
}

/// An array of the right dtype, shape and layout that cannot be borrowed: another argument of
/// the call holds its memory (an output overlapping another, or an input that is a view of an
/// output), which the description of what was found says, so that it never reads "expected X,
/// found X".
fn shared<T>(name: &str, expected: &str, obj: &Bound<'_, PyAny>, clash: &str) -> PyResult<T> {
    let mut found = describe(obj, expected);
    if !found.contains("read-only") {
        found.push_str(&format!(
            ", sharing memory with {clash} of this call (give each its own array)"
        ));
    }
    Err(to_py(Error::InvalidArgument(format!(
        "expected {name} to be an aligned, C-contiguous numpy array of {expected}, found {found}"
    ))))
}

/// A numpy array of the right dtype whose shape, layout or borrow does not fit.
fn wrong<T>(name: &str, expected: &str, obj: &Bound<'_, PyAny>) -> PyResult<T> {
    Err(to_py(Error::InvalidArgument(refusal(name, expected, obj))))
}

/// Not a numpy array, or one of another dtype: a `WrongTypeError`.
fn wrong_kind<T>(name: &str, expected: &str, obj: &Bound<'_, PyAny>) -> PyResult<T> {
    Err(wrong_type(refusal(name, expected, obj)))
}

fn shape_text(shape: &[usize]) -> String {
    let parts: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    if parts.len() == 1 {
        format!("({},)", parts[0])
    } else {
        format!("({})", parts.join(", "))
    }
}

/// The refusal of an array argument whose shape does not fit, `message` saying what was expected
/// and the shape found: a `WrongTypeError` when `obj` is not an array at all (it has no `.shape`,
/// which `message` shows as `[]`), else an `InvalidArgumentError`.
pub fn shape_refusal(obj: &Bound<'_, PyAny>, message: String) -> PyErr {
    if obj.hasattr("shape").unwrap_or(false) {
        return to_py(Error::InvalidArgument(message));
    }
    wrong_type(format!(
        "{message} ({}, not an array)",
        crate::args::type_name(obj)
    ))
}

/// A writable array of dtype `T` and exactly `shape`.
pub fn writable<'py, T: Element>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    dtype: &str,
    shape: &[usize],
) -> PyResult<PyReadwriteArrayDyn<'py, T>> {
    let (array, expected) = usable_array::<T>(obj, name, dtype, shape)?;
    array.try_readwrite().or_else(|_| {
        let unshared = format!("{expected}, writable and not borrowed elsewhere");
        shared(name, &unshared, obj, "another argument")
    })
}

/// A read-only array of dtype `T` and exactly `shape`.
pub fn readable<'py, T: Element>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    dtype: &str,
    shape: &[usize],
) -> PyResult<PyReadonlyArrayDyn<'py, T>> {
    let (array, expected) = usable_array::<T>(obj, name, dtype, shape)?;
    array.try_readonly().or_else(|_| {
        let unshared = format!("{expected}, not written by another argument of this call");
        shared(name, &unshared, obj, "an output")
    })
}

/// A copy of an array of dtype `T` and exactly `shape`: inputs are copied before a call borrows
/// its outputs, so an input may be one of the outputs (`reset(mask=colliding)`).
pub fn copied<T: Element + Copy>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    dtype: &str,
    shape: &[usize],
) -> PyResult<Vec<T>> {
    let array = readable::<T>(obj, name, dtype, shape)?;
    match array.as_slice() {
        Ok(values) => Ok(values.to_vec()),
        Err(_) => wrong(name, &expected_array(dtype, shape), obj),
    }
}

/// What an array argument must be: "dtype float32 and shape (4, 2)".
fn expected_array(dtype: &str, shape: &[usize]) -> String {
    format!("dtype {dtype} and shape {}", shape_text(shape))
}

/// `obj` as an array of dtype `T` that `usable` finds fit for `shape`, and what was expected of
/// it, for the messages of the checks that follow.
fn usable_array<'a, 'py, T: Element>(
    obj: &'a Bound<'py, PyAny>,
    name: &str,
    dtype: &str,
    shape: &[usize],
) -> PyResult<(&'a Bound<'py, PyArrayDyn<T>>, String)> {
    let expected = expected_array(dtype, shape);
    match obj.cast::<PyArrayDyn<T>>() {
        Ok(_) if is_masked(obj) => Err(wrong_type(format!(
            "expected {name} to be a plain numpy array of {expected}, found {}, whose mask \
             would be dropped: pass array.filled(value) to say what its masked entries are",
            describe(obj, &expected)
        ))),
        Ok(array) if usable(array, shape) => Ok((array, expected)),
        Ok(_) => wrong(name, &expected, obj),
        Err(_) => wrong_kind(name, &expected, obj),
    }
}

/// Walks the buffer checks once, accepting an array and refusing a misfit, so that the state
/// pyo3 makes on first use along them (interned attribute names such as `__mro__` and
/// `__name__`) is made by the import, which holds the interpreter alone. pyo3 makes such state
/// with the GIL released; a process forked while another thread was making it would find it
/// half-made in the child and wait for it for ever.
pub fn ready(py: Python<'_>) -> PyResult<()> {
    let fit = numpy::PyArray1::<f32>::zeros(py, 1, false).into_any();
    copied::<f32>(&fit, "probe", "float32", &[1])?;
    writable::<f32>(&fit, "probe", "float32", &[1])?;
    let misfit = numpy::PyArray1::<f32>::zeros(py, 2, false).into_any();
    let refused = readable::<f32>(&misfit, "probe", "float32", &[1]).is_err()
        && readable::<f32>(&py.None().into_bound(py), "probe", "float32", &[1]).is_err();
    if refused {
        Ok(())
    } else {
        Err(to_py(Error::Internal(
            "the buffer checks accepted a misfit while the import readied them".into(),
        )))
    }
}

/// Whether an array is numpy's masked array (`np.ma.MaskedArray` or a subclass): a slice
/// borrowed from it would drop its mask, reading its masked entries as the numbers under them.
fn is_masked(array: &Bound<'_, PyAny>) -> bool {
    array.get_type().mro().iter().any(|class| {
        class
            .cast::<pyo3::types::PyType>()
            .ok()
            .and_then(|c| c.name().ok())
            .is_some_and(|n| n == "MaskedArray")
    })
}

/// Whether `array` has `shape` and is C-contiguous and aligned, so that it can be a slice.
fn usable<T: Element>(array: &Bound<'_, PyArrayDyn<T>>, shape: &[usize]) -> bool {
    array.shape() == shape && array.is_c_contiguous() && array.is_aligned()
}
