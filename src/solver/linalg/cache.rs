//! The analyses a sequence of solves shares: the memory estimate before a solve, the solve
//! itself, and later solves and eigen-analyses of the same network take a pattern's analysis
//! from the [`AnalysisCache`] their caller holds (a network's model), and it is freed with it.

use std::hash::Hasher;
use std::sync::{Arc, Mutex};

use super::cholesky::SparseCholesky;
use super::ordering::Ordering;
use super::symbolic::{analyse_uncached, Symbolic};

/// What a cached analysis was made from: the pairs' hash (verified exactly by
/// [`Symbolic::slots`] on a hit), their count, the dimension and the ordering asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Key {
    pub(super) n: usize,
    pub(super) pairs: usize,
    pub(super) hash: u64,
    pub(super) ordering: Ordering,
}

/// Analyses kept: the solves of one network (estimate, solve, continuation phases, modes)
/// reuse the last few; older ones are dropped so that a pattern changing from solve to solve
/// does not accumulate them.
const CACHED: usize = 3;

/// The analyses of the last patterns factored, most recently used last. Held by whoever runs
/// a sequence of solves on one network (its model); clones share the analyses, which are
/// freed when the last clone is dropped.
#[derive(Clone, Default)]
pub struct AnalysisCache(Arc<Mutex<Vec<Arc<Symbolic>>>>);

impl std::fmt::Debug for AnalysisCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "AnalysisCache({} analyses)", self.lock().len())
    }
}

impl AnalysisCache {
    /// The sparse Cholesky of the pattern `pairs` (upper-triangle pairs, duplicates allowed,
    /// every diagonal entry present) of an `n`-unknown problem with `ordering`, on the
    /// pattern's analysis from this cache or made now (`positions`, asked only then, place the
    /// unknowns for the nested dissection), with each pair's index into its values.
    pub fn factorization(
        &self,
        n: usize,
        pairs: &[(usize, usize)],
        ordering: Ordering,
        positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    ) -> (SparseCholesky, Vec<usize>) {
        let (symbolic, slots) = self
            .analyse(n, pairs, ordering, positions)
            .expect("symbolic Cholesky analysis");
        (SparseCholesky::from_symbolic(symbolic), slots)
    }

    /// Analyses held.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<Arc<Symbolic>>> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The analysis of the pattern `pairs` (see [`Self::factorization`]) with each pair's
    /// slot. `None` where the symbolic analysis fails (index overflow).
    pub(super) fn analyse(
        &self,
        n: usize,
        pairs: &[(usize, usize)],
        ordering: Ordering,
        positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    ) -> Option<(Arc<Symbolic>, Vec<usize>)> {
        let (s, slots) = self.find_or_make(n, pairs, ordering, positions)?;
        let slots =
            slots.unwrap_or_else(|| s.slots(pairs).expect("the pattern holds its own pairs"));
        Some((s, slots))
    }

    /// [`Self::analyse`] without the slots (the memory estimate): a new analysis skips them.
    pub(super) fn analyse_pattern(
        &self,
        n: usize,
        pairs: &[(usize, usize)],
        ordering: Ordering,
        positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    ) -> Option<Arc<Symbolic>> {
        self.find_or_make(n, pairs, ordering, positions)
            .map(|(s, _)| s)
    }

    /// The cached analysis of `pairs` with their slots (the check that it is theirs), or a new
    /// one without.
    fn find_or_make(
        &self,
        n: usize,
        pairs: &[(usize, usize)],
        ordering: Ordering,
        positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    ) -> Option<(Arc<Symbolic>, Option<Vec<usize>>)> {
        let key = Key {
            n,
            pairs: pairs.len(),
            hash: hash_pairs(pairs),
            ordering,
        };
        let cached = take(&mut self.lock(), key);
        if let Some(s) = cached {
            if let Some(slots) = s.slots(pairs) {
                put(&mut self.lock(), s.clone());
                return Some((s, Some(slots)));
            }
        }
        let s = Arc::new(analyse_uncached(n, pairs, ordering, positions, key)?);
        put(&mut self.lock(), s.clone());
        Some((s, None))
    }
}

