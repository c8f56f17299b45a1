//! The library as a caller uses it, in-process: a case meshed and certified with its stages
//! told to the observer in pairs, 2D and 3D; bad input as an error of the right kind; a
//! case moved with its sensitivities, one per node and design variable.

use curvemesh::movement::{MoveOptions, Prepared, motion, move_case};
use curvemesh::{AnyCase, ErrorKind, Observer, Options};

/// Records what the library tells an observer.
#[derive(Default)]
struct Log {
    begun: Vec<String>,
    ended: Vec<String>,
    open: usize,
}

impl Observer for Log {
    fn stage_begun(&mut self, what: &str) {
        assert_eq!(self.open, 0, "{what} begun inside another stage");
        self.open += 1;
        self.begun.push(what.to_string());
    }
    fn stage_ended(&mut self, what: &str, seconds: f64) {
        assert!(seconds >= 0.0);
        self.open -= 1;
        self.ended.push(what.to_string());
    }
}

#[test]
fn a_2d_case_is_meshed_certified_and_its_stages_told_in_pairs() {
    let case = curvemesh::load("lshape").unwrap();
    let mut log = Log::default();
    let options = Options {
        order: Some(3),
        snapshot: true,
        ..Options::default()
    };
    let meshed = curvemesh::mesh(&case, &options, &mut log).unwrap();
    assert!(meshed.report.is_valid(), "{:?}", meshed.report.problems);
    assert_eq!(meshed.mesh.order, 3);
    assert_eq!(meshed.scaled_jacobian.len(), meshed.mesh.cells.len());
    assert!(meshed.scaled_jacobian.iter().all(|&j| j > 0.0));
    assert!(meshed.snapshot.is_some());
    assert_eq!(log.begun, log.ended);
    for stage in ["linear layered mesh (AFSF)", "curving (Vector-Adding)"] {
        assert!(
            log.begun.iter().any(|s| s == stage),
            "{stage}: {:?}",
            log.begun
        );
    }
    assert!(meshed.report.json().is_ok());
}

#[test]
fn a_3d_case_is_meshed_with_its_stages_told() {
    let case = curvemesh::load("step").unwrap();
    assert!(matches!(case, AnyCase::Three(_)));
    let mut log = Log::default();
    let meshed = curvemesh::mesh(&case, &Options::default(), &mut log).unwrap();
    assert!(meshed.report.is_valid(), "{:?}", meshed.report.problems);
    assert_eq!(meshed.report.dimension, 3);
    assert_eq!(log.begun, log.ended);
    assert!(
        log.begun.iter().any(|s| s == "layers (AFSF 3D)"),
        "{:?}",
        log.begun
    );
    // options that mean nothing in 3D are refused
    let bad = Options {
        triangles: true,
        ..Options::default()
    };
    let e = curvemesh::mesh(&case, &bad, &mut curvemesh::Silent).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Input);
    assert!(e.to_string().contains("--triangles"), "{e}");
}

#[test]
fn bad_input_is_an_error_of_its_kind_on_one_line() {
    let e = curvemesh::load("/no/such/case.toml").unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NotFound, "{e}");
    assert!(
        e.to_string()
            .starts_with("cannot read case file /no/such/case.toml"),
        "{e}"
    );
    let e = curvemesh::load("no-such-builtin").unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Input);
    let text = "[[loop]]\nnaca = \"0012\"\nrole = \"wall\"\n[layers]\ngrowth = 0.5\n";
    let e = curvemesh::load::parse_str(text).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Input);
    assert!(!e.to_string().contains('\n'), "{e}");
    let case = curvemesh::load("naca0012").unwrap();
    let e = curvemesh::mesh(
        &case,
        &Options {
            order: Some(4),
            ..Options::default()
        },
        &mut curvemesh::Silent,
    )
    .unwrap_err();
    assert!(e.to_string().contains("order 4"), "{e}");
}

