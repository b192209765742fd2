//! The state pyo3 and numpy make once, on first use, made by the import instead.
//!
//! pyo3 and numpy keep some state in cells filled on first use (interned attribute names such
//! as `__mro__` and `add_note`, the type objects of `collections.abc.Sequence` and `Mapping`,
//! `pathlib.Path`, numpy's C API and its array borrow registry). A cell is filled with the GIL
//! released while another thread waits; a process forked while a thread was filling one finds it
//! half-made in the child and waits for it for ever. [`ready`] fills every kind of such state the
//! binding's calls reach while the import holds the interpreter alone. [`KINDS`] names each kind
//! by the calls that reach it; a test of the package greps the binding's source for those calls
//! and refuses one of a kind that is not here, and any once-made cell of the binding's own (which
//! lives here, made by [`ready`], or not at all).

use pyo3::prelude::*;
use pyo3::type_object::PyTypeCheck;
use pyo3::types::{PyInt, PyMapping, PySequence, PyType};

use crate::buffers;

/// A kind of once-made state and the step of [`ready`] that makes it.
type Step = (&'static str, fn(Python<'_>) -> PyResult<()>);

/// Every kind of once-made state the binding's calls reach, each with the step that makes it;
/// the names are the kinds a test of the package finds in the binding's source.
pub const KINDS: [Step; 7] = [
    ("numpy arrays", numpy_arrays),
    ("buffer checks", buffers::ready),
    ("type names", type_names),
    ("sequences", sequences),
    ("mappings", mappings),
    ("paths", paths),
    ("argument notes", argument_notes),
];

/// Makes every kind of [`KINDS`], in order.
pub fn ready(py: Python<'_>) -> PyResult<()> {
    KINDS.iter().try_for_each(|(_, step)| step(py))
}

/// numpy's C API and the array borrow registry.
fn numpy_arrays(py: Python<'_>) -> PyResult<()> {
    let probe = numpy::PyArray1::<f32>::zeros(py, 1, false);
    numpy::PyArrayMethods::try_readwrite(&probe)?;
    Ok(())
}

/// The interned attribute names of a type's name, qualified name, module, bases and MRO.
fn type_names(py: Python<'_>) -> PyResult<()> {
    let class: Bound<'_, PyType> = py.get_type::<PyInt>();
    class.name()?;
    class.qualname()?;
    class.module()?;
    class.fully_qualified_name()?;
    class.bases();
    class.mro();
    Ok(())
}

/// `collections.abc.Sequence`, which a refused list argument (a `Vec`) is checked against.
fn sequences(py: Python<'_>) -> PyResult<()> {
    PySequence::type_check(&py.None().into_bound(py));
    let refused: PyResult<Vec<i64>> = PyInt::new(py, 0).extract();
    refused.map_or(Ok(()), |_| Err(probe_accepted("an int as a list")))
}

/// `collections.abc.Mapping`.
fn mappings(py: Python<'_>) -> PyResult<()> {
    PyMapping::type_check(&py.None().into_bound(py));
    Ok(())
}

/// `pathlib.Path`, which a returned path becomes.
fn paths(py: Python<'_>) -> PyResult<()> {
    std::path::Path::new(".").into_pyobject(py)?;
    Ok(())
}

/// The interned `add_note` with which pyo3 names the argument of a refused conversion.
fn argument_notes(py: Python<'_>) -> PyResult<()> {
    let error = pyo3::exceptions::PyTypeError::new_err("probe");
    pyo3::impl_::extract_argument::argument_extraction_error(py, "probe", error);
    Ok(())
}

fn probe_accepted(what: &str) -> PyErr {
    crate::errors::to_py(mazesim_core::Error::Internal(format!(
        "the import's probe of once-made state accepted {what}"
    )))
}
