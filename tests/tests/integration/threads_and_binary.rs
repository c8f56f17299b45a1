//! `--threads N` and `--binary`: the files written do not depend on the number of threads,
//! and a binary `.msh` holds the very mesh the text one does.

use clap::Parser;
use curvemesh_cli::cli::Cli;
use end_to_end::{Outcome, assert_one_line_naming, mesh, s};

#[test]
fn one_and_two_threads_write_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let (mut files, mut reports) = (Vec::new(), Vec::new());
    for threads in ["1", "2"] {
        let (msh, vtu, bin) = (
            dir.path().join(format!("t{threads}.msh")),
            dir.path().join(format!("t{threads}.vtu")),
            dir.path().join(format!("t{threads}-binary.msh")),
        );
        let report = dir.path().join(format!("t{threads}.json"));
        // P3 naca0012: some 80 000 nodes, many chunks of the parallel writers; the mesh is
        // written while the report certifies it
        for (out, binary) in [(&msh, false), (&vtu, false), (&bin, true)] {
            let mut rest = vec!["--threads", threads, "--out", s(out)];
            if binary {
                rest.push("--binary");
            } else {
                rest.extend(["--report", s(&report)]);
            }
            assert_eq!(mesh("naca0012", "3", &rest).unwrap(), Outcome::Valid);
        }
        files.push([msh, vtu, bin].map(|p| std::fs::read(p).unwrap()));
        // the report's measures (angle histogram, certified Jacobians, area) too
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
        reports.push([&json["quality"], &json["area"]].map(Clone::clone));
    }
    for (k, (one, two)) in files[0].iter().zip(&files[1]).enumerate() {
        assert!(one == two, "file {k} differs between 1 and 2 threads");
    }
    assert_eq!(reports[0], reports[1]);
    assert!(reports[0][0]["obtuse_hist"].is_array(), "{:?}", reports[0]);
}

#[test]
fn a_binary_msh_reads_back_as_the_text_one() {
    let dir = tempfile::tempdir().unwrap();
    let (text, binary) = (dir.path().join("t.msh"), dir.path().join("b.msh"));
    let ok = |rest: &[&str]| assert_eq!(mesh("lshape", "2", rest).unwrap(), Outcome::Valid);
    ok(&["--out", s(&text)]);
    ok(&["--out", s(&binary), "--binary"]);
    let bytes = std::fs::read(&binary).unwrap();
    assert!(bytes.starts_with(b"$MeshFormat\n4.1 1 8\n"));
    assert!(bytes.len() < std::fs::metadata(&text).unwrap().len() as usize);
    let (a, b) = (
        mesh_io::read_msh(&text).unwrap(),
        mesh_io::read_msh(&binary).unwrap(),
    );
    assert_eq!(a, b);
}

#[test]
fn binary_without_an_msh_output_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let vtu = dir.path().join("t.vtu");
    let err = mesh("lshape", "1", &["--out", s(&vtu), "--binary"]).unwrap_err();
    let msg = format!("{err:#}");
    assert!(msg.contains("--binary") && msg.contains(".msh"), "{msg}");
    assert!(!msg.contains('\n'), "{msg}");
    assert!(!vtu.exists());
}

#[test]
fn zero_threads_is_refused_in_one_line() {
    let err = Cli::try_parse_from(["cargo xtask", "mesh", "lshape", "--threads", "0"])
        .expect_err("clap refuses --threads 0");
    let e = curvemesh_cli::exit::of_usage_error(&err).expect("a usage error");
    assert_eq!(e.code, 1, "{e:?}");
    assert_one_line_naming(e.stderr.as_deref().unwrap(), &["--threads", "0"]);
}
