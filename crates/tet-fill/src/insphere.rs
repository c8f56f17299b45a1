//! The insertion's `insphere` test, exact in sign but fast where the points are nearly
//! co-spherical. Points on a sphere (a far field, a spherical body) are co-spherical up to
//! rounding, so the floating-point stage of Shewchuk's predicate cannot tell, and its exact
//! stages cost some 3 µs a test: over half of the whole fill's time. Between the two, the
//! determinant is evaluated once more in double-double arithmetic (about 106 bits, each
//! operation's relative error proven below 7u², u = 2⁻⁵³, by Joldes, Muller and Popescu,
//! "Tight and rigorous error bounds for basic building blocks of double-word arithmetic",
//! 2017); it decides whenever the determinant exceeds 2⁻⁹⁰ times the permanent, a thousand
//! times its error bound — every test but the truly co-spherical ones, left to the exact
//! stages.

use geom_predicates::insphere;

/// `u`, the unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// Shewchuk's `isperrboundA`: the floating-point stage's error over the permanent.
const BOUND_A: f64 = (16.0 + 224.0 * U) * U;

/// The double-double stage's threshold over the permanent, 2⁻⁹⁰: the stage's error is at most
/// `8 · 7u² / (1 - 56u²) < 2⁻¹⁰⁰` times it (at most eight operations from a coordinate
/// difference to the result).
const BOUND_DD: f64 = 1.0 / 1_237_940_039_285_380_274_899_124_224.0;

/// Below this (absolute), underflow in the double-double stage could matter (its error is at
/// most some 70 operations times the smallest subnormal).
const TINY: f64 = 1e-300;

/// Whether `e` lies strictly inside the sphere through the positive tet `a b c d`; the sign
/// of [`geom_predicates::insphere`], exactly.
#[inline]
pub(crate) fn inside(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> bool {
    let (det, permanent) = float_stage(a, b, c, d, e);
    if det.abs() > BOUND_A * permanent {
        return det > 0.0;
    }
    if let Some(det) = dd_stage(a, b, c, d, e)
        && det.abs() > BOUND_DD * permanent + TINY
    {
        return det > 0.0;
    }
    insphere(a, b, c, d, e) > 0.0
}

/// Shewchuk's floating-point stage, in his order of evaluation (which his bound assumes):
/// the determinant and its permanent.
#[inline]
fn float_stage(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> (f64, f64) {
    let [aex, aey, aez] = [a[0] - e[0], a[1] - e[1], a[2] - e[2]];
    let [bex, bey, bez] = [b[0] - e[0], b[1] - e[1], b[2] - e[2]];
    let [cex, cey, cez] = [c[0] - e[0], c[1] - e[1], c[2] - e[2]];
    let [dex, dey, dez] = [d[0] - e[0], d[1] - e[1], d[2] - e[2]];
    let (aexbey, bexaey) = (aex * bey, bex * aey);
    let (bexcey, cexbey) = (bex * cey, cex * bey);
    let (cexdey, dexcey) = (cex * dey, dex * cey);
    let (dexaey, aexdey) = (dex * aey, aex * dey);
    let (aexcey, cexaey) = (aex * cey, cex * aey);
    let (bexdey, dexbey) = (bex * dey, dex * bey);
    let ab = aexbey - bexaey;
    let bc = bexcey - cexbey;
    let cd = cexdey - dexcey;
    let da = dexaey - aexdey;
    let ac = aexcey - cexaey;
    let bd = bexdey - dexbey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    let (az, bz, cz, dz) = (aez.abs(), bez.abs(), cez.abs(), dez.abs());
    let ab_ = aexbey.abs() + bexaey.abs();
    let bc_ = bexcey.abs() + cexbey.abs();
    let cd_ = cexdey.abs() + dexcey.abs();
    let da_ = dexaey.abs() + aexdey.abs();
    let ac_ = aexcey.abs() + cexaey.abs();
    let bd_ = bexdey.abs() + dexbey.abs();
    let permanent = (cd_ * bz + bd_ * cz + bc_ * dz) * alift
        + (da_ * cz + ac_ * dz + cd_ * az) * blift
        + (ab_ * dz + bd_ * az + da_ * bz) * clift
        + (bc_ * az + ac_ * bz + ab_ * cz) * dlift;
    (det, permanent)
}

/// A double-double number: `hi + lo`, `|lo| ≤ ulp(hi) / 2`.
#[derive(Clone, Copy)]
struct Dd {
    hi: f64,
    lo: f64,
}

/// `a + b` exactly, as a double-double (Knuth's TwoSum).
#[inline]
fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    let lo = (a - (s - bb)) + (b - bb);
    Dd { hi: s, lo }
}

/// `a + b` exactly when `|a| ≥ |b|` (Dekker's Fast2Sum).
#[inline]
fn fast_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

/// Veltkamp's split of `a` into two halves of 26 bits (exact for `|a| < 2⁹⁹⁵`).
#[inline]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a · b` exactly, as a double-double (Dekker's TwoProduct; no underflow).
#[inline]
fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let lo = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
    Dd { hi: p, lo }
}

