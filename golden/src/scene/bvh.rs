//! A binned SAH bounding volume hierarchy over triangles.
//!
//! Construction follows Wald, "On fast construction of SAH-based bounding volume hierarchies" (IEEE
//! Symposium on Interactive Ray Tracing, 2007): at each node the triangle centroids are binned along the
//! axis of largest centroid extent into [`BINS`] equal bins; the split between bins minimising the
//! surface area heuristic `A(L) N(L) + A(R) N(R)` (MacDonald and Booth, "Heuristics for ray tracing
//! using space subdivision", The Visual Computer 6(3), 1990) is taken. A node with at most `max_leaf`
//! triangles becomes a leaf; a larger node is always split (so every leaf holds at most `max_leaf`),
//! at the median of its range along the axis when all centroids coincide.
//!
//! Bounds are exact: a leaf's box is the component-wise min and max of its triangles' vertices (min and
//! max do not round), an inner node's box the union of its children's. Construction is deterministic:
//! the same triangles give the same tree on every machine (IEEE f64 arithmetic, stable sorts, ties to
//! the lower bin / lower index).
//!
//! Layout: `nodes[0]` is the root; children come after their parent (depth-first, left subtree first);
//! every node has a parent link. A leaf covers `tri_index[first..first + count]`, indices into the
//! triangle slice the tree was built from.

use crate::error::Error;
use crate::geom::Aabb;
use crate::scene::tri::Triangle;
use glam::DVec3;

/// Number of SAH bins per split.
pub const BINS: usize = 16;

/// What a node holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// Two children, by node index.
    Inner { left: usize, right: usize },
    /// Triangles `tri_index[first..first + count]`.
    Leaf { first: usize, count: usize },
}

/// A BVH node: its exact bounds, its parent (`None` for the root) and its content.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhNode {
    pub bounds: Aabb,
    pub parent: Option<usize>,
    pub kind: NodeKind,
}

/// The tree. `tri_index` is a permutation of `0..tris.len()`.
#[derive(Clone, Debug, PartialEq)]
pub struct Bvh {
    pub nodes: Vec<BvhNode>,
    pub tri_index: Vec<usize>,
    pub max_leaf: usize,
}

fn empty_box() -> Aabb {
    Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    }
}

fn grow(b: &mut Aabb, min: DVec3, max: DVec3) {
    b.min = b.min.min(min);
    b.max = b.max.max(max);
}

fn half_area(b: &Aabb) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let e = b.max - b.min;
    e.x * e.y + e.y * e.z + e.z * e.x
}

