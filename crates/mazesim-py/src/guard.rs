//! The one way into the core from Python. Every entry point of the module runs its body through
//! [`enter`] (short calls, the GIL held) or [`enter_detached`] (long calls, the GIL released): a
//! panic, on the calling thread or on a batch's helper threads (rayon hands those to the caller),
//! becomes `mazesim.InternalError` ("internal error, please report" and the panic's message)
//! instead of pyo3's `PanicException`, which `except MazesimError` would not catch.

use std::panic::{catch_unwind, AssertUnwindSafe};

use mazesim_core::Error;
use pyo3::prelude::*;

use crate::errors::to_py;

/// The message of a panic's payload.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_string()
    }
}

/// Runs `body` with the GIL held; a panic becomes `InternalError`.
pub fn enter<T>(body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(body))
        .unwrap_or_else(|payload| Err(to_py(Error::Internal(panic_message(&*payload)))))
}

/// Runs `body` with the GIL released (other Python threads go on meanwhile); a core error becomes
/// its exception, a panic `InternalError`, and Ctrl-C pressed meanwhile `KeyboardInterrupt`
/// (signals are handled once the GIL is back).
pub fn enter_detached<T: Send>(
    py: Python<'_>,
    body: impl FnOnce() -> mazesim_core::Result<T> + Send,
) -> PyResult<T> {
    let outcome = py.detach(|| catch_unwind(AssertUnwindSafe(body)));
    py.check_signals()?;
    match outcome {
        Ok(result) => result.map_err(to_py),
        Err(payload) => Err(to_py(Error::Internal(panic_message(&*payload)))),
    }
}

/// Whether Ctrl-C was pressed since the last call (asked on the main thread; elsewhere never),
/// WITHOUT running Python's signal handlers: long calls ask it while they hold their simulator's
/// lock, where a handler that used the same simulator would wait for itself. The press is handed
/// back to Python when the call ends (`errors::to_py` of `Error::Interrupted`), so the handler
/// runs then, the lock free.
pub fn ctrl_c_pressed() -> bool {
    // SAFETY: called with the GIL held (`attach`), as the C API asks.
    Python::attach(|_| unsafe { pyo3::ffi::PyOS_InterruptOccurred() } != 0)
}

/// Panics with `message` inside the core's reach: on the calling thread, or on a helper thread
/// of a batch when `on_helper_thread`. Only the tests of the panic guard call it.
#[pyfunction]
#[pyo3(signature = (message, on_helper_thread = false))]
pub fn _panic_for_tests(py: Python<'_>, message: String, on_helper_thread: bool) -> PyResult<()> {
    enter_detached(py, move || {
        if on_helper_thread {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .build()
                .map_err(|e| Error::InvalidArgument(e.to_string()))?;
            pool.install(|| rayon::join(|| (), || panic!("{message}")));
        } else {
            panic!("{message}");
        }
        Ok(())
    })
}
