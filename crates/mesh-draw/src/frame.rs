//! From the mesh plane to the picture: the mesh-to-pixel map of a view fitted in the plot
//! area, and the curves (lines, quadratic and cubic Béziers, in pixels) that the edges of
//! linear, P2 and P3 cells become, culled outside the plot and clipped where their pixel
//! coordinates would grow too large to rasterise. It owns no colour and no drawing.

use geom_predicates::point_segment_distance;

use crate::error::DrawError;
use crate::params::View;

/// A rectangle in pixels, y down (`y0` is the top edge).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PxRect {
    /// Left.
    pub x0: f64,
    /// Top.
    pub y0: f64,
    /// Right.
    pub x1: f64,
    /// Bottom.
    pub y1: f64,
}

impl PxRect {
    /// Width, pixels.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    /// Height, pixels.
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }

    /// The rectangle grown by `d` pixels on every side.
    pub fn expand(&self, d: f64) -> PxRect {
        PxRect {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }

    /// True when the two rectangles overlap (touching counts).
    pub fn intersects(&self, o: &PxRect) -> bool {
        self.x0 <= o.x1 && o.x0 <= self.x1 && self.y0 <= o.y1 && o.y0 <= self.y1
    }

    /// True when `o` lies inside this rectangle.
    pub fn contains(&self, o: &PxRect) -> bool {
        self.x0 <= o.x0 && o.x1 <= self.x1 && self.y0 <= o.y0 && o.y1 <= self.y1
    }

    /// Bounding box of points.
    fn of_points(points: &[[f64; 2]]) -> PxRect {
        let mut r = PxRect {
            x0: f64::INFINITY,
            y0: f64::INFINITY,
            x1: f64::NEG_INFINITY,
            y1: f64::NEG_INFINITY,
        };
        for p in points {
            r.x0 = r.x0.min(p[0]);
            r.y0 = r.y0.min(p[1]);
            r.x1 = r.x1.max(p[0]);
            r.y1 = r.y1.max(p[1]);
        }
        r
    }
}

/// A piece of an edge in pixel coordinates: a line (2 points), a quadratic (3) or a cubic (4)
/// Bézier curve, given by its control points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Curve {
    points: [[f32; 2]; 4],
    count: u8,
}

impl Curve {
    fn new(control: &[[f64; 2]]) -> Curve {
        let mut points = [[0.0f32; 2]; 4];
        for (p, c) in points.iter_mut().zip(control) {
            *p = [c[0] as f32, c[1] as f32];
        }
        Curve {
            points,
            count: control.len() as u8,
        }
    }

    /// The control points: start, inner control points, end.
    pub fn points(&self) -> &[[f32; 2]] {
        &self.points[..self.count as usize]
    }

    /// First point.
    pub fn start(&self) -> [f32; 2] {
        self.points[0]
    }

    /// Last point.
    pub fn end(&self) -> [f32; 2] {
        self.points[self.count as usize - 1]
    }

    /// Diagonal of the control points' bounding box, pixels: an upper bound of the curve's
    /// extent.
    pub fn extent_px(&self) -> f64 {
        let p: Vec<[f64; 2]> = self
            .points()
            .iter()
            .map(|p| [p[0] as f64, p[1] as f64])
            .collect();
        let b = PxRect::of_points(&p);
        b.width().hypot(b.height())
    }
}

/// Bézier control points of the polynomial curve through Lagrange points at equally spaced
/// parameters 0, 1/p, …, 1 (`lagrange.len() = p + 1`, p = 1, 2 or 3): the same curve, exactly.
pub(crate) fn bezier_from_lagrange(lagrange: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mix = |w: &[f64]| -> [f64; 2] {
        let mut out = [0.0; 2];
        for (wi, p) in w.iter().zip(lagrange) {
            out[0] += wi * p[0];
            out[1] += wi * p[1];
        }
        out
    };
    match lagrange.len() {
        3 => vec![lagrange[0], mix(&[-0.5, 2.0, -0.5]), lagrange[2]],
        4 => vec![
            lagrange[0],
            mix(&[-5.0 / 6.0, 3.0, -1.5, 1.0 / 3.0]),
            mix(&[1.0 / 3.0, -1.5, 3.0, -5.0 / 6.0]),
            lagrange[3],
        ],
        _ => lagrange.to_vec(),
    }
}

