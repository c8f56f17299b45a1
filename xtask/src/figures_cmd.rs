//! `cargo xtask figures`: regenerates every figure of the README and `docs/user-guide.md`, and
//! those of `docs/3d.md` and `docs/movement.md` that a command draws, from real runs of `mesh`,
//! `move` and `quality` (the same code as the commands, run in-process), into
//! `docs/figures/` by default. Meshes made on the way go to a scratch folder that is removed at
//! the end; only the pictures are kept. The list of figures is [`FIGURES`]; the docs test
//! (`xtask/tests/integration/docs_examples.rs`) checks that the README and the guide show no
//! other figure and that every one of these is shown.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::cli::FiguresArgs;
use curvemesh_cli::{Finished, Outcome, entry};

use crate::CARGO_XTASK;

/// Width of every figure in pixels: small files, sharp enough on a page.
pub const WIDTH: &str = "900";

/// The case file the guide's figures are made from, relative to the repository root.
const EXAMPLE_CASE: &str = "fixtures/cases/example.toml";

/// The runs that make the figures, in order: each is a command line of `cargo xtask` in which
/// `{fig}` stands for the figures folder and `{tmp}` for the scratch folder.
pub const FIGURES: &[&[&str]] = &[
    // README: the 30P30N at P3 near the slat cove
    &[
        "mesh",
        "30p30n",
        "--order",
        "3",
        "--out",
        "{tmp}/30p30n.msh",
        "--png",
        "{fig}/30p30n-p3-slat-cove.png@slat-cove",
    ],
    // guide: the example case, whole and at the leading edge
    &[
        "mesh",
        EXAMPLE_CASE,
        "--out",
        "{tmp}/example.msh",
        "--png",
        "{fig}/example-walls.png@walls",
        "--png",
        "{fig}/example-le.png@le",
    ],
    // guide: the angle colouring at the trailing edge of the linear mesh
    &[
        "mesh",
        "naca0012",
        "--order",
        "1",
        "--out",
        "{tmp}/naca0012-p1.msh",
        "--colour",
        "angle",
        "--png",
        "{fig}/naca0012-p1-te-angle.png@te",
    ],
    // guide: the certified scaled Jacobian of the P3 30P30N in the flap gap
    &[
        "mesh",
        "30p30n",
        "--order",
        "3",
        "--out",
        "{tmp}/30p30n-jac.msh",
        "--colour",
        "jacobian",
        "--png",
        "{fig}/30p30n-p3-flap-gap-jacobian.png@flap-gap",
    ],
    // guide (3D): the step cut through its tower, the cells by type
    &[
        "mesh",
        "step",
        "--out",
        "{tmp}/step.msh",
        "--slice",
        "x=0.5",
        "--png",
        "{fig}/step-slice-x.png@-0.25,-0.25,1.25,1.15",
    ],
    // guide (3D): the wing cut at mid-span, its trailing edge, the tetrahedra by their
    // largest dihedral angle
    &[
        "mesh",
        "wing",
        "--out",
        "{tmp}/wing.msh",
        "--slice",
        "z=1",
        "--colour",
        "dihedral",
        "--png",
        "{fig}/wing-te-dihedral.png@0.9,-0.075,1.1,0.075",
    ],
    // 3D docs: the capsule's fin junction, cut across the fin
    &[
        "mesh",
        "fixtures/cases3d/capsule-fin.toml",
        "--out",
        "{tmp}/capsule-fin.msh",
        "--slice",
        "x=0.85",
        "--png",
        "{fig}/capsule-fin-slice-x.png@-0.35,0.05,0.35,0.55",
    ],
    // 3D docs: the swept wing's far tip, cut through its chord plane
    &[
        "mesh",
        "fixtures/cases3d/swept-wing.toml",
        "--out",
        "{tmp}/swept-wing.msh",
        "--slice",
        "y=0.005",
        "--png",
        "{fig}/swept-wing-tip-slice-y.png@1.2,0.45,1.75,1.25",
    ],
    // 3D docs: two spheres in a far field, cut through the gap between them: the layers
    // stopped where the fronts face each other, the fill between
    &[
        "mesh",
        "fixtures/cases/two-spheres.toml",
        "--out",
        "{tmp}/two-spheres.msh",
        "--slice",
        "z=0",
        "--colour",
        "layer",
        "--png",
        "{fig}/two-spheres-gap-slice-z.png@-1.5,-1,1.5,1",
    ],
    // 3D docs: the two cubes' hexahedral layers, their pyramid caps and the fill
    &[
        "mesh",
        "fixtures/cases/two-cubes.toml",
        "--out",
        "{tmp}/two-cubes.msh",
        "--slice",
        "z=0.0625",
        "--png",
        "{fig}/two-cubes-gap-slice-z.png@-0.35,-0.75,0.35,-0.25",
    ],
    // 3D docs: the 30P30N's extruded elements cut at mid-span through the slat cove, by the
    // tets' largest dihedral angle
    &[
        "mesh",
        "fixtures/cases/30p30n-3d.toml",
        "--order",
        "1",
        "--out",
        "{tmp}/30p30n-3d.msh",
        "--slice",
        "z=0",
        "--colour",
        "dihedral",
        "--png",
        "{fig}/30p30n-3d-slat-cove-slice-z.png@-0.06,-0.11,0.08,-0.005",
    ],
    // 3D docs: the wing in a far-field sphere at mid-span, layers to isotropic, then the fill
    &[
        "mesh",
        "fixtures/cases/wing-sphere.toml",
        "--out",
        "{tmp}/wing-sphere.msh",
        "--slice",
        "z=0",
        "--colour",
        "layer",
        "--png",
        "{fig}/wing-sphere-slice-z.png@-0.6,-0.7,1.9,0.7",
    ],
    // movement docs: the flap gap after the slat and the flap turned 10° each, by Jacobian
    &[
        "move",
        "30p30n",
        "--motion",
        "fixtures/motions/30p30n-slat-flap10.toml",
        "--out",
        "{tmp}/30p30n-slat-flap.msh",
        "--colour",
        "jacobian",
        "--png",
        "{fig}/30p30n-p3-slat-flap-moved-gap.png@flap-gap",
    ],
    // guide: `quality` drawing a .msh file
    &[
        "quality",
        "{tmp}/example.msh",
        "--png",
        "{fig}/quality-example-le.png@-0.03,-0.03,0.05,0.03",
    ],
];

