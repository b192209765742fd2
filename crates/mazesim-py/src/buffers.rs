//! Borrowing numpy arrays as Rust slices, with shape and dtype checked and reported in the
//! package's own errors.

use mazesim_core::Error;
use numpy::{
    Element, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyReadwriteArrayDyn,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::errors::to_py;

fn describe(obj: &Bound<'_, PyAny>) -> String {
    // Both read the object's own attributes, which may be anything: the dtype's text is cut
    // short, and a shape is shown only when it is a short sequence of sizes.
    let dtype = obj
        .getattr("dtype")
        .map(|d| d.to_string().chars().take(80).collect::<String>())
        .unwrap_or_else(|_| "no dtype".into());
    let shape = crate::args::shape_of(obj)
        .map(|s| shape_text(&s))
        .unwrap_or_else(|| "no usable shape".into());
    format!(
        "{} of dtype {dtype} and shape {shape}",
        crate::args::type_name(obj)
    )
}

fn wrong<T>(name: &str, expected: &str, obj: &Bound<'_, PyAny>) -> PyResult<T> {
    Err(to_py(Error::InvalidArgument(format!(
        "expected {name} to be an aligned, C-contiguous numpy array of {expected}, found a {}",
        describe(obj)
    ))))
}

fn shape_text(shape: &[usize]) -> String {
    let parts: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    if parts.len() == 1 {
        format!("({},)", parts[0])
    } else {
        format!("({})", parts.join(", "))
    }
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
        wrong(
            name,
            &format!("{expected}, writable and not borrowed elsewhere"),
            obj,
        )
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
    array
        .try_readonly()
        .or_else(|_| wrong(name, &expected, obj))
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
        Ok(array) if usable(array, shape) => Ok((array, expected)),
        _ => wrong(name, &expected, obj),
    }
}

/// Whether `array` has `shape` and is C-contiguous and aligned, so that it can be a slice.
fn usable<T: Element>(array: &Bound<'_, PyArrayDyn<T>>, shape: &[usize]) -> bool {
    array.shape() == shape && array.is_c_contiguous() && array.is_aligned()
}
