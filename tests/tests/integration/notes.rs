//! The report's notes say where and what to do: on the default case (the 30P30N), the wall
//! facets left without layers are located (the main element's cove corner at (0.700, 0.032))
//! and the layers whose spring balance stopped at its limit are named.

use end_to_end::{Outcome, read_json, run_into};

#[test]
fn the_default_cases_notes_say_where() {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run_into(dir.path(), "d", "mesh", "30p30n", &["--order", "1"]).unwrap();
    assert_eq!(outcome, Outcome::Valid);
    let report = read_json(&dir.path().join("d.json"));
    let notes: Vec<&str> = report["notes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    let bare = notes
        .iter()
        .find(|n| n.contains("wall facets have no layers"))
        .expect("the cove corner's note");
    assert!(bare.contains("at (0.700000, 0.0320"), "{bare}");
    assert!(
        bare.contains("first_height") && bare.contains("max_spacing"),
        "{bare}"
    );
    if let Some(limit) = notes.iter().find(|n| n.contains("iteration limit")) {
        assert!(limit.contains("layer"), "{limit}");
        assert!(
            limit.chars().any(|c| c.is_ascii_digit()),
            "no layer named: {limit}"
        );
    }
}