/// The file names of the figures [`FIGURES`] makes.
pub fn names() -> Vec<String> {
    FIGURES
        .iter()
        .flat_map(|run| run.iter())
        .filter_map(|a| a.strip_prefix("{fig}/"))
        .map(|a| a.split('@').next().unwrap_or(a).to_string())
        .collect()
}

/// Runs `cargo xtask figures`.
pub fn run(args: &FiguresArgs) -> Result<Finished> {
    if !Path::new(EXAMPLE_CASE).is_file() {
        bail!("figures: run from the repository root ({EXAMPLE_CASE} not found here)");
    }
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("figures: cannot make {}", args.dir.display()))?;
    let tmp = std::env::temp_dir().join(format!("curvemesh-figures-{}", std::process::id()));
    std::fs::create_dir_all(&tmp)
        .with_context(|| format!("figures: cannot make {}", tmp.display()))?;
    let made = make_all(&args.dir, &tmp, args.quiet);
    let _ = std::fs::remove_dir_all(&tmp);
    made?;
    if !args.quiet {
        for name in names() {
            println!("{}", args.dir.join(name).display());
        }
    }
    Ok(Finished::valid())
}

fn make_all(fig: &Path, tmp: &Path, quiet: bool) -> Result<()> {
    for run in FIGURES {
        let line = command_line(run, fig, tmp);
        if !quiet {
            eprintln!("figures: {CARGO_XTASK} {}", line.join(" "));
        }
        let mut argv = vec![CARGO_XTASK.to_string()];
        argv.extend(line.iter().cloned());
        argv.push("--width".into());
        argv.push(WIDTH.into());
        argv.push("--quiet".into());
        // every figure is a `curvemesh` command (mesh, move, quality)
        let cli = entry::parse::<curvemesh_cli::cli::Cli, _, _>(CARGO_XTASK, argv)
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        let finished =
            curvemesh_cli::run(cli).with_context(|| format!("figures: {}", line.join(" ")))?;
        if finished.outcome != Outcome::Valid {
            bail!(
                "figures: {}: {}",
                line.join(" "),
                finished.problem.unwrap_or_default()
            );
        }
    }
    Ok(())
}

fn command_line(run: &[&str], fig: &Path, tmp: &Path) -> Vec<String> {
    let (fig, tmp): (PathBuf, PathBuf) = (fig.into(), tmp.into());
    run.iter()
        .map(|a| {
            a.replace("{fig}", &fig.to_string_lossy())
                .replace("{tmp}", &tmp.to_string_lossy())
        })
        .collect()
}