impl Bvh {
    /// Builds the tree. Errors: no triangles, `max_leaf` outside `1..=64`, or a non-finite vertex (the
    /// error names the triangle and vertex).
    pub fn build(tris: &[Triangle], max_leaf: usize) -> Result<Bvh, Error> {
        if tris.is_empty() {
            return Err(Error::Io(
                "BVH build: the scene has no triangles".to_string(),
            ));
        }
        if !(1..=64).contains(&max_leaf) {
            return Err(Error::BadFormat {
                param: "max_leaf",
                value: max_leaf as i64,
                why: "the BVH leaf size must be in 1..=64".to_string(),
            });
        }
        for (i, t) in tris.iter().enumerate() {
            for (k, p) in t.v.iter().enumerate() {
                for a in 0..3 {
                    if !p[a].is_finite() {
                        return Err(Error::bad_value(
                            format!("triangle {i} vertex {k}.{}", ["x", "y", "z"][a]),
                            p[a],
                            "triangle vertices must be finite",
                        ));
                    }
                }
            }
        }
        let mm: Vec<(DVec3, DVec3)> = tris.iter().map(|t| t.min_max()).collect();
        let cen: Vec<DVec3> = mm.iter().map(|(a, b)| (*a + *b) * 0.5).collect();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * tris.len() / max_leaf + 1),
            tri_index: (0..tris.len()).collect(),
            max_leaf,
        };
        bvh.build_node(&mm, &cen, 0, tris.len(), None);
        Ok(bvh)
    }

    fn build_node(
        &mut self,
        mm: &[(DVec3, DVec3)],
        cen: &[DVec3],
        first: usize,
        end: usize,
        parent: Option<usize>,
    ) -> usize {
        let id = self.nodes.len();
        let mut bounds = empty_box();
        let mut cb = empty_box();
        for &t in &self.tri_index[first..end] {
            grow(&mut bounds, mm[t].0, mm[t].1);
            grow(&mut cb, cen[t], cen[t]);
        }
        let count = end - first;
        self.nodes.push(BvhNode {
            bounds,
            parent,
            kind: NodeKind::Leaf { first, count },
        });
        if count <= self.max_leaf {
            return id;
        }
        let ext = cb.max - cb.min;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let mid = if ext[axis] > 0.0 {
            self.sah_split(mm, cen, first, end, axis, cb.min[axis], ext[axis])
        } else {
            None
        }
        .unwrap_or_else(|| {
            // All centroids coincide on the axis (or binning found no split): split the range at its
            // median after a stable sort by centroid.
            let idx = &mut self.tri_index[first..end];
            idx.sort_by(|&a, &b| cen[a][axis].total_cmp(&cen[b][axis]).then(a.cmp(&b)));
            first + count / 2
        });
        let left = self.build_node(mm, cen, first, mid, Some(id));
        let right = self.build_node(mm, cen, mid, end, Some(id));
        self.nodes[id].kind = NodeKind::Inner { left, right };
        id
    }

    /// Binned SAH split along `axis`; partitions `tri_index[first..end]` and returns the split point.
    #[allow(clippy::too_many_arguments)]
    fn sah_split(
        &mut self,
        mm: &[(DVec3, DVec3)],
        cen: &[DVec3],
        first: usize,
        end: usize,
        axis: usize,
        cmin: f64,
        cext: f64,
    ) -> Option<usize> {
        let scale = BINS as f64 / cext;
        let bin_of = |c: f64| (((c - cmin) * scale) as usize).min(BINS - 1);
        let mut boxes = [empty_box(); BINS];
        let mut counts = [0usize; BINS];
        for &t in &self.tri_index[first..end] {
            let b = bin_of(cen[t][axis]);
            counts[b] += 1;
            grow(&mut boxes[b], mm[t].0, mm[t].1);
        }
        // Sweep from the right: area and count of bins i..BINS.
        let mut right_area = [0.0; BINS];
        let mut right_count = [0usize; BINS];
        let mut acc = empty_box();
        let mut n = 0;
        for i in (1..BINS).rev() {
            grow(&mut acc, boxes[i].min, boxes[i].max);
            n += counts[i];
            right_area[i] = half_area(&acc);
            right_count[i] = n;
        }
        let mut best: Option<(f64, usize)> = None;
        let mut acc = empty_box();
        let mut n = 0;
        for i in 0..BINS - 1 {
            grow(&mut acc, boxes[i].min, boxes[i].max);
            n += counts[i];
            let (nl, nr) = (n, right_count[i + 1]);
            if nl == 0 || nr == 0 {
                continue;
            }
            let cost = half_area(&acc) * nl as f64 + right_area[i + 1] * nr as f64;
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, i));
            }
        }
        let (_, split) = best?;
        // Stable partition: bins 0..=split to the left.
        let idx = &self.tri_index[first..end];
        let (l, r): (Vec<usize>, Vec<usize>) =
            idx.iter().partition(|&&t| bin_of(cen[t][axis]) <= split);
        let mid = first + l.len();
        self.tri_index[first..mid].copy_from_slice(&l);
        self.tri_index[mid..end].copy_from_slice(&r);
        Some(mid)
    }

    /// Triangle indices (into the build slice) of a leaf; empty for an inner node.
    pub fn leaf_tris(&self, node: usize) -> &[usize] {
        match self.nodes[node].kind {
            NodeKind::Leaf { first, count } => &self.tri_index[first..first + count],
            NodeKind::Inner { .. } => &[],
        }
    }

    /// Every triangle index under `node`, in tree order.
    pub fn subtree_tris(&self, node: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            match self.nodes[n].kind {
                NodeKind::Leaf { first, count } => {
                    out.extend_from_slice(&self.tri_index[first..first + count])
                }
                NodeKind::Inner { left, right } => {
                    stack.push(right);
                    stack.push(left);
                }
            }
        }
        out
    }

    /// Depth of the deepest leaf (root alone: 0).
    pub fn depth(&self) -> usize {
        let mut d = vec![0usize; self.nodes.len()];
        let mut max = 0;
        for i in 1..self.nodes.len() {
            d[i] = d[self.nodes[i].parent.unwrap_or(0)] + 1;
            max = max.max(d[i]);
        }
        max
    }

    /// Number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| matches!(n.kind, NodeKind::Leaf { .. }))
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::tri::random_triangle;
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    fn soup(n: usize, seed: u64) -> Vec<Triangle> {
        let mut rng = Pcg64::seed_from_u64(seed);
        (0..n)
            .map(|_| random_triangle(&mut rng, DVec3::splat(-50.0), DVec3::splat(50.0), 2.0))
            .collect()
    }

    #[test]
    fn tree_is_well_formed_and_bounds_are_exact() {
        let tris = soup(3000, 1);
        let bvh = Bvh::build(&tris, 4).unwrap();
        // tri_index is a permutation.
        let mut seen = vec![false; tris.len()];
        for &t in &bvh.tri_index {
            assert!(!seen[t]);
            seen[t] = true;
        }
        assert!(seen.iter().all(|&s| s));
        for (i, n) in bvh.nodes.iter().enumerate() {
            match n.kind {
                NodeKind::Leaf { count, .. } => {
                    assert!((1..=4).contains(&count));
                    // Tight: the box is exactly the min/max of the vertices.
                    let mut b = empty_box();
                    for &t in bvh.leaf_tris(i) {
                        let (lo, hi) = tris[t].min_max();
                        grow(&mut b, lo, hi);
                    }
                    assert_eq!(b, n.bounds);
                }
                NodeKind::Inner { left, right } => {
                    assert!(left > i && right > i);
                    assert_eq!(bvh.nodes[left].parent, Some(i));
                    assert_eq!(bvh.nodes[right].parent, Some(i));
                    let mut b = bvh.nodes[left].bounds;
                    grow(
                        &mut b,
                        bvh.nodes[right].bounds.min,
                        bvh.nodes[right].bounds.max,
                    );
                    assert_eq!(b, n.bounds);
                }
            }
        }
        assert_eq!(bvh.nodes[0].parent, None);
        // SAH on a uniform soup gives a balanced-ish tree.
        assert!(bvh.depth() < 30, "depth {}", bvh.depth());
    }

    #[test]
    fn build_is_deterministic_and_handles_coincident_centroids() {
        let tris = soup(500, 3);
        assert_eq!(Bvh::build(&tris, 4).unwrap(), Bvh::build(&tris, 4).unwrap());
        // 100 copies of one triangle: median splits, every leaf within the size limit.
        let t = tris[0];
        let same = vec![t; 100];
        let bvh = Bvh::build(&same, 2).unwrap();
        assert_eq!(bvh.subtree_tris(0).len(), 100);
        assert!(bvh.nodes.iter().all(|n| match n.kind {
            NodeKind::Leaf { count, .. } => count <= 2,
            _ => true,
        }));
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(Bvh::build(&[], 4).is_err());
        let tris = soup(3, 4);
        assert!(Bvh::build(&tris, 0).is_err());
        let mut bad = tris.clone();
        bad[1].v[2].y = f64::NAN;
        let e = Bvh::build(&bad, 4).unwrap_err().to_string();
        assert!(e.contains("triangle 1 vertex 2.y"), "{e}");
    }
}
