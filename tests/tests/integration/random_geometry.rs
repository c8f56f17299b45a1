//! The random-geometry family: geometries of the kinds users bring (stars with corners, smooth
//! Fourier curves, NACA sections at random angles, two to four bodies with gaps of 1e-3 … 0.1 of the size, shapes
//! meshed inside; scales 1e-3 … 1e3, first heights 1e-7 … 1e-2 of the size, growths 1.1–1.5),
//! each run through the whole pipeline (`cargo xtask mesh`, in-process) at P1 and P3 and the
//! result checked independently of the report: the `.msh` read back is structurally valid
//! (indices, exact orientation, conforming edges), every cell is certified valid by the
//! Bernstein check, the cells' area equals the area the boundary encloses, and no triangle
//! (quads cut on the shorter diagonal) reaches 150°. A run may instead refuse its
//! input with one line and exit 1 (a gap too narrow for the first height, say), which is
//! counted and shown; it may never write an invalid mesh or panic.
//!
//! `RANDOM_GEOMETRY_CASES=N` sets the number of geometries per kind (default 6 in the normal
//! test run, each at P1 and P3); `RANDOM_GEOMETRY_SEED=S` the first seed. A failure prints
//! the case file, so it can be run again with `cargo xtask mesh case.toml`.

use crate::checked_run;

use std::fmt::Write as _;

use checked_run::{Verdict, run_and_check};

/// A small deterministic generator (xorshift64*), so that a seed names a case for good.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// 10^u, u uniform in [lo, hi).
    fn log(&mut self, lo: f64, hi: f64) -> f64 {
        10f64.powf(self.range(lo, hi))
    }
    fn int(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.next() % (hi - lo + 1)
    }
}

/// The kinds of geometry of the family.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Star,
    Fourier,
    Naca,
    MultiBody,
    Inside,
}

const KINDS: [Kind; 5] = [
    Kind::Star,
    Kind::Fourier,
    Kind::Naca,
    Kind::MultiBody,
    Kind::Inside,
];

/// A case file of `kind` drawn from `rng`, with its description.
fn random_case(kind: Kind, rng: &mut Rng) -> String {
    let scale = rng.log(-3.0, 3.0);
    let mut toml = String::new();
    let size = match kind {
        Kind::Star => {
            let pts = star(rng, scale, [0.0, 0.0]);
            push_points_loop(&mut toml, "wall", &pts);
            scale
        }
        Kind::Fourier => {
            let pts = fourier(rng, scale, [0.0, 0.0]);
            push_points_loop(&mut toml, "wall", &pts);
            scale
        }
        Kind::Naca => {
            push_naca_loop(&mut toml, rng, scale, [0.0, 0.0]);
            scale
        }
        Kind::MultiBody => multi_body(&mut toml, rng, scale),
        Kind::Inside => {
            toml.insert_str(0, "inside = true\n");
            let pts = if rng.int(0, 1) == 0 {
                star(rng, scale, [0.0, 0.0])
            } else {
                fourier(rng, scale, [0.0, 0.0])
            };
            push_points_loop(&mut toml, "wall", &pts);
            scale
        }
    };
    if !matches!(kind, Kind::Inside) {
        let _ = write!(
            toml,
            "[[loop]]\nrole = \"farfield\"\ncircle = {{ center = [0.0, 0.0], radius = {:e} }}\n\n",
            20.0 * size
        );
    }
    let first_height = size * rng.log(-7.0, -2.0);
    let _ = write!(
        toml,
        "[boundary]\ngrowth = {:.3}\nmax_spacing = {:e}\n\n[layers]\nfirst_height = {:e}\ngrowth = {:.3}\n",
        rng.range(1.1, 1.3),
        size,
        first_height,
        rng.range(1.1, 1.5)
    );
    toml.insert_str(0, &format!("name = \"random-{kind:?}\"\n"));
    toml
}