impl Dd {
    /// The sum (AccurateDWPlusDW: relative error below 3u²).
    #[inline]
    fn plus(self, y: Dd) -> Dd {
        let s = two_sum(self.hi, y.hi);
        let t = two_sum(self.lo, y.lo);
        let v = fast_two_sum(s.hi, s.lo + t.hi);
        fast_two_sum(v.hi, t.lo + v.lo)
    }

    #[inline]
    fn minus(self, y: Dd) -> Dd {
        self.plus(Dd {
            hi: -y.hi,
            lo: -y.lo,
        })
    }

    /// The product (DWTimesDW1: relative error below 7u²).
    #[inline]
    fn times(self, y: Dd) -> Dd {
        let c = two_prod(self.hi, y.hi);
        let cl2 = self.hi * y.lo + self.lo * y.hi;
        fast_two_sum(c.hi, c.lo + cl2)
    }
}

/// The determinant in double-double arithmetic, from the exact coordinate differences; None
/// when a difference is so large that a product could overflow.
fn dd_stage(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> Option<f64> {
    let diff = |p: [f64; 3]| [0, 1, 2].map(|k| two_sum(p[k], -e[k]));
    let [ax, ay, az] = diff(a);
    let [bx, by, bz] = diff(b);
    let [cx, cy, cz] = diff(c);
    let [dx, dy, dz] = diff(d);
    let big = [ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz]
        .iter()
        .any(|x| x.hi.abs() > 1e50);
    if big {
        return None;
    }
    let minor = |p: Dd, q: Dd, r: Dd, s: Dd| p.times(q).minus(r.times(s));
    let ab = minor(ax, by, bx, ay);
    let bc = minor(bx, cy, cx, by);
    let cd = minor(cx, dy, dx, cy);
    let da = minor(dx, ay, ax, dy);
    let ac = minor(ax, cy, cx, ay);
    let bd = minor(bx, dy, dx, by);
    let abc = az.times(bc).minus(bz.times(ac)).plus(cz.times(ab));
    let bcd = bz.times(cd).minus(cz.times(bd)).plus(dz.times(bc));
    let cda = cz.times(da).plus(dz.times(ac)).plus(az.times(cd));
    let dab = dz.times(ab).plus(az.times(bd)).plus(bz.times(da));
    let lift = |x: Dd, y: Dd, z: Dd| x.times(x).plus(y.times(y)).plus(z.times(z));
    let (alift, blift) = (lift(ax, ay, az), lift(bx, by, bz));
    let (clift, dlift) = (lift(cx, cy, cz), lift(dx, dy, dz));
    let det = dlift
        .times(abc)
        .minus(clift.times(dab))
        .plus(blift.times(cda).minus(alift.times(bcd)));
    Some(det.hi + det.lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` points within rounding of a sphere, some exactly on it.
    fn near_sphere(n: usize) -> Vec<[f64; 3]> {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        (0..n)
            .map(|i| {
                if i % 7 == 0 {
                    // exactly on the sphere of radius 1 about (3, 3, 3)
                    let k = i % 3;
                    let mut p = [3.0; 3];
                    p[k] += if i % 2 == 0 { 1.0 } else { -1.0 };
                    return p;
                }
                let p = [next(), next(), next()];
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                p.map(|x| 3.0 + x / r)
            })
            .collect()
    }

    #[test]
    fn agrees_with_the_exact_predicate() {
        let p = near_sphere(60);
        let mut undecided = 0;
        for i in 0..p.len() {
            for j in 0..5 {
                let w = [0, 1, 2, 3, 4].map(|k| p[(i + k * (j + 1)) % p.len()]);
                let exact = insphere(w[0], w[1], w[2], w[3], w[4]);
                assert_eq!(inside(w[0], w[1], w[2], w[3], w[4]), exact > 0.0, "{w:?}");
                let (det, permanent) = float_stage(w[0], w[1], w[2], w[3], w[4]);
                if det.abs() <= BOUND_A * permanent {
                    undecided += 1;
                    // the double-double stage: right whenever it decides
                    let dd = dd_stage(w[0], w[1], w[2], w[3], w[4]).unwrap();
                    if dd.abs() > BOUND_DD * permanent + TINY {
                        assert_eq!(dd > 0.0, exact > 0.0, "{w:?}");
                    }
                }
            }
        }
        assert!(
            undecided > 100,
            "only {undecided} tests left to the later stages"
        );
    }

    #[test]
    fn double_double_products_are_exact() {
        let (a, b) = (0.1f64, 3.0f64.sqrt());
        let p = two_prod(a, b);
        // (a·b − hi) exactly equals lo: check by splitting again
        let q = two_prod(b, a);
        assert_eq!((p.hi, p.lo), (q.hi, q.lo));
        assert!(p.lo != 0.0 && p.lo.abs() <= p.hi.abs() * U);
    }
}