/// The point at parameter `t` of the Bézier curve with these control points (de Casteljau).
pub(crate) fn bezier_point(control: &[[f64; 2]], t: f64) -> [f64; 2] {
    let mut p: Vec<[f64; 2]> = control.to_vec();
    for level in (1..p.len()).rev() {
        for i in 0..level {
            p[i] = [
                p[i][0] + t * (p[i + 1][0] - p[i][0]),
                p[i][1] + t * (p[i + 1][1] - p[i][1]),
            ];
        }
    }
    p[0]
}

/// Curves whose control points lie within this distance (pixels) of their chord are drawn as
/// lines.
const STRAIGHT_TOLERANCE_PX: f64 = 0.05;
/// Largest error (pixels) when a curve has to be flattened for clipping.
const FLATTEN_TOLERANCE_PX: f64 = 0.1;

/// The map from a view to a plot rectangle (aspect kept, view centred), and the rectangles
/// that decide what is drawn.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    /// Pixels per mesh unit.
    pub scale: f64,
    view_center: [f64; 2],
    plot_center: [f64; 2],
    /// Where the mesh is drawn, pixels.
    pub plot: PxRect,
    /// Curves outside this rectangle (the plot plus a few pixels for bold strokes) are culled.
    cull: PxRect,
    /// Curves reaching outside this rectangle are clipped to it, so that coordinates stay
    /// small enough for the rasteriser.
    guard: PxRect,
}

impl Frame {
    /// Fits `view` in `plot`.
    pub fn new(view: &View, plot: PxRect) -> Result<Frame, DrawError> {
        view.check()?;
        let scale = (plot.width() / view.width()).min(plot.height() / view.height());
        if !(scale.is_finite() && scale > 0.0) {
            return Err(DrawError::InvalidView {
                x0: view.x0,
                y0: view.y0,
                x1: view.x1,
                y1: view.y1,
                reason: "its size gives no finite scale",
            });
        }
        let pad = plot.width().max(plot.height());
        Ok(Frame {
            scale,
            view_center: view.center(),
            plot_center: [0.5 * (plot.x0 + plot.x1), 0.5 * (plot.y0 + plot.y1)],
            plot,
            cull: plot.expand(4.0),
            guard: plot.expand(pad),
        })
    }

