//! The report's notes say where and what to do: on the default case (the 30P30N) the layers
//! whose spring balance stopped at its limit are named, and no wall facet is left without
//! layers (the main element's cove corner is layered); on the bat, meshed inside, the facets
//! its narrow wing tips leave without layers are located.

use end_to_end::{Outcome, read_json, run_into};

fn notes_of(case: &str) -> Vec<String> {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run_into(dir.path(), "d", "mesh", case, &["--order", "1"]).unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let report = read_json(&dir.path().join("d.json"));
    report["notes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect()
}

#[test]
fn the_default_cases_notes_say_where() {
    let notes = notes_of("30p30n");
    assert!(
        !notes
            .iter()
            .any(|n| n.contains("wall facets have no layers")),
        "{notes:?}"
    );
    if let Some(limit) = notes.iter().find(|n| n.contains("iteration limit")) {
        assert!(limit.contains("layer"), "{limit}");
        assert!(
            limit.chars().any(|c| c.is_ascii_digit()),
            "no layer named: {limit}"
        );
    }
}

#[test]
fn bare_wall_facets_are_located() {
    let notes = notes_of("bat");
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
