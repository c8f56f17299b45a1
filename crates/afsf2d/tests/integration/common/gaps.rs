//! Random multi-body domains with narrow gaps, built the way the pipeline builds its loops
//! (points of circles, ellipses and NACA sections → `geom-curve` curves → `boundary1d`
//! nodes, through `test-cases`), for the gap survey example and the narrow-gap tests.
#![allow(dead_code)]

use geom_curve::{ClosedCurve, CurveParams, Point2};
use mesh_model::Role;
use test_cases::Case;

/// A small deterministic generator (SplitMix64), so that every case is reproducible from
/// its seed.
#[derive(Debug, Clone)]
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [a, b).
    pub fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Log-uniform in [a, b).
    pub fn log_uniform(&mut self, a: f64, b: f64) -> f64 {
        self.uniform(a.ln(), b.ln()).exp()
    }
    /// Uniform integer in a..=b.
    pub fn int(&mut self, a: usize, b: usize) -> usize {
        a + (self.next_u64() % (b - a + 1) as u64) as usize
    }
}

/// The closest approach of two bodies.
#[derive(Debug, Clone, Copy)]
pub struct Gap {
    /// Wall loop indices.
    pub a: usize,
    pub b: usize,
    /// Width (distance between the fitted curves).
    pub width: f64,
    /// Midpoint of the closest pair of points.
    pub at: [f64; 2],
}

/// A random domain: wall loops (points before boundary meshing) and a far field, with the
/// gaps between its bodies and the layer parameters drawn for it.
#[derive(Debug, Clone)]
pub struct Domain {
    /// What the bodies are, for the report.
    pub label: String,
    pub loops: Vec<(String, Role, Vec<[f64; 2]>)>,
    /// The gap each body was placed at (to the body it was placed next to).
    pub gaps: Vec<Gap>,
    pub first_height: f64,
    pub growth: f64,
}

impl Domain {
    /// The domain as a pipeline case (boundary spacing as `cargo xtask mesh` does it).
    pub fn case(&self) -> Case {
        let case = test_cases::case_of("random", self.loops.clone(), false);
        test_cases::with_layers(&case, self.first_height, self.growth)
    }
}

fn body_points(rng: &mut Rng) -> (String, Vec<[f64; 2]>) {
    let angle = rng.uniform(0.0, std::f64::consts::TAU);
    let (s, c) = angle.sin_cos();
    let rot = |p: [f64; 2]| [p[0] * c - p[1] * s, p[0] * s + p[1] * c];
    match rng.int(0, 2) {
        0 => {
            let r = rng.uniform(0.2, 0.5);
            (format!("circle r{r:.2}"), circle([0.0, 0.0], r))
        }
        1 => {
            let a = 0.5;
            let b = rng.uniform(0.1, 0.4);
            let pts = (0..256)
                .map(|i| {
                    let t = std::f64::consts::TAU * i as f64 / 256.0;
                    rot([a * t.cos(), b * t.sin()])
                })
                .collect();
            (format!("ellipse b{b:.2}"), pts)
        }
        _ => {
            let digits = format!("{}{}{:02}", rng.int(0, 6), rng.int(2, 6), rng.int(8, 18));
            let digits = if digits.starts_with('0') {
                format!("00{}", &digits[2..])
            } else {
                digits
            };
            let chord = rng.uniform(0.5, 1.0);
            let pts = geom_curve::naca::naca4(&digits, 101, true)
                .expect("a NACA section")
                .iter()
                .map(|p| rot([(p.x - 0.5) * chord, p.y * chord]))
                .collect();
            (format!("naca{digits} c{chord:.2}"), pts)
        }
    }
}

fn curve_of(points: &[[f64; 2]]) -> ClosedCurve {
    let mut p: Vec<Point2<f64>> = points.iter().map(|q| Point2::new(q[0], q[1])).collect();
    geom_curve::loops::make_counter_clockwise(&mut p);
    ClosedCurve::new(&p, &CurveParams::default()).expect("a body curve")
}

/// Points along a curve (`n` per input segment).
fn samples(curve: &ClosedCurve, n: usize) -> Vec<[f64; 2]> {
    let m = curve.segment_count() * n;
    (0..m)
        .map(|i| {
            let p = curve.point(i as f64 / n as f64);
            [p.x, p.y]
        })
        .collect()
}

fn d2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

/// Distance of two sampled bodies (the second shifted by `off`), and the closest pair.
fn sampled_distance(a: &[[f64; 2]], b: &[[f64; 2]], off: [f64; 2]) -> (f64, usize, usize) {
    let mut best = (f64::INFINITY, 0, 0);
    for (j, q) in b.iter().enumerate() {
        let q = [q[0] + off[0], q[1] + off[1]];
        for (i, p) in a.iter().enumerate() {
            let d = d2(*p, q);
            if d < best.0 {
                best = (d, i, j);
            }
        }
    }
    (best.0.sqrt(), best.1, best.2)
}

