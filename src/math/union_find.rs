//! Disjoint sets over `0..n`, for grouping what joints and merges tie together.

/// Union-find with path halving. The root of a union is the first argument's root, so the
/// representative of every set (and any order derived from it) depends only on the order of
/// the unions, not on set sizes.
#[derive(Debug, Clone)]
pub struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    /// The representative of `i`'s set.
    pub fn find(&mut self, mut i: usize) -> usize {
        let p = &mut self.parent;
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }

    /// Merges the sets of `a` and `b` under `a`'s root, and returns that root.
    pub fn union(&mut self, a: usize, b: usize) -> usize {
        let (ra, rb) = (self.find(a), self.find(b));
        self.parent[rb] = ra;
        ra
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unions_keep_the_first_root() {
        let mut u = UnionFind::new(5);
        assert_eq!(u.union(3, 1), 3);
        assert_eq!(u.union(0, 1), 0);
        assert_eq!(u.find(3), 0);
        assert_eq!(u.find(1), 0);
        assert_eq!(u.find(2), 2);
        assert_eq!(u.find(4), 4);
    }
}
