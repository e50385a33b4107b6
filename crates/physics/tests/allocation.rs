//! Once its storage has grown to fit the scene, a step allocates nothing:
//! the grid, the contacts, the solver's rows and the warm start all keep
//! their memory from step to step. Every allocation in this test binary is
//! counted, so it holds a single test: nothing else runs while it counts.

mod common;

use common::{build, crowded_pit};
use rolypoly_physics::{World, WorldConfig};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering};

/// The system allocator, counting every allocation and reallocation.
struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// Allocations made by `steps` steps of `world`.
fn allocations_over(world: &mut World, steps: usize) -> u64 {
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..steps {
        world.step();
        world.drain_events().for_each(drop);
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

/// Allocations per step of `world` over `steps` steps, after `warm_up`.
/// Storage may still grow now and then, when the contacts reach a number
/// not seen before, and the thread pool's queue takes a block of memory
/// for every 63 jobs it is handed (a crowded world hands it each step): a
/// step that allocates would make at least one allocation every step, and
/// these make fewer than one in ten.
fn allocations_per_step(mut world: World, warm_up: usize, steps: usize) -> f64 {
    allocations_over(&mut world, warm_up);
    allocations_over(&mut world, steps) as f64 / steps as f64
}

#[test]
fn a_step_allocates_nothing_once_its_storage_fits_the_scene() {
    // The default room, on one thread: balls, tumblers and walls.
    let room = allocations_per_step(build(WorldConfig::default(), 3), 600, 1200);
    assert!(room < 0.1, "the default room: {room} allocations per step");
    // A crowded pile, on all threads.
    let pit = allocations_per_step(build(crowded_pit(), 11), 120, 300);
    assert!(pit < 0.1, "a 3000-ball pile: {pit} allocations per step");
}