/// Removes and returns the analysis made under `key`.
fn take(cache: &mut Vec<Arc<Symbolic>>, key: Key) -> Option<Arc<Symbolic>> {
    let at = cache.iter().position(|s| s.key == key)?;
    Some(cache.remove(at))
}

/// Keeps `s` as the most recently used, dropping the least recently used beyond [`CACHED`].
fn put(cache: &mut Vec<Arc<Symbolic>>, s: Arc<Symbolic>) {
    cache.retain(|c| c.key != s.key);
    if cache.len() >= CACHED {
        cache.remove(0);
    }
    cache.push(s);
}

/// A fast hash of the pairs (FxHash's multiply-rotate), to find a cached analysis; a match is
/// then checked pair by pair.
pub(super) fn hash_pairs(pairs: &[(usize, usize)]) -> u64 {
    struct Fx(u64);
    impl Hasher for Fx {
        fn finish(&self) -> u64 {
            self.0
        }
        fn write(&mut self, _: &[u8]) {
            unreachable!("only u64 words are hashed")
        }
        fn write_u64(&mut self, w: u64) {
            self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }
    let mut h = Fx(0);
    for &(r, c) in pairs {
        h.write_u64(r as u64);
        h.write_u64(c as u64);
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::super::ordering::grid_graph;
    use super::super::symbolic::with_order;
    use super::*;

    /// The same pairs find the same analysis in the cache; pairs of another pattern would not
    /// pass [`Symbolic::slots`], and the least recently used analysis is dropped.
    #[test]
    fn an_analysis_is_found_by_its_pairs_and_checked_on_reuse() {
        let (pairs, _) = grid_graph(12);
        let n = 144;
        let key = Key {
            n,
            pairs: pairs.len(),
            hash: hash_pairs(&pairs),
            ordering: Ordering::Amd,
        };
        let a = Arc::new(analyse_uncached(n, &pairs, Ordering::Amd, || None, key).unwrap());
        let mut cache = Vec::new();
        put(&mut cache, a.clone());
        let b = take(&mut cache, key).unwrap();
        assert!(Arc::ptr_eq(&a, &b));
        assert!(take(&mut cache, key).is_none());
        let slots = a.slots(&pairs).unwrap();
        assert_eq!(slots.len(), pairs.len());
        assert_eq!(a.hessian_nnz(), pairs.len());
        let mut other = pairs.clone();
        other.pop();
        assert!(a.slots(&other).is_none(), "an entry in no pair");
        other.push((0, 143));
        assert!(a.slots(&other).is_none(), "a pair not in the pattern");
        for k in 0..=CACHED {
            put(
                &mut cache,
                Arc::new(
                    with_order(n, &pairs, None)
                        .map(|mut s| {
                            s.key.hash = k as u64;
                            s
                        })
                        .unwrap(),
                ),
            );
        }
        assert_eq!(cache.len(), CACHED);
        assert!(cache.iter().all(|s| s.key.hash != 0));
    }

    /// The estimate's analysis is the solve's when they share a cache, another cache makes its
    /// own, and the analysis lives no longer than the caches and factorizations holding it.
    #[test]
    fn an_analysis_is_shared_through_its_cache_only_and_freed_with_it() {
        let (pairs, _) = grid_graph(12);
        let n = 144;
        let cache = AnalysisCache::default();
        let estimate = cache
            .analyse_pattern(n, &pairs, Ordering::Amd, || None)
            .unwrap();
        let (chol, slots) = cache
            .clone()
            .factorization(n, &pairs, Ordering::Amd, || None);
        assert!(Arc::ptr_eq(&estimate, &chol.symbolic));
        assert_eq!(slots, estimate.slots(&pairs).unwrap());
        let other = AnalysisCache::default();
        let (mine, _) = other.factorization(n, &pairs, Ordering::Amd, || None);
        assert!(!Arc::ptr_eq(&estimate, &mine.symbolic));
        let weak = Arc::downgrade(&estimate);
        drop((estimate, chol));
        assert_eq!(cache.len(), 1);
        assert!(weak.upgrade().is_some(), "held by its cache");
        drop(cache);
        assert!(weak.upgrade().is_none(), "freed with its cache");
    }
}