    /// Pixel position of a mesh point.
    pub fn to_px(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.plot_center[0] + (p[0] - self.view_center[0]) * self.scale,
            self.plot_center[1] - (p[1] - self.view_center[1]) * self.scale,
        ]
    }

    /// Mesh position of a pixel.
    pub fn to_mesh(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.view_center[0] + (p[0] - self.plot_center[0]) / self.scale,
            self.view_center[1] - (p[1] - self.plot_center[1]) / self.scale,
        ]
    }

    /// The mesh-plane rectangle whose content may show (the cull rectangle), to skip cells.
    pub fn cull_view(&self) -> View {
        let a = self.to_mesh([self.cull.x0, self.cull.y1]);
        let b = self.to_mesh([self.cull.x1, self.cull.y0]);
        View {
            x0: a[0],
            y0: a[1],
            x1: b[0],
            y1: b[1],
        }
    }

    /// Bézier control points, in pixels, of the edge through these Lagrange points (mesh
    /// units), reduced to a line when it is straight to within a twentieth of a pixel.
    fn control_px(&self, lagrange: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let px: Vec<[f64; 2]> = lagrange.iter().map(|&p| self.to_px(p)).collect();
        let control = bezier_from_lagrange(&px);
        let (a, b) = (control[0], control[control.len() - 1]);
        if control.len() > 2
            && control[1..control.len() - 1]
                .iter()
                .all(|&c| point_segment_distance(c, a, b) <= STRAIGHT_TOLERANCE_PX)
        {
            vec![a, b]
        } else {
            control
        }
    }

    /// Appends the visible part of the edge through these Lagrange points (mesh units, in
    /// order along the edge) to `out`: one curve, or line pieces clipped to the guard rectangle
    /// when it reaches far outside the picture; nothing when it lies outside the plot.
    pub fn push_edge(&self, lagrange: &[[f64; 2]], out: &mut Vec<Curve>) {
        let control = self.control_px(lagrange);
        let bbox = PxRect::of_points(&control);
        if !bbox.intersects(&self.cull) {
            return;
        }
        if self.guard.contains(&bbox) {
            out.push(Curve::new(&control));
            return;
        }
        let points = flatten(&control);
        for w in points.windows(2) {
            if let Some((t0, t1)) = clip_segment(w[0], w[1], &self.guard) {
                let lerp = |t: f64| {
                    [
                        w[0][0] + t * (w[1][0] - w[0][0]),
                        w[0][1] + t * (w[1][1] - w[0][1]),
                    ]
                };
                out.push(Curve::new(&[lerp(t0), lerp(t1)]));
            }
        }
    }

    /// Appends the closed outline of a cell whose edges pass through these Lagrange points
    /// (one slice per edge, in order around the cell) to `out`: its curves, or a polygon
    /// clipped to the guard rectangle when the cell reaches far outside the picture. Returns
    /// the number of curves appended (0 when nothing of it is visible).
    pub fn push_outline(&self, edges: &[&[[f64; 2]]], out: &mut Vec<Curve>) -> usize {
        let controls: Vec<Vec<[f64; 2]>> = edges.iter().map(|e| self.control_px(e)).collect();
        let all: Vec<[f64; 2]> = controls.iter().flatten().copied().collect();
        let bbox = PxRect::of_points(&all);
        if !bbox.intersects(&self.cull) {
            return 0;
        }
        if self.guard.contains(&bbox) {
            out.extend(controls.iter().map(|c| Curve::new(c)));
            return controls.len();
        }
        let mut polygon: Vec<[f64; 2]> = Vec::new();
        for c in &controls {
            let pts = flatten(c);
            polygon.extend_from_slice(&pts[..pts.len() - 1]);
        }
        let clipped = clip_polygon(&polygon, &self.guard);
        if clipped.len() < 3 {
            return 0;
        }
        let n = clipped.len();
        for i in 0..n {
            out.push(Curve::new(&[clipped[i], clipped[(i + 1) % n]]));
        }
        n
    }
}

/// Points along a Bézier curve, close enough that the polyline is within
/// [`FLATTEN_TOLERANCE_PX`] of the curve (uniform parameter steps, from the second-difference
/// bound of the flattening error).
fn flatten(control: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let degree = control.len() - 1;
    if degree <= 1 {
        return control.to_vec();
    }
    let second_difference = control
        .windows(3)
        .map(|w| (w[0][0] - 2.0 * w[1][0] + w[2][0]).hypot(w[0][1] - 2.0 * w[1][1] + w[2][1]))
        .fold(0.0, f64::max);
    let bound = (degree * (degree - 1)) as f64 / 8.0 * second_difference;
    let segments = (bound / FLATTEN_TOLERANCE_PX)
        .sqrt()
        .ceil()
        .clamp(1.0, 4096.0) as usize;
    (0..=segments)
        .map(|i| bezier_point(control, i as f64 / segments as f64))
        .collect()
}

/// Liang–Barsky: the parameter interval of segment `a b` inside `r`, if any.
fn clip_segment(a: [f64; 2], b: [f64; 2], r: &PxRect) -> Option<(f64, f64)> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d[0], a[0] - r.x0),
        (d[0], r.x1 - a[0]),
        (-d[1], a[1] - r.y0),
        (d[1], r.y1 - a[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 < t1).then_some((t0, t1))
}

