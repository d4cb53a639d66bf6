//! A tree of bounding spheres over the clustered lights, so that a view's clusters are
//! built from the lights near its frustum alone: a light far from every view costs a
//! frame nothing but the nodes above it that the view rejects.
//!
//! Built when the lights' spheres change (every slot's, in one tree), by splitting the
//! spheres at the median of their centres along the axis where the centres spread most,
//! down to leaves of at most [`LEAF_SPHERES`]. Each node's sphere holds every sphere
//! below it, so a node that a view's clusters cannot meet has no light below it that can.

use bevy::math::DVec3;

/// Most spheres in a leaf.
const LEAF_SPHERES: usize = 16;

/// A light's place in the clusters' input: its slot, and its index in that slot's spheres.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct LightAt {
    pub slot: u32,
    pub index: u32,
}

/// A node: its bounding sphere, and either its two children or its range of lights.
#[derive(Clone, Copy, Debug)]
struct Node {
    center: DVec3,
    radius: f64,
    /// Leaves: the range `first..first + count` of [`SphereTree::lights`]; inner nodes:
    /// `count == 0`, children at `first` and `first + 1`.
    first: u32,
    count: u32,
}

/// The tree (empty until built).
#[derive(Debug, Default)]
pub(crate) struct SphereTree {
    nodes: Vec<Node>,
    lights: Vec<LightAt>,
    /// Scratch for building: each light's centre and radius.
    spheres: Vec<(DVec3, f64)>,
}

impl SphereTree {
    /// Builds the tree over `spheres`: each light's place, centre and radius.
    pub fn build(&mut self, spheres: impl Iterator<Item = (LightAt, DVec3, f64)>) {
        self.nodes.clear();
        self.lights.clear();
        self.spheres.clear();
        for (at, center, radius) in spheres {
            self.lights.push(at);
            self.spheres.push((center, radius));
        }
        if self.lights.is_empty() {
            return;
        }
        self.nodes.push(Node {
            center: DVec3::ZERO,
            radius: 0.0,
            first: 0,
            count: 0,
        });
        self.split(0, 0, self.lights.len());
    }

    /// Makes node `node` hold the lights `start..end`, splitting them below it.
    fn split(&mut self, node: usize, start: usize, end: usize) {
        let (center, radius) = bounding_sphere(&self.spheres[start..end]);
        if end - start <= LEAF_SPHERES {
            self.nodes[node] = Node {
                center,
                radius,
                first: start as u32,
                count: (end - start) as u32,
            };
            return;
        }
        let (low, high) = self.spheres[start..end].iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(low, high), (center, _)| (low.min(*center), high.max(*center)),
        );
        let axis = (high - low).max_position();
        let middle = (end - start) / 2;
        // Sort the lights and their spheres together by the axis, up to the median.
        let mut pairs: Vec<(LightAt, (DVec3, f64))> = self.lights[start..end]
            .iter()
            .copied()
            .zip(self.spheres[start..end].iter().copied())
            .collect();
        pairs.select_nth_unstable_by(middle, |a, b| a.1.0[axis].total_cmp(&b.1.0[axis]));
        for (offset, (at, sphere)) in pairs.into_iter().enumerate() {
            self.lights[start + offset] = at;
            self.spheres[start + offset] = sphere;
        }
        let children = self.nodes.len();
        self.nodes[node] = Node {
            center,
            radius,
            first: children as u32,
            count: 0,
        };
        let child = Node {
            center,
            radius,
            first: 0,
            count: 0,
        };
        self.nodes.extend([child, child]);
        self.split(children, start, start + middle);
        self.split(children + 1, start + middle, end);
    }

    /// Calls `visit` with every light below a node whose sphere `meets` accepts, going down
    /// only through nodes it accepts.
    pub fn visit(&self, meets: impl Fn(DVec3, f64) -> bool, mut visit: impl FnMut(LightAt)) {
        let mut stack = Vec::new();
        if !self.nodes.is_empty() {
            stack.push(0usize);
        }
        while let Some(index) = stack.pop() {
            let node = self.nodes[index];
            if !meets(node.center, node.radius) {
                continue;
            }
            if node.count > 0 {
                let lights = node.first as usize..(node.first + node.count) as usize;
                self.lights[lights].iter().copied().for_each(&mut visit);
            } else {
                stack.extend([node.first as usize, node.first as usize + 1]);
            }
        }
    }
}

/// A sphere that holds every sphere of `spheres` (not the smallest: around the middle of
/// their centres' box, reaching the farthest one's far side).
fn bounding_sphere(spheres: &[(DVec3, f64)]) -> (DVec3, f64) {
    let (low, high) = spheres.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(low, high), (center, _)| (low.min(*center), high.max(*center)),
    );
    let center = (low + high) / 2.0;
    let radius = spheres
        .iter()
        .map(|(c, r)| c.distance(center) + r)
        .fold(0.0, f64::max);
    (center, radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres(count: u32) -> Vec<(LightAt, DVec3, f64)> {
        (0..count)
            .map(|index| {
                let t = f64::from(index);
                let center = DVec3::new(
                    (t * 0.754_877_7).fract(),
                    (t * 0.569_840_3).fract(),
                    (t * 0.618_034).fract(),
                ) * 1000.0;
                (
                    LightAt {
                        slot: index % 2,
                        index,
                    },
                    center,
                    5.0 + (t * 0.37).fract() * 60.0,
                )
            })
            .collect()
    }

    #[test]
    fn a_query_visits_every_light_it_accepts_once_and_few_others() {
        // Lights within 100 units of a point, in a cube 1,000 units across: every light the
        // query accepts is visited once (a node's sphere holds the spheres below it, else
        // one would be missed), and the visit stops at nodes far from the point: it sees
        // the accepted lights' leaves, a small part of the 5,000.
        let all = spheres(5000);
        let mut tree = SphereTree::default();
        tree.build(all.iter().copied());
        let point = DVec3::new(300.0, 500.0, 700.0);
        let meets = |center: DVec3, radius: f64| center.distance(point) <= 100.0 + radius;
        let mut visited = Vec::new();
        tree.visit(meets, |at| visited.push(at));
        visited.sort();
        let accepted: Vec<LightAt> = all
            .iter()
            .filter(|(_, center, radius)| meets(*center, *radius))
            .map(|(at, ..)| *at)
            .collect();
        assert!(!accepted.is_empty());
        for at in &accepted {
            assert_eq!(
                visited.iter().filter(|seen| *seen == at).count(),
                1,
                "{at:?}"
            );
        }
        assert!(
            visited.len() < all.len() / 10,
            "{} of {} lights visited for {} accepted",
            visited.len(),
            all.len(),
            accepted.len()
        );
    }

    #[test]
    fn a_query_that_accepts_everything_finds_every_light_once() {
        let all = spheres(1000);
        let mut tree = SphereTree::default();
        tree.build(all.iter().copied());
        let mut found = Vec::new();
        tree.visit(|_, _| true, |at| found.push(at));
        found.sort();
        let mut expected: Vec<LightAt> = all.iter().map(|(at, ..)| *at).collect();
        expected.sort();
        assert_eq!(found, expected);
    }
}
