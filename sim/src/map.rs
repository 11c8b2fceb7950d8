//! The map: places joined by routes, and shortest routes over them.
//!
//! Owns the petgraph graph of the world's places (one node per place, in file
//! order; one undirected edge per route, weighted by its length in metres).
//! Invariant: node `i` is place `i` of the [`World`], every weight is finite
//! and positive, so Dijkstra's shortest routes are well defined and the same
//! on every run.

use std::collections::BTreeSet;

use petgraph::algo::astar;
use petgraph::graph::{NodeIndex, UnGraph};
use petgraph::visit::{EdgeFiltered, EdgeRef};

use crate::world::World;

/// A route between two places, as the map sees it: undirected, so the pair
/// is kept smaller index first.
pub(crate) type Edge = (usize, usize);

pub(crate) fn edge(a: usize, b: usize) -> Edge {
    (a.min(b), a.max(b))
}

#[derive(Clone, Debug)]
pub(crate) struct Map {
    graph: UnGraph<usize, f64>,
}

impl Map {
    /// The world's routes, or every pair of places at Euclidean distance when
    /// the world has no `[[route]]`. Two places at the same spot and without
    /// an explicit route are not joined (a route of length 0 is no route).
    pub fn new(world: &World) -> Map {
        let mut graph = UnGraph::with_capacity(world.places.len(), 0);
        for i in 0..world.places.len() {
            graph.add_node(i);
        }
        match &world.routes {
            Some(routes) => {
                for r in routes {
                    graph.add_edge(NodeIndex::new(r.from), NodeIndex::new(r.to), r.length);
                }
            }
            None => {
                for a in 0..world.places.len() {
                    for b in a + 1..world.places.len() {
                        let d = (world.places[a].pos - world.places[b].pos).norm();
                        if d > 0.0 {
                            graph.add_edge(NodeIndex::new(a), NodeIndex::new(b), d);
                        }
                    }
                }
            }
        }
        Map { graph }
    }

    /// The shortest route from `from` to `to` that uses none of `avoid`:
    /// its places (both ends included) and its length. Dijkstra's algorithm,
    /// run as petgraph's A* with a zero heuristic (which also returns the
    /// path).
    pub fn plan(
        &self,
        from: usize,
        to: usize,
        avoid: &BTreeSet<Edge>,
    ) -> Option<(Vec<usize>, f64)> {
        if from == to {
            return Some((vec![from], 0.0));
        }
        let open =
            EdgeFiltered::from_fn(&self.graph, |e: petgraph::graph::EdgeReference<'_, f64>| {
                !avoid.contains(&edge(e.source().index(), e.target().index()))
            });
        let (length, path) = astar(
            &open,
            NodeIndex::new(from),
            |n| n.index() == to,
            |e| *e.weight(),
            |_| 0.0,
        )?;
        Some((path.into_iter().map(|n| n.index()).collect(), length))
    }

    /// The length of the direct route between two places, if there is one
    /// (the shortest, if there are several).
    pub fn direct(&self, a: usize, b: usize) -> Option<f64> {
        self.graph
            .edges_connecting(NodeIndex::new(a), NodeIndex::new(b))
            .map(|e| *e.weight())
            .reduce(f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world(text: &str) -> World {
        World::parse("t.toml", text).unwrap_or_else(|e| panic!("{e:?}"))
    }

    const HEAD: &str = "[robot]\nname = \"G\"\nat = \"a\"\n[user]\nname = \"L\"\nat = \"a\"\n";

    #[test]
    fn complete_graph_by_default() {
        let w = world(&format!(
            "{HEAD}[[place]]\nname = \"a\"\nx = 0\ny = 0\n[[place]]\nname = \"b\"\nx = 3\ny = 4\n[[place]]\nname = \"c\"\nx = 6\ny = 0\n"
        ));
        let m = Map::new(&w);
        let (p, l) = m.plan(0, 2, &BTreeSet::new()).unwrap();
        assert_eq!(p, [0, 2]);
        assert_eq!(l, 6.0);
        let (p, l) = m.plan(0, 2, &[edge(2, 0)].into()).unwrap();
        assert_eq!(p, [0, 1, 2]);
        assert_eq!(l, 10.0);
    }

    #[test]
    fn explicit_routes_and_no_route() {
        let w = world(&format!(
            "{HEAD}[[place]]\nname = \"a\"\nx = 0\ny = 0\n[[place]]\nname = \"b\"\nx = 1\ny = 0\n[[place]]\nname = \"c\"\nx = 2\ny = 0\n\
             [[route]]\nfrom = \"a\"\nto = \"b\"\nlength = 5\n"
        ));
        let m = Map::new(&w);
        assert_eq!(m.plan(0, 1, &BTreeSet::new()).unwrap().1, 5.0);
        assert!(m.plan(0, 2, &BTreeSet::new()).is_none());
        assert_eq!(m.direct(1, 0), Some(5.0));
        assert_eq!(m.direct(1, 2), None);
    }
}
