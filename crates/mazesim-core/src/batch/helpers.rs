//! Who steps a batch besides the calling thread: the pool shared by batches that use every core
//! (made again in a forked child) or a batch's own pool for an explicit thread count.

use std::sync::Mutex;

use rayon::prelude::*;
use rayon::ThreadPool;

use crate::error::{Error, Result};
use crate::limits::MAX_THREADS;

/// The helpers of batches that use every core: one thread fewer than the machine has cores,
/// shared by all such batches of a process; `None` on a single core.
///
/// A forked child process inherits the parent's pool without its threads (`fork` copies only the
/// calling thread), so work given to it would wait forever. The pool is therefore kept with the
/// id of the process that made it, and a process that finds another's makes its own (the
/// parent's copy is left alone: its threads do not exist here). This is the fork guard.
fn shared_helpers() -> Option<&'static ThreadPool> {
    static HELPERS: Mutex<Option<(u32, Option<&'static ThreadPool>)>> = Mutex::new(None);
    let pid = std::process::id();
    let mut helpers = HELPERS.lock().unwrap_or_else(|p| p.into_inner());
    match *helpers {
        Some((owner, pool)) if owner == pid => pool,
        _ => {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            let pool = helper_pool(cores.min(MAX_THREADS))
                .ok()
                .flatten()
                .map(|p| &*Box::leak(Box::new(p)));
            *helpers = Some((pid, pool));
            pool
        }
    }
}

/// A pool of `threads - 1` helper threads (`None` for one thread: the caller works alone).
fn helper_pool(threads: usize) -> Result<Option<ThreadPool>> {
    if threads <= 1 {
        return Ok(None);
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads - 1)
        .thread_name(|i| format!("mazesim-batch-{i}"))
        .build()
        .map(Some)
        .map_err(|e| Error::InvalidArgument(format!("cannot start {threads} threads: {e}")))
}

/// Who steps a batch besides the calling thread.
pub(crate) enum Helpers {
    /// The pool shared by batches that use every core.
    Shared(Option<&'static ThreadPool>),
    /// A pool of the batch's own, for an explicit thread count.
    Own(Option<ThreadPool>, usize),
}

impl Helpers {
    /// The helpers for `threads` (0: every core), made in this process.
    pub(crate) fn new(threads: usize) -> Result<Helpers> {
        if threads > MAX_THREADS {
            return Err(Error::InvalidArgument(format!(
                "expected threads in 0..={MAX_THREADS} (0 = one per core), found {threads}"
            )));
        }
        Ok(if threads == 0 {
            Helpers::Shared(shared_helpers())
        } else {
            Helpers::Own(helper_pool(threads)?, threads)
        })
    }

    pub(crate) fn pool(&self) -> Option<&ThreadPool> {
        match self {
            Helpers::Shared(p) => *p,
            Helpers::Own(p, _) => p.as_ref(),
        }
    }

    /// `make` of every item, in order, on the helpers where there are some; the error of an
    /// item that fails.
    pub(crate) fn make_all<T: Send, U: Send>(
        &self,
        items: Vec<T>,
        make: impl Fn(T) -> Result<U> + Sync + Send,
    ) -> Result<Vec<U>> {
        match self.pool() {
            Some(p) => p.install(|| items.into_par_iter().map(make).collect()),
            None => items.into_iter().map(make).collect(),
        }
    }

    /// The same helpers made again in a forked child; the parent's pool, whose threads do not
    /// exist in the child, is forgotten rather than dropped (dropping would signal them).
    pub(super) fn remade(self) -> Result<Helpers> {
        match self {
            Helpers::Shared(_) => Helpers::new(0),
            Helpers::Own(pool, threads) => {
                std::mem::forget(pool);
                Helpers::new(threads)
            }
        }
    }
}
