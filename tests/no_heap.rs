//! Vectors and bivectors up to N = 8, and 4D rotors, never touch the heap: a counting global
//! allocator asserts it for construction and the hot kernels.

use rotorflow::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    // Per thread, so that tests running in parallel do not count each other.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards to the system allocator and only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Returns how many allocations `f` made.
fn allocations_in(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn graded_kernels_do_not_allocate_for_small_n() {
    // Inputs are built outside the measured closures.
    for n in 2..=8 {
        let comps: Vec<f64> = (0..n * (n - 1) / 2).map(|k| (k as f64).sin()).collect();
        let xs: Vec<f64> = (0..n).map(|k| (k as f64).cos()).collect();
        let count = allocations_in(|| {
            let a = Bivector::from_components(n, &comps).unwrap();
            let b = &a * 0.5 + &a;
            let c = a.commutator(&b);
            let x = Vector::from_components(&xs).unwrap();
            let v = x.left_contract(&c);
            let w = x.wedge(&v);
            let _ = std::hint::black_box((c.norm(), w.inner(&a), a.pfaffian()));
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations");
    }
}

#[test]
fn rotor_kernels_do_not_allocate_in_3d_and_4d() {
    for n in [3, 4] {
        let comps: Vec<f64> = (0..n * (n - 1) / 2).map(|k| 0.3 + k as f64).collect();
        let b = Bivector::from_components(n, &comps).unwrap();
        let x = Vector::basis(n, 0);
        // The first use in each dimension builds cached blade tables once; warm them up.
        let _ = b.exp().compose(&b.exp()).rotate_vector(&x);
        let count = allocations_in(|| {
            let r = b.exp();
            let mut s = r.compose(&r);
            s.rotate_in_plane_mut(0, 1, 0.1);
            let y = s.rotate_vector(&x);
            let l = s.log();
            let _ = std::hint::black_box((y, l, s.unit_error()));
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations");
    }
}
