//! Maps the core's error to the exception tree of `mazesim.errors`.

use mazesim_core::Error;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;

/// Builds the Python exception for a core error.
pub fn to_py(err: Error) -> PyErr {
    if let Error::Interrupted = err {
        // Ctrl-C was taken from Python without running its handler (see `guard::ctrl_c_pressed`):
        // handed back, so that the SIGINT handler (by default: raise KeyboardInterrupt) runs now.
        return Python::attach(|py| {
            // SAFETY: called with the GIL held, as the C API asks.
            unsafe { pyo3::ffi::PyErr_SetInterrupt() };
            match py.check_signals() {
                Err(raised) => raised,
                Ok(()) => PyKeyboardInterrupt::new_err("interrupted"),
            }
        });
    }
    Python::attach(|py| match build(py, &err) {
        Ok(e) => e,
        Err(import_failed) => PyRuntimeError::new_err(format!(
            "{err} (and mazesim.errors could not be imported: {import_failed})"
        )),
    })
}

fn build(py: Python<'_>, err: &Error) -> PyResult<PyErr> {
    let errors = py.import("mazesim.errors")?;
    let class_name = match err {
        Error::Format { .. } => "WorldFormatError",
        Error::UnknownName { .. } => "UnknownNameError",
        Error::InvalidAction(_) => "InvalidActionError",
        Error::InvalidArgument(_) => "InvalidArgumentError",
        Error::Io { .. } => "MazesimIOError",
        Error::Snapshot(_) => "SnapshotError",
        Error::Busy(_) => "SimulatorBusyError",
        Error::Internal(_) | Error::Interrupted => "InternalError",
    };
    let class = errors.getattr(class_name)?;
    let message = mazesim_core::readable_numbers(&err.to_string());
    let instance = match err {
        // The name asked for, so that the message can end with the closest available name.
        Error::UnknownName {
            name, available, ..
        } => {
            let keywords = pyo3::types::PyDict::new(py);
            keywords.set_item("name", name)?;
            keywords.set_item("available", available.clone())?;
            class.call((message,), Some(&keywords))?
        }
        _ => class.call1((message,))?,
    };
    match err {
        Error::Format {
            location, field, ..
        } => {
            instance.setattr("source", &location.source)?;
            // Line 0: the file as a whole (no line is known).
            let known = |n: usize| (n > 0).then_some(n);
            instance.setattr("line", known(location.line))?;
            instance.setattr("column", known(location.column))?;
            instance.setattr("field", field)?;
        }
        Error::Io {
            path,
            errno,
            reason,
            ..
        } => {
            instance.setattr("filename", path)?;
            instance.setattr("errno", errno)?;
            instance.setattr("strerror", reason)?;
        }
        _ => {}
    }
    Ok(PyErr::from_value(instance))
}

/// An `InvalidArgumentError` with `message`.
pub fn invalid(message: String) -> PyErr {
    to_py(Error::InvalidArgument(message))
}

/// A `WrongTypeError` (an `InvalidArgumentError` that is also a `TypeError`) with `message`: the
/// refusal of an argument of a type its parameter does not take, as opposed to [`invalid`]'s
/// value of the right type out of its range (a str that is not Unicode text is one).
pub fn wrong_type(message: String) -> PyErr {
    if message.contains(crate::args::NOT_UNICODE) {
        return invalid(message); // a str, of a value that is not text
    }
    Python::attach(|py| {
        match py
            .import("mazesim.errors")
            .and_then(|errors| errors.getattr("WrongTypeError"))
            .and_then(|class| class.call1((message.as_str(),)))
        {
            Ok(instance) => PyErr::from_value(instance),
            Err(_) => invalid(message),
        }
    })
}

/// Shorthand: a core result as a Python result.
pub trait IntoPy<T> {
    /// Maps the error.
    fn py(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for mazesim_core::Result<T> {
    fn py(self) -> PyResult<T> {
        self.map_err(to_py)
    }
}