/// A star of 5–9 tips with sharp corners (alternating radii), radius about `scale`/2.
fn star(rng: &mut Rng, scale: f64, c: [f64; 2]) -> Vec<[f64; 2]> {
    let tips = rng.int(5, 9) as usize;
    let inner = rng.range(0.45, 0.8);
    let turn = rng.range(0.0, std::f64::consts::TAU);
    (0..2 * tips)
        .map(|i| {
            let a = turn + std::f64::consts::PI * i as f64 / tips as f64;
            let r = 0.5 * scale * if i % 2 == 0 { 1.0 } else { inner };
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

/// A smooth closed curve `r(θ) = 1 + Σ a_k cos kθ + b_k sin kθ`, k = 2…5, star-shaped and
/// of bounded curvature, about `scale` across.
fn fourier(rng: &mut Rng, scale: f64, c: [f64; 2]) -> Vec<[f64; 2]> {
    let coef: Vec<(f64, f64)> = (2..=5)
        .map(|k| {
            let amp = 0.25 / (k * k) as f64;
            (rng.range(-amp, amp), rng.range(-amp, amp))
        })
        .collect();
    let n = 48;
    (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let mut r = 1.0;
            for (j, (a, b)) in coef.iter().enumerate() {
                let k = (j + 2) as f64;
                r += a * (k * t).cos() + b * (k * t).sin();
            }
            let r = 0.5 * scale * r;
            [c[0] + r * t.cos(), c[1] + r * t.sin()]
        })
        .collect()
}

fn push_points_loop(toml: &mut String, role: &str, pts: &[[f64; 2]]) {
    let list: Vec<String> = pts
        .iter()
        .map(|p| format!("[{:e}, {:e}]", p[0], p[1]))
        .collect();
    let _ = write!(
        toml,
        "[[loop]]\nrole = \"{role}\"\npoints = [{}]\n\n",
        list.join(", ")
    );
}

/// A NACA 4-digit section of chord `scale`, rotated by ±30°, its leading edge at `at`.
fn push_naca_loop(toml: &mut String, rng: &mut Rng, scale: f64, at: [f64; 2]) {
    let m = rng.int(0, 6);
    let p = if m == 0 { 0 } else { rng.int(2, 6) };
    let t = rng.int(6, 24);
    let _ = write!(
        toml,
        "[[loop]]\nrole = \"wall\"\nnaca = \"{m}{p}{t:02}\"\nscale = {scale:e}\nrotate_deg = {:.2}\ntranslate = [{:e}, {:e}]\n\n",
        rng.range(-30.0, 30.0),
        at[0],
        at[1]
    );
}

/// Two to four circles, ellipses or tandem sections in a row, `gap` (1e-3 … 0.1 of the
/// size) apart; returns the size of the group.
fn multi_body(toml: &mut String, rng: &mut Rng, scale: f64) -> f64 {
    let bodies = rng.int(2, 4) as usize;
    let mut x = 0.0;
    for _ in 0..bodies {
        let gap = scale * rng.log(-3.0, -1.0);
        match rng.int(0, 2) {
            0 => {
                let r = 0.5 * scale * rng.range(0.3, 1.0);
                let _ = write!(
                    toml,
                    "[[loop]]\nrole = \"wall\"\ncircle = {{ center = [{:e}, 0.0], radius = {r:e} }}\n\n",
                    x + r
                );
                x += 2.0 * r + gap;
            }
            1 => {
                // an axis-aligned ellipse: its nearest points to the next body lie on the axis
                let (a, b) = (0.5 * scale, 0.5 * scale * rng.range(0.3, 0.9));
                let n = 64;
                let pts: Vec<[f64; 2]> = (0..n)
                    .map(|i| {
                        let t = std::f64::consts::TAU * i as f64 / n as f64;
                        [x + a + a * t.cos(), b * t.sin()]
                    })
                    .collect();
                push_points_loop(toml, "wall", &pts);
                x += 2.0 * a + gap;
            }
            _ => {
                let m = rng.int(0, 4);
                let p = if m == 0 { 0 } else { rng.int(2, 6) };
                let t = rng.int(8, 18);
                let _ = write!(
                    toml,
                    "[[loop]]\nrole = \"wall\"\nnaca = \"{m}{p}{t:02}\"\nscale = {scale:e}\ntranslate = [{x:e}, 0.0]\n\n"
                );
                x += scale + gap;
            }
        }
    }
    x
}

fn env_or(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn random_geometries_mesh_valid_or_refuse_in_one_line() {
    let per_kind = env_or("RANDOM_GEOMETRY_CASES", 6);
    let first_seed = env_or("RANDOM_GEOMETRY_SEED", 1);
    let dir = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    let mut table = String::new();
    for kind in KINDS {
        let (mut valid, mut refused) = (0, Vec::new());
        let (mut worst, mut over_135) = (0.0f64, 0);
        for seed in first_seed..first_seed + per_kind {
            let mut rng = Rng::new(seed * 31 + kind as u64);
            let toml = random_case(kind, &mut rng);
            let case = dir.path().join("case.toml");
            std::fs::write(&case, &toml).unwrap();
            for order in [1, 3] {
                match run_and_check(dir.path(), &case, order, 150.0) {
                    Ok(Verdict::Valid(angle)) => {
                        valid += 1;
                        worst = worst.max(angle);
                        if angle >= 135.0 {
                            over_135 += 1;
                            eprintln!("{kind:?} seed {seed} P{order}: {angle:.1}°");
                        }
                    }
                    Ok(Verdict::Refused(msg)) => {
                        refused.push(format!("seed {seed} P{order}: {msg}"))
                    }
                    Err(why) => failures.push(format!(
                        "{kind:?} seed {seed} P{order}: {why}\n--- case.toml ---\n{toml}"
                    )),
                }
            }
        }
        let _ = writeln!(
            table,
            "{kind:?}: {valid} valid (worst angle {worst:.1}°, {over_135} at 135° or more), {} refused{}",
            refused.len(),
            refused
                .iter()
                .map(|r| format!("\n    {r}"))
                .collect::<String>()
        );
    }
    eprintln!("{table}");
    assert!(
        failures.is_empty(),
        "{} of the random runs failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
