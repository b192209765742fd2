//! Bytes per environment, counted by a counting allocator: every byte a batch allocates, for
//! 4,096 distinct generated 5 x 5 mazes and for 4,096 envs sharing one maze, and the batch's own
//! account of them (`Batch::bytes_per_env`).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering};
use std::sync::Arc;

use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::{Batch, RobotProfile, World};

struct Counting;

static LIVE: AtomicIsize = AtomicIsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE.fetch_add(layout.size() as isize, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size() as isize, Ordering::Relaxed);
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LIVE.fetch_add(
            new_size as isize - layout.size() as isize,
            Ordering::Relaxed,
        );
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

const ENVS: usize = 4096;

fn mazes(distinct: bool) -> Vec<Arc<World>> {
    let p = MazeParams {
        loops: 0.1,
        ..Default::default()
    };
    let one = Arc::new(generate(&p, 0).unwrap());
    (0..ENVS as u64)
        .map(|s| {
            if distinct {
                Arc::new(generate(&p, s).unwrap())
            } else {
                one.clone()
            }
        })
        .collect()
}

/// Bytes the batch and its worlds hold per env: live bytes with them, less live bytes without.
fn measured(distinct: bool) -> (usize, usize) {
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let seeds: Vec<u64> = (0..ENVS as u64).collect();
    let before = LIVE.load(Ordering::Relaxed);
    let worlds = mazes(distinct);
    let batch = Batch::new(worlds, robot, &seeds, true, None, 1).unwrap();
    let held = LIVE.load(Ordering::Relaxed) - before;
    let told = batch.bytes_per_env();
    drop(batch);
    (held as usize / ENVS, told)
}

#[test]
fn bytes_per_env_stay_small() {
    // One test: the counter is global, so nothing else may allocate meanwhile.
    let (distinct, distinct_told) = measured(true);
    let (shared, shared_told) = measured(false);
    println!("distinct mazes: {distinct} B/env (told {distinct_told}); one maze: {shared} B/env (told {shared_told})");
    assert!(
        distinct <= 16_000,
        "{distinct} bytes per env of distinct mazes"
    );
    assert!(shared <= 4_000, "{shared} bytes per env sharing one maze");
    for (held, told) in [(distinct, distinct_told), (shared, shared_told)] {
        assert!(
            told <= held && told * 10 >= held * 8,
            "told {told} bytes per env, held {held}"
        );
    }
}
