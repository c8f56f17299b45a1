//! The whole-state check of the growing mesh.
//!
//! [`Work::sanity_check`] checks the invariant that the growth keeps after every step: the
//! node store is consistent, every cell is alive-cornered and positive, and the fronts are
//! closed loops whose edges meet only at the nodes they share. It runs after every step in
//! debug builds (and in the tests); it is never run in release builds, and it reports the
//! first problem instead of panicking.

use mesh_model::NONE;

use geom_predicates::{for_each_overlapping_pair, polygon_area};

use crate::contact::front_edges_meet;
use crate::geom::P2;
use crate::grow::Work;

impl Work<'_> {
    /// The first problem of the whole front state, if any (see the module documentation).
    pub(crate) fn sanity_check(&self) -> Result<(), String> {
        self.nodes.check()?;
        let n = self.nodes.len();
        let usable = |g: u32| (g as usize) < n && self.nodes.alive[g as usize];
        for (ci, c) in self.cells.iter().enumerate() {
            if c.len == 0 {
                continue;
            }
            if !(c.len == 3 || c.len == 4) || !c.corners().iter().all(|&g| usable(g)) {
                return Err(format!(
                    "cell {ci}: corners {:?} not alive nodes",
                    c.corners()
                ));
            }
            let p: Vec<P2> = c
                .corners()
                .iter()
                .map(|&g| self.nodes.pos[g as usize])
                .collect();
            let area = polygon_area(p.iter().copied());
            if area.is_nan() || area <= 0.0 {
                return Err(format!("cell {ci}: area {area:e} is not positive"));
            }
        }
        for (li, l) in self.loops.iter().enumerate() {
            if l.items.len() != l.edges.len() || l.items.len() < 3 {
                return Err(format!(
                    "front {li}: {} nodes and {} edges",
                    l.items.len(),
                    l.edges.len()
                ));
            }
            if let Some(g) = l.items.iter().find(|&&g| !usable(g)) {
                return Err(format!("front {li}: node {g} is not an alive node"));
            }
            if let Some(e) = l
                .edges
                .iter()
                .find(|e| e.cell != NONE && e.cell as usize >= self.cells.len())
            {
                return Err(format!("front {li}: edge cell {} out of range", e.cell));
            }
        }
        let (segs, boxes) = self.front_segments();
        let mut first: Option<String> = None;
        for_each_overlapping_pair(&boxes, |x, y| {
            let (sx, sy) = (segs[x], segs[y]);
            if first.is_none() && front_edges_meet(&self.nodes.pos, [sx.0, sx.1], [sy.0, sy.1]) {
                first = Some(format!(
                    "front edges {}:{} ({}-{}) and {}:{} ({}-{}) meet",
                    sx.2, sx.3, sx.0, sx.1, sy.2, sy.3, sy.0, sy.1
                ));
            }
        });
        first.map_or(Ok(()), Err)
    }
}

#[cfg(test)]
mod tests {
    use crate::grow::{Law, Work};
    use crate::input::AfsfParams;

    /// A small body (a 16-gon, wall) inside a circle (far field), grown a few layers.
    fn grown(params: &AfsfParams) -> Work<'_> {
        let ring = |r: f64, m: usize, ccw: bool| -> Vec<[f64; 2]> {
            (0..m)
                .map(|k| {
                    let t = 2.0 * std::f64::consts::PI * k as f64 / m as f64;
                    let t = if ccw { t } else { -t };
                    [r * t.cos(), r * t.sin()]
                })
                .collect()
        };
        let mut points = ring(1.0, 16, false); // the domain on the left: clockwise body
        points.extend(ring(6.0, 24, true));
        let fronts = vec![
            (
                (0..16).collect(),
                (0..16).collect(),
                Law::Geometric {
                    first: 0.02,
                    growth: 1.3,
                },
            ),
            (
                (16..40).collect(),
                (16..40).collect(),
                Law::Isotropic { factor: 1.0 },
            ),
        ];
        let mut w = Work::new(params, points, fronts);
        w.grow().expect("the springs solve");
        w
    }

    #[test]
    fn a_grown_state_is_sane_and_each_kind_of_damage_is_reported() {
        let params = AfsfParams {
            max_layers: 6,
            ..AfsfParams::default()
        };
        let w = grown(&params);
        assert!(w.nodes.len() > 40 && !w.cells.is_empty());
        assert_eq!(w.sanity_check(), Ok(()));

        // a cell turned clockwise
        let mut bad = grown(&params);
        let c = bad.cells.iter().position(|c| c.len == 4).unwrap();
        bad.cells[c].nodes[..4].reverse();
        let e = bad.sanity_check().unwrap_err();
        assert!(
            e.contains(&format!("cell {c}")) && e.contains("not positive"),
            "{e}"
        );

        // a front node thrown across the domain: its edges cross the other front
        let mut bad = grown(&params);
        let g = *bad.loops[0].items.iter().max().unwrap() as usize;
        bad.nodes.pos[g] = [8.0, 0.1];
        for c in &mut bad.cells {
            c.len = 0; // only the fronts are damaged
        }
        let e = bad.sanity_check().unwrap_err();
        assert!(e.contains("meet"), "{e}");

        // a store array out of step, and a parent that is not older
        let mut bad = grown(&params);
        bad.nodes.ideal.pop();
        assert!(bad.sanity_check().unwrap_err().contains("node store"));
        let mut bad = grown(&params);
        let last = bad.nodes.len() - 1;
        bad.nodes.parent2[5] = last as u32;
        assert!(
            bad.sanity_check()
                .unwrap_err()
                .contains("not an older node")
        );
    }
}
