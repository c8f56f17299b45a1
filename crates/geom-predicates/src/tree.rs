//! A static k-d tree over points (a thin wrapper over `kiddo`'s immutable tree) for nearest
//! point and fixed-radius queries, answering with indices into the points it was built from.

use kiddo::SquaredEuclidean;
use kiddo::immutable::float::kdtree::ImmutableKdTree;

/// Points in a k-d tree, by their index in the slice the tree was built from.
pub struct PointTree<const D: usize> {
    tree: ImmutableKdTree<f64, u64, D, 32>,
    len: usize,
}

impl<const D: usize> std::fmt::Debug for PointTree<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PointTree").field("len", &self.len).finish()
    }
}

impl<const D: usize> PointTree<D> {
    /// Builds the tree (O(n log n)). Coordinates must be finite.
    pub fn new(points: &[[f64; D]]) -> Self {
        Self {
            tree: ImmutableKdTree::new_from_slice(points),
            len: points.len(),
        }
    }

    /// How many points the tree holds.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the tree holds no point.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The index of a point nearest to `p` and its distance, `None` for an empty tree. Among
    /// points at the same distance any may be returned.
    pub fn nearest(&self, p: [f64; D]) -> Option<(usize, f64)> {
        if self.len == 0 {
            return None;
        }
        let n = self.tree.nearest_one::<SquaredEuclidean>(&p);
        Some((n.item as usize, n.distance.sqrt()))
    }

    /// The indices of the points within distance `radius` of `p` (closed ball), nearest first.
    pub fn within(&self, p: [f64; D], radius: f64) -> Vec<(usize, f64)> {
        if self.len == 0 {
            return Vec::new();
        }
        self.tree
            .within::<SquaredEuclidean>(&p, radius * radius)
            .into_iter()
            .map(|n| (n.item as usize, n.distance.sqrt()))
            .collect()
    }
}
