//! Where every variable of a network lives in the one vector `q`, stated once.
//!
//! `q` = node coordinates (3 per node) | edge angles θ (1 per edge) | frame rotation increments
//! ω (3 per vertex frame) | hinge angles α (1 each) | one variable that is always zero. Terms,
//! supports, contact, projection, results and form finding all index `q` through this type.

/// What a variable is, for step limits and residual scaling.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarKind {
    Position,
    Angle,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DofLayout {
    n_nodes: usize,
    n_edges: usize,
    n_frames: usize,
    n_alpha: usize,
}

impl DofLayout {
    pub fn new(n_nodes: usize, n_edges: usize, n_frames: usize, n_alpha: usize) -> Self {
        DofLayout {
            n_nodes,
            n_edges,
            n_frames,
            n_alpha,
        }
    }

    pub fn n_nodes(&self) -> usize {
        self.n_nodes
    }
    pub fn n_edges(&self) -> usize {
        self.n_edges
    }
    pub fn n_frames(&self) -> usize {
        self.n_frames
    }
    pub fn n_alpha(&self) -> usize {
        self.n_alpha
    }

    /// Number of variables, the zero variable included.
    pub fn len(&self) -> usize {
        self.zero() + 1
    }
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The three coordinate variables of node `n`.
    #[inline]
    pub fn node(&self, n: usize) -> [usize; 3] {
        [3 * n, 3 * n + 1, 3 * n + 2]
    }
    /// Coordinate `k` of node `n`.
    #[inline]
    pub fn node_coord(&self, n: usize, k: usize) -> usize {
        3 * n + k
    }
    /// Variables of every node coordinate, as one range (`q[positions()]` is the nodes' xyz).
    pub fn positions(&self) -> std::ops::Range<usize> {
        0..3 * self.n_nodes
    }
    /// The edge angle θ of edge `e`.
    #[inline]
    pub fn theta(&self, e: usize) -> usize {
        3 * self.n_nodes + e
    }
    /// The three rotation increments ω of vertex frame `f`.
    #[inline]
    pub fn frame(&self, f: usize) -> [usize; 3] {
        let b = 3 * self.n_nodes + self.n_edges + 3 * f;
        [b, b + 1, b + 2]
    }
    /// Hinge angle `a`.
    #[inline]
    pub fn alpha(&self, a: usize) -> usize {
        3 * self.n_nodes + self.n_edges + 3 * self.n_frames + a
    }
    /// The variable that is fixed at zero (the hinge angle of ports without a hinge).
    #[inline]
    pub fn zero(&self) -> usize {
        self.alpha(self.n_alpha)
    }

    #[inline]
    pub fn kind(&self, v: usize) -> VarKind {
        if v < 3 * self.n_nodes {
            VarKind::Position
        } else {
            VarKind::Angle
        }
    }
    /// The node a coordinate variable belongs to.
    #[inline]
    pub fn node_of(&self, v: usize) -> Option<usize> {
        (v < 3 * self.n_nodes).then_some(v / 3)
    }

    /// Position of node `n` in `q`.
    #[inline]
    pub fn position(&self, q: &[f64], n: usize) -> [f64; 3] {
        [q[3 * n], q[3 * n + 1], q[3 * n + 2]]
    }
    pub fn set_position(&self, q: &mut [f64], n: usize, p: [f64; 3]) {
        q[3 * n..3 * n + 3].copy_from_slice(&p);
    }
    /// The three values of frame `f`'s increment ω in `q`.
    pub fn frame_increment(&self, q: &[f64], f: usize) -> [f64; 3] {
        self.frame(f).map(|v| q[v])
    }
    /// Every node position of `q`.
    pub fn node_positions<'a>(&self, q: &'a [f64]) -> impl Iterator<Item = [f64; 3]> + 'a {
        q[..3 * self.n_nodes]
            .chunks_exact(3)
            .map(|x| [x[0], x[1], x[2]])
    }
}

/// Marks a fixed variable in a free map and an unused Hessian slot.
pub const FIXED: u32 = u32::MAX;

/// The free unknowns of a layout: `free[v]` is variable v's index among the unknowns, or
/// [`FIXED`]. What constraint and projection code needs of a model, without the model.
#[derive(Debug, Clone, Copy)]
pub struct Unknowns<'a> {
    pub layout: &'a DofLayout,
    pub free: &'a [u32],
}

impl Unknowns<'_> {
    /// Unknown of variable `v`, if it is free.
    #[inline]
    pub fn of(&self, v: usize) -> Option<usize> {
        let f = self.free[v];
        (f != FIXED).then_some(f as usize)
    }
    /// Unknown of coordinate `k` of node `n`, if it is free.
    #[inline]
    pub fn of_node(&self, n: usize, k: usize) -> Option<usize> {
        self.of(self.layout.node_coord(n, k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_follow_each_other_without_gaps() {
        let l = DofLayout::new(4, 3, 2, 1);
        assert_eq!(l.node(3), [9, 10, 11]);
        assert_eq!(l.theta(0), 12);
        assert_eq!(l.theta(2), 14);
        assert_eq!(l.frame(0), [15, 16, 17]);
        assert_eq!(l.frame(1), [18, 19, 20]);
        assert_eq!(l.alpha(0), 21);
        assert_eq!(l.zero(), 22);
        assert_eq!(l.len(), 23);
        assert_eq!(l.kind(11), VarKind::Position);
        assert_eq!(l.kind(12), VarKind::Angle);
        assert_eq!(l.node_of(10), Some(3));
        assert_eq!(l.node_of(12), None);
    }
}
