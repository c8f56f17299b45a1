//! The report's notes: the default case (the 30P30N) has none (every wall facet layered,
//! every spring balance converged); on the bat, meshed inside, the facets its narrow wing
//! tips leave without layers are located, with what to change.

use end_to_end::{Outcome, read_json, run_into};

/// The notes of `mesh CASE FLAGS`.
fn notes_of(case: &str, flags: &[&str]) -> Vec<String> {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run_into(dir.path(), "d", "mesh", case, flags).unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let report = read_json(&dir.path().join("d.json"));
    report["notes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect()
}

/// The default case runs clean: no wall facet without layers (the main element's cove
/// corner is layered) and every spring balance converged, so no note at all.
#[test]
fn the_default_case_runs_without_notes() {
    // at the case's own order (P3), as the README's first command runs it
    let notes = notes_of("30p30n", &[]);
    assert!(notes.is_empty(), "{notes:?}");
}

#[test]
fn bare_wall_facets_are_located() {
    let notes = notes_of("bat", &["--order", "1"]);
    let bare = notes
        .iter()
        .find(|n| n.contains("wall facets have no layers"))
        .expect("the bat's wing tips' note");
    assert!(bare.contains("at (-29.99"), "{bare}");
    assert!(
        bare.contains("first_height") && bare.contains("max_spacing"),
        "{bare}"
    );
}
