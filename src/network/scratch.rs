//! Buffers a `Model` reuses across assemblies and commits, so that Newton
//! iterations do not allocate: the per-term results of each term kind (their types differ by
//! kind, hence the type-erased slots) and the reference twists a commit remembers.

use std::any::Any;
use std::sync::{Mutex, MutexGuard};

/// The most categories one kind of term reports (`energy::Term::CATEGORIES`).
pub(super) const MAX_CATEGORIES: usize = 2;

/// Not state: a clone starts with empty buffers.
#[derive(Default)]
pub struct Scratch(Mutex<Buffers>);

#[derive(Default)]
pub struct Buffers {
    /// (twist slot, reference twist) pairs of a commit.
    pub remembered: Vec<(usize, f64)>,
    /// Energies (by category) of the blocks of one term kind, summed in order.
    pub energy_blocks: Vec<[f64; MAX_CATEGORIES]>,
    /// Per-term results, one buffer per slot (term kind and derivative order).
    results: Vec<Option<Box<dyn Any + Send>>>,
}

impl Scratch {
    pub fn get(&mut self) -> &mut Buffers {
        self.0.get_mut().unwrap_or_else(|e| e.into_inner())
    }

    /// The buffers, or `None` while another assembly of the same model holds them (the caller
    /// then uses fresh ones).
    pub fn lock(&self) -> Option<MutexGuard<'_, Buffers>> {
        self.0.try_lock().ok()
    }
}

impl Buffers {
    /// The buffer of `slot`, holding results of type `T` (emptied of another type's).
    pub fn results<T: Send + 'static>(&mut self, slot: usize) -> &mut Vec<T> {
        if self.results.len() <= slot {
            self.results.resize_with(slot + 1, || None);
        }
        let b = self.results[slot].get_or_insert_with(|| Box::new(Vec::<T>::new()));
        if !b.is::<Vec<T>>() {
            *b = Box::new(Vec::<T>::new());
        }
        b.downcast_mut::<Vec<T>>()
            .expect("the buffer's type was just set")
    }
}

impl Clone for Scratch {
    fn clone(&self) -> Self {
        Scratch::default()
    }
}

impl std::fmt::Debug for Scratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Scratch")
    }
}