/// Sutherland–Hodgman: the polygon clipped to the rectangle.
fn clip_polygon(polygon: &[[f64; 2]], r: &PxRect) -> Vec<[f64; 2]> {
    let mut current = polygon.to_vec();
    // Each half-plane as (axis, bound, keep when coordinate >= bound?).
    for (axis, bound, keep_above) in [
        (0, r.x0, true),
        (0, r.x1, false),
        (1, r.y0, true),
        (1, r.y1, false),
    ] {
        if current.is_empty() {
            break;
        }
        let inside = |p: &[f64; 2]| {
            if keep_above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let mut next = Vec::with_capacity(current.len() + 4);
        for i in 0..current.len() {
            let a = current[i];
            let b = current[(i + 1) % current.len()];
            let (ia, ib) = (inside(&a), inside(&b));
            if ia {
                next.push(a);
            }
            if ia != ib {
                let t = (bound - a[axis]) / (b[axis] - a[axis]);
                next.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
            }
        }
        current = next;
    }
    current
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The Lagrange interpolant through equally spaced points, evaluated directly.
    fn lagrange_point(nodes: &[[f64; 2]], t: f64) -> [f64; 2] {
        let (weights, _) = jacobian_check::lagrange::equispaced_line(nodes.len() - 1, t);
        let mut out = [0.0; 2];
        for (n, w) in nodes.iter().zip(weights) {
            out[0] += w * n[0];
            out[1] += w * n[1];
        }
        out
    }

    proptest! {
        #[test]
        fn the_bezier_form_is_the_lagrange_interpolant(
            nodes in prop::collection::vec(prop::array::uniform2(-5.0f64..5.0), 2..=4),
            t in 0.0f64..=1.0,
        ) {
            let control = bezier_from_lagrange(&nodes);
            let a = bezier_point(&control, t);
            let b = lagrange_point(&nodes, t);
            prop_assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9, "{a:?} {b:?}");
        }

        #[test]
        fn clipped_segments_stay_in_the_rectangle_and_on_the_segment(
            a in prop::array::uniform2(-1e6f64..1e6),
            b in prop::array::uniform2(-1e6f64..1e6),
        ) {
            let r = PxRect { x0: 0.0, y0: 0.0, x1: 100.0, y1: 50.0 };
            if let Some((t0, t1)) = clip_segment(a, b, &r) {
                prop_assert!(0.0 <= t0 && t0 < t1 && t1 <= 1.0);
                for t in [t0, t1] {
                    let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                    let point = PxRect { x0: p[0], y0: p[1], x1: p[0], y1: p[1] };
                    // Within a micro-pixel per unit of the segment's size.
                    prop_assert!(r.expand(1.0).contains(&point), "{:?}", p);
                }
            }
        }
    }

    #[test]
    fn a_huge_cell_is_clipped_to_small_coordinates() {
        let view = View::around([0.0, 0.0], 1e-6);
        let plot = PxRect {
            x0: 0.0,
            y0: 0.0,
            x1: 200.0,
            y1: 100.0,
        };
        let frame = Frame::new(&view, plot).unwrap();
        let a = [-10.0, -10.0];
        let b = [10.0, -10.0];
        let c = [0.0, 10.0];
        let mut out = Vec::new();
        let n = frame.push_outline(&[&[a, b], &[b, c], &[c, a]], &mut out);
        assert!(n >= 3);
        for p in out.iter().flat_map(|c| c.points()) {
            assert!(p[0].abs() < 1e4 && p[1].abs() < 1e4, "{p:?}");
        }
        // The view lies inside the triangle: the clipped polygon covers the whole plot.
        let xs: Vec<f32> = out.iter().map(|c| c.start()[0]).collect();
        assert!(xs.iter().any(|&x| x <= 0.0) && xs.iter().any(|&x| x >= 200.0));
    }

    #[test]
    fn an_edge_outside_the_plot_is_culled_and_a_straight_p2_edge_is_a_line() {
        let plot = PxRect {
            x0: 0.0,
            y0: 0.0,
            x1: 100.0,
            y1: 100.0,
        };
        let frame = Frame::new(&View::around([0.0, 0.0], 1.0), plot).unwrap();
        let mut out = Vec::new();
        frame.push_edge(&[[5.0, 5.0], [6.0, 6.0]], &mut out);
        assert!(out.is_empty());
        frame.push_edge(&[[0.0, 0.0], [0.25, 0.0], [0.5, 0.0]], &mut out);
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].points().len(), 2);
        frame.push_edge(&[[0.0, 0.0], [0.25, 0.1], [0.5, 0.0]], &mut out);
        assert_eq!(out[1].points().len(), 3);
    }
}
