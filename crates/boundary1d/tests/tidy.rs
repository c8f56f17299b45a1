//! Every source file of this crate opens with a `//!` paragraph saying what it owns.

#[test]
fn every_module_opens_with_a_doc_paragraph() {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut checked = 0;
    for entry in std::fs::read_dir(&src).expect("src folder") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&path).expect("readable");
            assert!(
                text.trim_start().starts_with("//!"),
                "{} does not open with a //! paragraph",
                path.display()
            );
            checked += 1;
        }
    }
    assert!(checked >= 3, "only {checked} files found");
}
