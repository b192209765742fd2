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
    let dtype = obj
        .getattr("dtype")
        .map(|d| d.to_string())
        .unwrap_or_else(|_| "no dtype".into());
    let shape = obj
        .getattr("shape")
        .map(|s| s.to_string())
        .unwrap_or_else(|_| "no shape".into());
    format!(
        "{} of dtype {dtype} and shape {shape}",
        obj.get_type()
            .name()
            .map(|n| n.to_string())
            .unwrap_or_default()
    )
}

fn wrong<T>(name: &str, expected: &str, obj: &Bound<'_, PyAny>) -> PyResult<T> {
    Err(to_py(Error::InvalidArgument(format!(
        "expected {name} to be a C-contiguous numpy array of {expected}, found a {}",
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
    let expected = format!("dtype {dtype} and shape {}", shape_text(shape));
    let Ok(array) = obj.cast::<PyArrayDyn<T>>() else {
        return wrong(name, &expected, obj);
    };
    if array.shape() != shape || !array.is_c_contiguous() {
        return wrong(name, &expected, obj);
    }
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
    let expected = format!("dtype {dtype} and shape {}", shape_text(shape));
    let Ok(array) = obj.cast::<PyArrayDyn<T>>() else {
        return wrong(name, &expected, obj);
    };
    if array.shape() != shape || !array.is_c_contiguous() {
        return wrong(name, &expected, obj);
    }
    array
        .try_readonly()
        .or_else(|_| wrong(name, &expected, obj))
}