/// Distance between the curves of two bodies (the second shifted by `off`), refined from
/// the closest sampled pair; returns the distance and the midpoint of the closest pair.
fn curve_distance(ca: &ClosedCurve, cb: &ClosedCurve, off: [f64; 2]) -> (f64, [f64; 2]) {
    let n = 8;
    let (sa, sb) = (samples(ca, n), samples(cb, n));
    let (_, _, j) = sampled_distance(&sa, &sb, off);
    // golden-section search over the parameter of b around the closest sample
    let f = |t: f64| {
        let p = cb.point(t);
        let q = Point2::new(p.x + off[0], p.y + off[1]);
        let (_, foot, d) = ca.closest_point(q);
        (d, [0.5 * (q.x + foot.x), 0.5 * (q.y + foot.y)])
    };
    let t0 = j as f64 / n as f64;
    let (mut lo, mut hi) = (t0 - 1.0 / n as f64, t0 + 1.0 / n as f64);
    let m = cb.segment_count() as f64;
    let wrap = |t: f64| t.rem_euclid(m);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let x1 = hi - g * (hi - lo);
        let x2 = lo + g * (hi - lo);
        if f(wrap(x1)).0 < f(wrap(x2)).0 {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    f(wrap(0.5 * (lo + hi)))
}

/// A placed body: label, points, curve, coarse samples.
type Placed = (String, Vec<[f64; 2]>, ClosedCurve, Vec<[f64; 2]>);

/// A random domain of `bodies` bodies, each placed at a gap drawn log-uniformly in
/// `[gap_lo, gap_hi]` from one of the bodies placed before it; first height log-uniform in
/// `[h_lo, h_hi]`, growth uniform in [1.1, 1.5]. None when a placement fails (rare).
pub fn random_domain(
    rng: &mut Rng,
    bodies: usize,
    (gap_lo, gap_hi): (f64, f64),
    (h_lo, h_hi): (f64, f64),
) -> Option<Domain> {
    let mut placed: Vec<Placed> = Vec::new();
    let mut gaps = Vec::new();
    for k in 0..bodies {
        let (name, pts) = body_points(rng);
        let curve = curve_of(&pts);
        let coarse = samples(&curve, 1);
        if k == 0 {
            placed.push((name, pts, curve, coarse));
            continue;
        }
        let near = rng.int(0, k - 1);
        let gap = rng.log_uniform(gap_lo, gap_hi);
        let dir = rng.uniform(0.0, std::f64::consts::TAU);
        let u = [dir.cos(), dir.sin()];
        // coarse bisection on the distance along u from the centre of `near`
        let c = centroid(&placed[near].1);
        let shift = |t: f64| [c[0] + t * u[0], c[1] + t * u[1]];
        let coarse_dist = |t: f64| {
            placed
                .iter()
                .map(|(_, _, _, smp)| sampled_distance(smp, &coarse, shift(t)).0)
                .fold(f64::INFINITY, f64::min)
        };
        // scan in from far away to the first contact, so that no body ends up inside
        // another, then bisect
        let (mut lo, mut hi) = (0.0, 4.0);
        if coarse_dist(hi) <= gap {
            return None;
        }
        while hi > 0.0 {
            lo = hi - 0.02;
            if coarse_dist(lo) <= gap {
                break;
            }
            hi = lo;
        }
        for _ in 0..50 {
            let mid = 0.5 * (lo + hi);
            if coarse_dist(mid) > gap {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        // then secant steps on the fitted curves' distance to `near`
        let fine = |t: f64| curve_distance(&placed[near].2, &curve, shift(t));
        let mut t = hi;
        for _ in 0..8 {
            let (d, _) = fine(t);
            let (d2_, _) = fine(t + 1e-6);
            let slope = (d2_ - d) / 1e-6;
            if slope <= 1e-3 {
                break;
            }
            t -= (d - gap) / slope;
        }
        let off = shift(t);
        let (width, at) = fine(t);
        if !(width > 0.5 * gap && width < 2.0 * gap) {
            return None;
        }
        // no other body nearer than the gap
        for (i, (_, _, cu, _)) in placed.iter().enumerate() {
            if i != near && curve_distance(cu, &curve, off).0 < 0.5 * gap {
                return None;
            }
        }
        let moved: Vec<[f64; 2]> = pts.iter().map(|p| [p[0] + off[0], p[1] + off[1]]).collect();
        let moved_curve = curve_of(&moved);
        let moved_coarse = samples(&moved_curve, 1);
        gaps.push(Gap {
            a: near,
            b: k,
            width,
            at,
        });
        placed.push((name, moved, moved_curve, moved_coarse));
    }
    let all: Vec<[f64; 2]> = placed.iter().flat_map(|p| p.1.iter().copied()).collect();
    let c = centroid(&all);
    let label = placed
        .iter()
        .map(|p| p.0.as_str())
        .collect::<Vec<_>>()
        .join(" + ");
    let mut loops: Vec<(String, Role, Vec<[f64; 2]>)> = placed
        .into_iter()
        .enumerate()
        .map(|(i, p)| (format!("body{i}"), Role::Wall, p.1))
        .collect();
    let far = circle(c, 20.0);
    loops.push(("farfield".into(), Role::Farfield, far));
    Some(Domain {
        label,
        loops,
        gaps,
        first_height: rng.log_uniform(h_lo, h_hi),
        growth: rng.uniform(1.1, 1.5),
    })
}

fn centroid(p: &[[f64; 2]]) -> [f64; 2] {
    let n = p.len() as f64;
    [
        p.iter().map(|q| q[0]).sum::<f64>() / n,
        p.iter().map(|q| q[1]).sum::<f64>() / n,
    ]
}

/// Two walls (points before boundary meshing) in a far field of radius 20.
pub fn two_bodies(a: Vec<[f64; 2]>, b: Vec<[f64; 2]>, first_height: f64, growth: f64) -> Domain {
    let c = centroid(&[a.clone(), b.clone()].concat());
    let far = circle(c, 20.0);
    Domain {
        label: "two bodies".into(),
        loops: vec![
            ("a".into(), Role::Wall, a),
            ("b".into(), Role::Wall, b),
            ("farfield".into(), Role::Farfield, far),
        ],
        gaps: Vec::new(),
        first_height,
        growth,
    }
}

/// Circle points as the case files make them (256 points).
pub fn circle(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    testkit::shapes::circle(c, r, 256)
}
