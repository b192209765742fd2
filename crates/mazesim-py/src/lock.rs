//! The lock of a simulator or batch: exclusive use, and never a deadlock with the GIL.
//!
//! - A call that finds the object busy on another thread waits with the GIL released (so the
//!   thread using it can take the GIL back, for Ctrl-C), and Ctrl-C ends the wait.
//! - A call that finds the object busy on its own thread (re-entrant use: an argument's `dtype`
//!   property that reads the same simulator) raises `SimulatorBusyError` instead of waiting for
//!   itself.
//! - The owner is recorded with its process id: a child made by `fork()` while a thread of its
//!   parent used the object (a thread the child does not have) raises `SimulatorBusyError` saying
//!   so, where a plain mutex would wait forever.
//!
//! The lock is one atomic word (owner process and thread), so that a child inherits nothing else.

use std::cell::UnsafeCell;
use std::ops::{Deref, DerefMut};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::time::Duration;

use mazesim_core::{Error, Result};

use crate::errors::to_py;
use crate::guard::ctrl_c_pressed;

/// Numbers the threads of the process, from 1, for the owner word.
static THREADS: AtomicU32 = AtomicU32::new(1);

thread_local! {
    static THREAD: u32 = THREADS.fetch_add(1, Ordering::Relaxed);
}

/// This thread of this process, as an owner word (never 0, which means free).
fn me() -> u64 {
    (u64::from(std::process::id()) << 32) | u64::from(THREAD.with(|t| *t))
}

/// How long a waiting call sleeps between attempts, at most.
const MOST_BACKOFF: Duration = Duration::from_millis(2);

/// A value used by one thread at a time; see the module's documentation.
pub struct Exclusive<T> {
    owner: AtomicU64,
    value: UnsafeCell<T>,
    /// What the value is called in the busy error ("this Simulator").
    what: &'static str,
}

// The value is reached only through a `Held`, which the owner word makes exclusive.
unsafe impl<T: Send> Send for Exclusive<T> {}
unsafe impl<T: Send> Sync for Exclusive<T> {}

/// The value while held; dropping it frees the lock.
pub struct Held<'a, T> {
    lock: &'a Exclusive<T>,
}

impl<T> Deref for Held<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        // SAFETY: the owner word names this thread until the `Held` is dropped.
        unsafe { &*self.lock.value.get() }
    }
}

impl<T> DerefMut for Held<'_, T> {
    fn deref_mut(&mut self) -> &mut T {
        // SAFETY: as in `deref`, and `&mut self` makes this the only reference.
        unsafe { &mut *self.lock.value.get() }
    }
}

impl<T> Drop for Held<'_, T> {
    fn drop(&mut self) {
        self.lock.owner.store(0, Ordering::Release);
    }
}

impl<T> Exclusive<T> {
    /// `value`, free; `what` names it in messages.
    pub fn new(value: T, what: &'static str) -> Self {
        Self {
            owner: AtomicU64::new(0),
            value: UnsafeCell::new(value),
            what,
        }
    }

    /// Takes the lock if it is free now; `Ok(None)` when another thread of this process has it.
    fn try_take(&self) -> Result<Option<Held<'_, T>>> {
        let me = me();
        match self
            .owner
            .compare_exchange(0, me, Ordering::Acquire, Ordering::Relaxed)
        {
            Ok(_) => Ok(Some(Held { lock: self })),
            Err(owner) if owner == me => Err(Error::Busy(format!(
                "{} is busy: this thread is already inside one of its calls (re-entrant use, \
                 e.g. from an argument's property or a signal handler); call it once that \
                 call has returned",
                self.what
            ))),
            Err(owner) if owner >> 32 != me >> 32 => Err(Error::Busy(format!(
                "{} was in use by another thread when this process was forked, so its state \
                 is half-way through a call; make a new one in the child process",
                self.what
            ))),
            Err(_) => Ok(None),
        }
    }

    /// Takes the lock; the caller does not hold the GIL. Another thread's use is waited for
    /// (Ctrl-C ends the wait with `Error::Interrupted`); re-entrant use and a lock inherited
    /// over `fork()` are `Error::Busy`.
    pub fn wait(&self) -> Result<Held<'_, T>> {
        let mut backoff = Duration::from_micros(20);
        let mut slept = Duration::ZERO;
        loop {
            if let Some(held) = self.try_take()? {
                return Ok(held);
            }
            std::thread::sleep(backoff);
            slept += backoff;
            backoff = (backoff * 2).min(MOST_BACKOFF);
            if slept >= Duration::from_millis(50) {
                slept = Duration::ZERO;
                if ctrl_c_pressed() {
                    return Err(Error::Interrupted);
                }
            }
        }
    }

    /// Takes the lock with the GIL held: at once when free, else waiting with the GIL released.
    pub fn take(&self, py: pyo3::Python<'_>) -> Result<Held<'_, T>>
    where
        T: Send,
    {
        if let Some(held) = self.try_take()? {
            return Ok(held);
        }
        py.detach(|| self.wait())
    }

    /// Runs `f` on the value, the GIL held (released while waiting for another thread).
    pub fn with<R>(&self, f: impl FnOnce(&mut T) -> R) -> pyo3::PyResult<R>
    where
        T: Send,
    {
        let mut held = pyo3::Python::attach(|py| self.take(py)).map_err(to_py)?;
        Ok(f(&mut held))
    }

    /// Runs `f` on the value, the GIL released.
    pub fn with_detached<R>(&self, f: impl FnOnce(&mut T) -> Result<R>) -> Result<R> {
        let mut held = self.wait()?;
        f(&mut held)
    }
}
