//! The summary table printed on stdout after a run: what was made, how long it took, what was
//! written.

use std::fmt::Write;

use curvemesh::Report;

/// The table for a report, as text.
pub fn table(r: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "case {}  (dimension {}, order {})",
        r.case, r.dimension, r.order
    );
    let _ = writeln!(s, "  {:<22} {:>12}", "nodes", r.nodes);
    for (kind, n) in &r.cells {
        let _ = writeln!(s, "  {:<22} {:>12}", format!("cells {kind}"), n);
    }
    for (group, n) in &r.boundary_groups {
        let _ = writeln!(s, "  {:<22} {:>12}", format!("boundary {group}"), n);
    }
    if let Some(layers) = r.layers {
        let _ = writeln!(s, "  {:<22} {:>12}", "layers", layers);
    }
    for l in &r.loops {
        let _ = writeln!(
            s,
            "  loop {:<17} {:>12}  ({}, {} corners, spacing {:.2e} .. {:.2e})",
            l.name, l.nodes, l.role, l.corners, l.spacing_min, l.spacing_max
        );
    }
    if let Some(q) = &r.quality {
        quality_2d(&mut s, q, r.order);
    }
    if let Some(f) = r.curved_edge_fraction {
        let _ = writeln!(s, "  {:<22} {:>11.1}%", "curved edges", 100.0 * f);
    }
    if let Some(c) = &r.curving {
        let _ = writeln!(
            s,
            "  {:<22} {:>12}  (stops: {} valid straight, {} collapsed, {} pipe ended; {} repaired)",
            "curved layers (max)",
            c.deepest_curved_layer,
            c.stops.jacobian,
            c.stops.collapsed,
            c.stops.pipe_ended,
            c.repaired_cells
        );
    }
    if let Some(a) = r.area {
        let _ = writeln!(s, "  {:<22} {:>12.6e}", "area", a);
    }
    if let Some(q) = &r.quality_3d {
        quality_3d(&mut s, q);
    }
    if let (Some(v), Some(c)) = (r.volume, &r.volume_check) {
        let _ = writeln!(
            s,
            "  {:<22} {:>12.6e}  (between wall and front {:.6e}, relative difference {:.1e})",
            "volume", v, c.between_wall_and_front, c.relative_difference
        );
    }
    if let Some(c) = r.coverage {
        let _ = writeln!(s, "  {:<22} {:>11.1}%", "coverage", 100.0 * c);
    }
    if let Some(f) = &r.fill {
        let _ = writeln!(
            s,
            "  {:<22} {:>12}  ({} pyramids on the front's quads, {} front edges capped, {} Steiner and {} refinement points, max dihedral {:.1} deg)",
            "fill tets",
            f.tets,
            f.pyramids,
            f.caps,
            f.steiner_points,
            f.refinement_points,
            f.max_dihedral_deg
        );
    }
    let _ = writeln!(s, "  time: {}", timings(r).join(", "));
    for n in &r.notes {
        let _ = writeln!(s, "  note: {n}");
    }
    for p in &r.problems {
        let _ = writeln!(s, "  PROBLEM: {p}");
    }
    files(&mut s, r);
    s
}

/// The 2D quality lines: the linear mesh's angles, the certified scaled Jacobian and verdict.
fn quality_2d(s: &mut String, q: &curvemesh::report::Quality, order: u8) {
    let _ = writeln!(
        s,
        "  angles of the linear mesh (cell corners, quads cut on the shorter diagonal):"
    );
    let _ = writeln!(s, "  {:<22} {:>12.1}", "max angle (deg)", q.max_angle_deg);
    let h = q.obtuse_hist;
    let _ = writeln!(
        s,
        "  obtuse triangles      95-105: {}  105-115: {}  115-125: {}  125-135: {}  >=135: {}",
        h[0], h[1], h[2], h[3], h[4]
    );
    if let (Some(sj), Some(bad), Some(certified)) =
        (q.min_scaled_jacobian, q.invalid_cells, q.certified)
    {
        let _ = writeln!(s, "  {:<22} {:>12.3}", "min scaled Jacobian", sj);
        // Gmsh numbers elements from 1 (and the .msh file's tags are these indices plus 1)
        let at = |w: &curvemesh::report::WorstCell| {
            format!("cell {} (0-based) at ({:.6}, {:.6})", w.cell, w.x, w.y)
        };
        if let Some(w) = &q.worst_cell {
            let _ = writeln!(
                s,
                "    (certified min/max of det J per cell, order {}; {})",
                order,
                at(w)
            );
        }
        if let Some(g) = &q.min_sj_gmsh {
            let _ = writeln!(
                s,
                "  {:<22} {:>12.3}\n    (min det J / det J of the straight cell at its centre; {})",
                "Gmsh's minSJ",
                g.value,
                at(g)
            );
        }
        let _ = writeln!(
            s,
            "  {:<22} {:>12}",
            "certified check",
            verdict(bad, certified)
        );
    }
}

