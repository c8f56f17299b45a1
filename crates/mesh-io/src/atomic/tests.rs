//! Tests of the atomic writes: one file, transactions that commit all or nothing, duplicate
//! outputs, and the removal of stale temporary files.

use super::*;

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn text(target: &Path, s: &'static str) -> impl FnOnce(&mut dyn Write) -> Result<(), IoError> {
    let target = target.to_path_buf();
    move |w| {
        w.write_all(s.as_bytes())
            .map_err(|e| IoError::io(&target, e))
    }
}

#[test]
fn a_successful_write_leaves_exactly_the_target() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("a.txt");
    write_atomic(&target, text(&target, "hello")).unwrap();
    assert_eq!(fs::read(&target).unwrap(), b"hello");
    assert_eq!(entries(dir.path()), vec!["a.txt"]);
}

#[test]
fn a_failed_write_leaves_the_old_file_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("a.txt");
    fs::write(&target, b"old").unwrap();
    let err = write_atomic(&target, |w| {
        w.write_all(b"partial new content").unwrap();
        Err(IoError::InvalidMesh {
            path: target.clone(),
            message: "stop".into(),
        })
    })
    .unwrap_err();
    assert!(matches!(err, IoError::InvalidMesh { .. }), "{err}");
    assert_eq!(fs::read(&target).unwrap(), b"old");
    assert_eq!(entries(dir.path()), vec!["a.txt"]);
}

#[test]
fn a_missing_directory_is_an_error_naming_the_target() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("no/such/dir/a.txt");
    let err = write_atomic(&target, |_| Ok(())).unwrap_err();
    assert!(matches!(err, IoError::Io { .. }));
    assert!(err.to_string().contains("no/such/dir/a.txt"), "{err}");
    assert!(!dir.path().join("no").exists());
}

#[test]
fn a_path_without_file_name_is_an_error() {
    let err = write_atomic(Path::new("/"), |_| Ok(())).unwrap_err();
    assert!(matches!(err, IoError::Io { .. }), "{err}");
}

#[test]
fn a_folder_as_target_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("m.msh")).unwrap();
    let err = write_atomic(&dir.path().join("m.msh"), |_| Ok(())).unwrap_err();
    assert!(err.to_string().contains("is a folder"), "{err}");
    assert_eq!(entries(dir.path()), vec!["m.msh"]);
}

#[test]
fn a_transaction_replaces_every_target_on_commit() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (
        dir.path().join("a.txt"),
        dir.path().join("sub/deeper/b.txt"),
    );
    fs::write(&a, b"old a").unwrap();
    let mut t = Transaction::creating_folders();
    let ia = t.reserve(&a).unwrap();
    let ib = t.reserve(&b).unwrap();
    assert_eq!(
        t.targets().collect::<Vec<_>>(),
        vec![a.as_path(), b.as_path()]
    );
    // both temporary files exist before any content is made; the targets are untouched
    assert_eq!(entries(dir.path()).len(), 3, "{:?}", entries(dir.path()));
    assert_eq!(fs::read(&a).unwrap(), b"old a");
    t.write(ia, text(&a, "new a")).unwrap();
    t.write(ib, text(&b, "new b")).unwrap();
    assert_eq!(
        fs::read(&a).unwrap(),
        b"old a",
        "nothing replaced before commit"
    );
    t.commit().unwrap();
    assert_eq!(fs::read(&a).unwrap(), b"new a");
    assert_eq!(fs::read(&b).unwrap(), b"new b");
    assert_eq!(entries(dir.path()), vec!["a.txt", "sub"]);
    assert_eq!(entries(&dir.path().join("sub/deeper")), vec!["b.txt"]);
}

#[test]
fn one_failed_output_leaves_every_target_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.txt"), dir.path().join("new/b.txt"));
    fs::write(&a, b"old a").unwrap();
    let mut t = Transaction::creating_folders();
    let ia = t.reserve(&a).unwrap();
    let ib = t.reserve(&b).unwrap();
    t.write(ia, text(&a, "new a")).unwrap();
    let err = t
        .write(ib, |_| Err(IoError::io(&b, io::Error::other("disk full"))))
        .unwrap_err();
    assert!(err.to_string().contains("disk full"), "{err}");
    drop(t);
    assert_eq!(fs::read(&a).unwrap(), b"old a");
    // the folder `new` was made by the transaction and is removed again
    assert_eq!(entries(dir.path()), vec!["a.txt"]);
}