#[test]
fn a_moved_case_has_one_sensitivity_per_node_and_variable() {
    let case = curvemesh::load::load_2d("naca0012").unwrap();
    let text = "[[motion]]\nloop = \"naca0012\"\nrotate_deg = 3.0\nabout = [0.25, 0.0]\n";
    let motions = motion::parse_str(text, "pitch.toml").unwrap();
    let options = MoveOptions {
        order: Some(2),
        sensitivities: true,
        ..MoveOptions::default()
    };
    let moved = move_case(&case, &motions, None, &options, &mut curvemesh::Silent).unwrap();
    assert!(moved.report.is_valid(), "{:?}", moved.report.problems);
    // the transposed product (for adjoints) against the forward one: v · (dX/dα · dα)
    let v: Vec<[f64; 2]> = moved
        .mesh
        .nodes
        .iter()
        .map(|p| [p[1] - 0.1, 0.3 * p[0] + 1.0])
        .collect();
    let adjoint = moved.transposed_product(&v).expect("sensitivities");
    assert!(moved.transposed_product(&v[1..]).is_none());
    let columns = moved.sensitivities.expect("sensitivities");
    let dalpha: Vec<f64> = (0..columns.len()).map(|i| 0.5 + i as f64).collect();
    let forward: f64 = v
        .iter()
        .enumerate()
        .map(|(n, v)| {
            let dx = columns
                .iter()
                .zip(&dalpha)
                .fold([0.0, 0.0], |a, ((_, c), d)| {
                    [a[0] + d * c[n][0], a[1] + d * c[n][1]]
                });
            v[0] * dx[0] + v[1] * dx[1]
        })
        .sum();
    let backward: f64 = adjoint.iter().zip(&dalpha).map(|(a, d)| a * d).sum();
    assert!(
        (forward - backward).abs() <= 1e-10 * forward.abs().max(1.0),
        "{forward} {backward}"
    );
    assert!(
        columns
            .iter()
            .any(|(name, _)| name == "naca0012.rotate_deg"),
        "{columns:?}"
    );
    for (_, column) in &columns {
        assert_eq!(column.len(), moved.mesh.nodes.len());
    }
    let movement = moved.report.movement.as_ref().expect("the movement block");
    assert_eq!(movement.method, "springs");
    // a motion that names no loop of the case is refused before any meshing
    let wrong = motion::parse_str("[[motion]]\nloop = \"flap\"\nrotate_deg = 1.0\n", "m").unwrap();
    let e = move_case(&case, &wrong, None, &options, &mut curvemesh::Silent).unwrap_err();
    assert!(e.to_string().contains("flap"), "{e}");
}

#[test]
fn a_prepared_case_moves_as_a_fresh_move_does_in_any_order() {
    let case = curvemesh::load::load_2d("naca0012").unwrap();
    let options = MoveOptions {
        order: Some(2),
        ..MoveOptions::default()
    };
    let pitch = |degrees: f64| {
        let text = format!("[[motion]]\nloop = \"naca0012\"\nrotate_deg = {degrees}\n");
        motion::parse_str(&text, "pitch.toml").unwrap()
    };
    let prepared = Prepared::new(&case, None, &options, &mut curvemesh::Silent).unwrap();
    // a motion the case cannot take is refused and leaves the prepared case as it was
    let wrong = motion::parse_str("[[motion]]\nloop = \"flap\"\nrotate_deg = 1.0\n", "m").unwrap();
    let e = prepared
        .move_by(&wrong, &mut curvemesh::Silent)
        .unwrap_err();
    assert!(e.to_string().contains("flap"), "{e}");
    for degrees in [12.0, -4.0, 12.0] {
        let motions = pitch(degrees);
        let again = prepared.move_by(&motions, &mut curvemesh::Silent).unwrap();
        let fresh = move_case(&case, &motions, None, &options, &mut curvemesh::Silent).unwrap();
        assert!(again.report.is_valid(), "{:?}", again.report.problems);
        assert_eq!(again.mesh.cells, fresh.mesh.cells);
        // the same balance, to the Newton solve's tolerance (10⁻¹⁰ of a node's edges)
        let apart = again
            .mesh
            .nodes
            .iter()
            .zip(&fresh.mesh.nodes)
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .fold(0.0, f64::max);
        assert!(apart < 1e-12, "{degrees}°: {apart:e} apart");
    }
}