/// The 3D quality lines: the largest dihedral angle, the certification, the histograms.
fn quality_3d(s: &mut String, q: &curvemesh::report::Quality3d) {
    // (0 when the mesh has no tetrahedron: nothing to show)
    if q.max_dihedral_deg > 0.0 {
        let _ = writeln!(
            s,
            "  {:<22} {:>12.1}",
            "max tet dihedral (deg)", q.max_dihedral_deg
        );
    }
    if let Some(v) = &q.validity {
        let _ = writeln!(
            s,
            "  {:<22} {:>12.3}\n  {:<22} {:>12}",
            "min scaled Jacobian",
            v.min_scaled_jacobian,
            "certified check",
            verdict(v.invalid_cells, v.certified)
        );
    }
    for h in &q.histograms {
        let bins: Vec<String> = h.counts.iter().map(ToString::to_string).collect();
        let edges: Vec<String> = h.upper_edges_deg.iter().map(ToString::to_string).collect();
        let _ = writeln!(
            s,
            "  {:<22} {}  (up to {} deg, above; max {:.1})",
            h.name,
            bins.join(" / "),
            edges.join(", "),
            h.max_deg
        );
    }
}

/// The stages' times in the order they ran, `total` last (the report keeps them by name;
/// a stage not listed here comes after the listed ones).
fn timings(r: &Report) -> Vec<String> {
    const ORDER: [&str; 18] = [
        "setup",
        "read",
        "surface",
        "check",
        "boundary",
        "grow",
        "linear",
        "cut",
        "measure",
        "move",
        "curving",
        "volume",
        "sensitivities",
        "describe",
        "validate",
        "validity",
        "write",
        "pictures",
    ];
    let rank = |k: &str| match k {
        "total" => usize::MAX,
        _ => ORDER.iter().position(|o| *o == k).unwrap_or(ORDER.len()),
    };
    let mut stages: Vec<(&&str, &f64)> = r.timings_s.iter().collect();
    // stable: stages of one rank keep their order by name
    stages.sort_by_key(|(k, _)| rank(k));
    stages
        .iter()
        .map(|(k, v)| format!("{k} {:.1} ms", **v * 1e3))
        .collect()
}

/// One line per file written, with the order of the mesh in it.
fn files(s: &mut String, r: &Report) {
    for f in &r.files {
        match r.meshes.iter().find(|m| &m.file == f) {
            Some(m) if m.order == 1 && r.order > 1 => {
                let _ = writeln!(s, "  wrote {f}  (order 1: linear, not order {})", r.order);
            }
            Some(m) => {
                let _ = writeln!(s, "  wrote {f}  (order {})", m.order);
            }
            None => {
                let _ = writeln!(s, "  wrote {f}");
            }
        }
    }
}

/// The certified check's verdict in words.
fn verdict(invalid: usize, certified: bool) -> String {
    match (invalid, certified) {
        (0, true) => "every cell proved valid".to_string(),
        (0, false) => "no cell proved invalid, some undecided".to_string(),
        (n, _) => format!("{n} cells INVALID"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_times_are_in_pipeline_order_with_the_total_last() {
        let mut r = Report::new("c", 3);
        for k in [
            "total", "write", "boundary", "curving", "linear", "setup", "validity",
        ] {
            r.timings_s.insert(k, 0.001);
        }
        let names: Vec<String> = timings(&r)
            .iter()
            .map(|t| t.split(' ').next().unwrap().to_string())
            .collect();
        assert_eq!(
            names,
            [
                "setup", "boundary", "linear", "curving", "validity", "write", "total"
            ]
        );
    }
}