#[test]
fn an_unwritable_folder_fails_at_reservation_before_any_content() {
    // A regular file where a folder should be: refused for root too (unlike permissions).
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.txt");
    fs::write(dir.path().join("ro"), b"a file").unwrap();
    let mut t = Transaction::creating_folders();
    t.reserve(&a).unwrap();
    let err = t.reserve(&dir.path().join("ro/p.png")).unwrap_err();
    assert!(matches!(err, IoError::Io { .. }), "{err}");
    assert!(err.to_string().contains("ro"), "{err}");
    drop(t);
    assert_eq!(entries(dir.path()), vec!["ro"]);
}

#[test]
fn an_output_never_written_blocks_the_commit() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
    let mut t = Transaction::new();
    let ia = t.reserve(&a).unwrap();
    t.reserve(&b).unwrap();
    t.write(ia, text(&a, "a")).unwrap();
    let err = t.commit().unwrap_err();
    assert!(matches!(err, IoError::Unwritten { .. }), "{err}");
    assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
}

#[test]
fn two_outputs_on_one_file_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("d")).unwrap();
    let a = dir.path().join("d/m.msh");
    let same = dir.path().join("d/../d/./m.msh");
    let mut t = Transaction::new();
    t.reserve(&a).unwrap();
    let err = t.reserve(&same).unwrap_err();
    match &err {
        IoError::DuplicateOutput { first, .. } => assert_eq!(first, &a),
        other => panic!("{other}"),
    }
    drop(t);
    assert!(entries(&dir.path().join("d")).is_empty());
}

#[test]
fn temporary_names_are_recognised() {
    assert_eq!(temporary_pid(".m.msh.tmp-123-4"), Some(123));
    assert_eq!(temporary_pid(".a.tmp-b.tmp-77-0"), Some(77));
    for not_ours in [
        "m.msh.tmp-1-2",
        ".m.msh.tmp-1",
        ".m.msh.tmp-x-1",
        ".m.tmp-1-",
        ".m",
    ] {
        assert_eq!(temporary_pid(not_ours), None, "{not_ours}");
    }
}

#[test]
fn stale_temporaries_of_dead_processes_are_removed() {
    let dir = tempfile::tempdir().unwrap();
    // a pid above Linux's largest (2^22) belongs to no process; pid 1 is always alive
    let dead = dir.path().join(".m.msh.tmp-99999999-3");
    let alive = dir.path().join(".m.msh.tmp-1-3");
    let other = dir.path().join("keep.tmp-99999999-3");
    for p in [&dead, &alive, &other] {
        fs::write(p, b"x").unwrap();
    }
    let target = dir.path().join("m.msh");
    write_atomic(&target, text(&target, "mesh")).unwrap();
    let left = entries(dir.path());
    if cfg!(target_os = "linux") {
        assert_eq!(left, vec![".m.msh.tmp-1-3", "keep.tmp-99999999-3", "m.msh"]);
    } else {
        assert!(left.contains(&".m.msh.tmp-99999999-3".to_string()));
    }
}

#[test]
fn a_failed_sync_behind_the_writer_leaves_the_old_file_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("m.msh");
    fs::write(&target, b"old").unwrap();
    let mut t = Transaction::new();
    let id = t.reserve(&target).unwrap();
    let err = t
        .write_via(
            id,
            text(&target, "new content, longer than one step"),
            |f| SyncBehind::with_step(f, 8, |_| Err(io::Error::other("the disk refused"))),
        )
        .unwrap_err();
    assert!(err.to_string().contains("m.msh"), "{err}");
    assert!(err.to_string().contains("the disk refused"), "{err}");
    assert!(matches!(t.commit(), Err(IoError::Unwritten { .. })));
    assert_eq!(fs::read(&target).unwrap(), b"old");
    assert_eq!(entries(dir.path()), vec!["m.msh"]);
}
