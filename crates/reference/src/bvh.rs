//! A bounding volume hierarchy: boxes within boxes, so that a ray tests
//! the few things near its path instead of all of them. One serves the
//! scene's objects, one each mesh's triangles.

use crate::geometry::{Aabb, Ray};

/// Things per leaf: below this, splitting costs more than it saves.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Debug)]
struct Node {
    bounds: Aabb,
    /// A leaf: its first item in `order`; a branch: its second child (the
    /// first follows it).
    first: u32,
    /// A leaf's item count; 0 for a branch.
    count: u32,
}

/// Boxes within boxes over items numbered 0..n.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Bvh {
    /// The hierarchy over items with these bounds: each branch splits its
    /// items at the median of their centres along its widest axis.
    pub fn new(bounds: &[Aabb]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * bounds.len() / LEAF_SIZE + 1),
            order: (0..bounds.len() as u32).collect(),
        };
        if !bounds.is_empty() {
            bvh.build(bounds, 0, bounds.len());
        }
        bvh
    }

    fn build(&mut self, bounds: &[Aabb], start: usize, end: usize) -> usize {
        let items = &mut self.order[start..end];
        let whole = items
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(bounds[i as usize]));
        let index = self.nodes.len();
        self.nodes.push(Node {
            bounds: whole,
            first: start as u32,
            count: (end - start) as u32,
        });
        if end - start <= LEAF_SIZE {
            return index;
        }
        let centres = items
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.with(bounds[i as usize].centre()));
        let axis = (centres.max - centres.min).max_position();
        let middle = (end - start) / 2;
        items.select_nth_unstable_by(middle, |&a, &b| {
            let key = |i: u32| bounds[i as usize].centre()[axis];
            key(a).total_cmp(&key(b))
        });
        self.build(bounds, start, start + middle);
        let second = self.build(bounds, start + middle, end);
        self.nodes[index].first = second as u32;
        self.nodes[index].count = 0;
        index
    }

    /// Offers `ray` every item whose boxes it enters before the nearest
    /// hit so far: `hit(item, t_max)` returns the distance at which the
    /// item is met, nearer than `t_max`, if it is. Returns the nearest.
    pub fn nearest(
        &self,
        ray: &Ray,
        mut t_max: f32,
        mut hit: impl FnMut(u32, f32) -> Option<f32>,
    ) -> f32 {
        if self.nodes.is_empty() {
            return t_max;
        }
        let inv_dir = ray.dir.recip();
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let index = stack[top];
            let node = &self.nodes[index as usize];
            if !node.bounds.hit(ray.origin, inv_dir, t_max) {
                continue;
            }
            if node.count > 0 {
                let first = node.first as usize;
                for &item in &self.order[first..first + node.count as usize] {
                    if let Some(t) = hit(item, t_max) {
                        t_max = t;
                    }
                }
            } else {
                // A branch's first child follows it. The median split
                // keeps the depth near log2(n), far below the stack's size.
                stack[top] = node.first;
                stack[top + 1] = index + 1;
                top += 2;
            }
        }
        t_max
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::hit_sphere;
    use crate::sampler::Sampler;
    use glam::Vec3;

    #[test]
    fn finds_the_same_nearest_sphere_as_testing_every_one() {
        let mut rng = Sampler::new(1, 2, 3);
        let mut r = || rng.uniform();
        let spheres: Vec<(Vec3, f32)> = (0..500)
            .map(|_| (Vec3::new(r(), r(), r()) * 10.0, 0.1 + 0.3 * r()))
            .collect();
        let bounds: Vec<Aabb> = spheres
            .iter()
            .map(|&(c, s)| Aabb::of_sphere(c, s))
            .collect();
        let bvh = Bvh::new(&bounds);
        for _ in 0..2000 {
            let ray = Ray {
                origin: Vec3::new(r(), r(), r()) * 12.0 - Vec3::ONE,
                dir: (Vec3::new(r(), r(), r()) - Vec3::splat(0.5)).normalize(),
            };
            let each = spheres
                .iter()
                .filter_map(|&(c, s)| hit_sphere(&ray, c, s, f32::INFINITY))
                .fold(f32::INFINITY, f32::min);
            let through = bvh.nearest(&ray, f32::INFINITY, |i, t_max| {
                let (c, s) = spheres[i as usize];
                hit_sphere(&ray, c, s, t_max)
            });
            assert_eq!(each, through);
        }
    }
}
