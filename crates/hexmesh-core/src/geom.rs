//! Small geometric primitives shared by every module: exact orientation and incircle signs
//! (Shewchuk's adaptive predicates through the `robust` crate), the flat-topped hexagon,
//! and the minimum enclosing circle (Welzl 1991, "Smallest enclosing disks").

/// A point in the plane.
pub type Point = [f64; 2];

/// Exact sign of the orientation of (a, b, c): > 0 counter-clockwise, < 0 clockwise, 0 collinear.
/// The magnitude is twice the signed area when the computation is exact.
pub fn orient2d(a: Point, b: Point, c: Point) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Exact incircle sign: > 0 when `d` lies strictly inside the circle through the
/// counter-clockwise triangle (a, b, c), 0 when cocircular, < 0 outside.
pub fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
    robust::incircle(coord(a), coord(b), coord(c), coord(d))
}

fn coord(p: Point) -> robust::Coord<f64> {
    robust::Coord { x: p[0], y: p[1] }
}

/// ⌊log₂|x|⌋ for a finite non-zero `x`, subnormals included, read from the bits (exact: no
/// rounded logarithm). 0 for 0; 1024 for infinities and NaN.
pub fn exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if biased != 0 {
        return biased - 1023;
    }
    let mantissa = bits & ((1 << 52) - 1);
    if mantissa == 0 {
        0
    } else {
        // x = mantissa · 2^-1074.
        63 - mantissa.leading_zeros() as i32 - 1074
    }
}

/// x · 2ⁿ (C's `scalbn`): exact whenever the result is a normal number (or zero, or
/// subnormal without lost bits); rounded once when it is subnormal, ±∞ beyond the range.
pub fn scale2(mut x: f64, mut n: i32) -> f64 {
    let p1023 = f64::from_bits(0x7fe0_0000_0000_0000); // 2^1023
    let pm969 = f64::from_bits(((0x3ff - 1022 + 53) as u64) << 52); // 2^-969
    if n > 1023 {
        x *= p1023;
        n -= 1023;
        if n > 1023 {
            x *= p1023;
            n = (n - 1023).min(1023);
        }
    } else if n < -1022 {
        // Two steps that keep the intermediate normal (2^-1022 · 2^53), so that only the
        // last multiplication rounds (musl's scalbn).
        x *= pm969;
        n += 1022 - 53;
        if n < -1022 {
            x *= pm969;
            n = (n + 1022 - 53).max(-1022);
        }
    }
    x * f64::from_bits(((0x3ff + n) as u64) << 52)
}

/// The exponent (`exponent`) of the largest magnitude among `values`: scaling them all by
/// 2^-e (`scale2`) brings the largest into [1, 2) and changes no bit of any of them that
/// stays normal. 0 when every value is zero or one is not finite (nothing to scale).
pub fn scale_exponent(values: &[f64]) -> i32 {
    let mut m = 0.0f64;
    for &v in values {
        if !v.is_finite() {
            return 0;
        }
        m = m.max(v.abs());
    }
    if m == 0.0 {
        0
    } else {
        exponent(m)
    }
}

/// The point (or vector) `p` times 2ⁿ, coordinate by coordinate (`scale2`).
pub fn scale_point(p: Point, n: i32) -> Point {
    [scale2(p[0], n), scale2(p[1], n)]
}

/// The angle at `a` between the rays to `b` and `c`, in degrees: the library's one angle
/// function (the meshers' rules and self-checks, `quality`, the fuzz campaigns). atan2 of the
/// cross and dot products keeps angles near 0° and 180° accurate, where acos of a rounded
/// cosine is not; both difference vectors are first scaled by one power of two to a largest
/// component in [1, 2) (exact), so the products neither overflow nor underflow at any finite
/// coordinates.
pub fn angle_deg(a: Point, b: Point, c: Point) -> f64 {
    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    let e = scale_exponent(&[u[0], u[1], v[0], v[1]]);
    vector_angle_deg(scale_point(u, -e), scale_point(v, -e))
}

/// The angle between the vectors `u` and `v`, in degrees, from atan2 of their cross and dot
/// products (`angle_deg` without the scaling: atan2 does not see a factor common to both, so
/// a caller may scale u and v by one power of two, as `quality`'s metrics do for a triangle's
/// three edges at once).
pub fn vector_angle_deg(u: [f64; 2], v: [f64; 2]) -> f64 {
    (u[0] * v[1] - u[1] * v[0])
        .abs()
        .atan2(u[0] * v[0] + u[1] * v[1])
        .to_degrees()
}

/// The exponent by which the predicates scale their points, when the largest coordinate
/// magnitude lies outside [2^-limit, 2^limit]: `None` when no scaling is needed.
fn predicate_scale(points: &[Point], limit: i32) -> Option<i32> {
    let mut m = 0.0f64;
    for &v in points.iter().flatten() {
        if !v.is_finite() {
            return None; // nothing to scale: `robust` gives what it gives
        }
        m = m.max(v.abs());
    }
    if m == 0.0 {
        return None;
    }
    let e = exponent(m);
    (e > limit || e < -limit).then_some(e)
}

/// `v · 2ⁿ` without losing the sign of a non-zero `v`: an underflow gives the smallest
/// subnormal of that sign instead of zero (an overflow gives ±∞).
fn scale_keeping_sign(v: f64, n: i32) -> f64 {
    let r = scale2(v, n);
    if r == 0.0 && v != 0.0 {
        f64::from_bits(1).copysign(v)
    } else {
        r
    }
}

/// `orient2d` for coordinates of any finite magnitude. Shewchuk's predicates are exact only
/// while their products neither overflow nor underflow (`robust` gives a wrong sign for
/// nearly collinear points from about 2^±510 on, and its error terms underflow sooner):
/// when the largest coordinate is below 2^-300 or above 2^300, the three points are first
/// scaled by the power of two that brings it into [1, 2) — exact, and the sign of a
/// degree-2 polynomial does not change — and the result is scaled back (an underflow keeps
/// its sign as the smallest subnormal, an overflow saturates to ±∞). Within that range it
/// is `orient2d`, bit for bit.
pub fn orient2d_scaled(a: Point, b: Point, c: Point) -> f64 {
    match predicate_scale(&[a, b, c], 300) {
        None => orient2d(a, b, c),
        Some(e) => {
            let s = |p| scale_point(p, -e);
            scale_keeping_sign(orient2d(s(a), s(b), s(c)), 2 * e)
        }
    }
}

/// `incircle` for coordinates of any finite magnitude: its products of four coordinates
/// overflow inside `robust` from about 2^256 on (NaN: 1e80 is beyond) and underflow below
/// about 2^-260 (a wrong 0 for nearly cocircular points), so when the largest coordinate
/// lies outside [2^-150, 2^150] the four points are scaled by the power of two that brings
/// it into [1, 2) first (exact; the sign of the degree-4 determinant does not change). The
/// magnitude is scaled back as in `orient2d_scaled`; callers use the sign. Within that range
/// it is `incircle`, bit for bit.
pub fn incircle_scaled(a: Point, b: Point, c: Point, d: Point) -> f64 {
    match predicate_scale(&[a, b, c, d], 150) {
        None => incircle(a, b, c, d),
        Some(e) => {
            let s = |p| scale_point(p, -e);
            scale_keeping_sign(incircle(s(a), s(b), s(c), s(d)), 4 * e)
        }
    }
}

/// The Euclidean length of `v` without overflow or underflow in its squares: `v` is scaled
/// by a power of two to a largest component in [1, 2), measured, and the length scaled back.
/// Equal to `(v·v).sqrt()` bit for bit whenever that does not under- or overflow.
pub fn norm(v: [f64; 2]) -> f64 {
    let e = scale_exponent(&v);
    let s = scale_point(v, -e);
    scale2((s[0] * s[0] + s[1] * s[1]).sqrt(), e)
}

/// `dist` without overflow or underflow (`norm` of the difference).
pub fn dist_scaled(a: Point, b: Point) -> f64 {
    norm([a[0] - b[0], a[1] - b[1]])
}

/// A squared distance as `mantissa · 2^exponent` with the mantissa in [1, 2), so that it
/// neither overflows nor underflows at any finite coordinates. Ordered like the squared
/// distances; where `dist2` neither under- nor overflows, the order and `sqrt` are those of
/// `dist2`, bit for bit.
#[derive(Debug, Clone, Copy)]
pub struct Dist2 {
    exponent: i32,
    mantissa: f64,
}

impl Dist2 {
    /// The squared distance of a point to itself; smaller than every other.
    pub const ZERO: Dist2 = Dist2 {
        exponent: i32::MIN,
        mantissa: 0.0,
    };
    /// Larger than every squared distance of finite points (and what non-finite ones get).
    pub const INFINITY: Dist2 = Dist2 {
        exponent: i32::MAX,
        mantissa: f64::INFINITY,
    };

    /// The squared distance between `a` and `b`.
    pub fn between(a: Point, b: Point) -> Dist2 {
        let d = [a[0] - b[0], a[1] - b[1]];
        if !(d[0].is_finite() && d[1].is_finite()) {
            return Dist2::INFINITY;
        }
        if d[0] == 0.0 && d[1] == 0.0 {
            return Dist2::ZERO;
        }
        let e = scale_exponent(&d);
        let s = scale_point(d, -e);
        let sum = s[0] * s[0] + s[1] * s[1]; // in [1, 8)
        let j = exponent(sum);
        Dist2 {
            exponent: 2 * e + j,
            mantissa: scale2(sum, -j),
        }
    }

    /// The distance, rounded once (as `sqrt` of the squared distance); ±∞ only beyond f64.
    pub fn sqrt(self) -> f64 {
        if self.exponent == i32::MIN || self.exponent == i32::MAX {
            return self.mantissa;
        }
        let odd = self.exponent.rem_euclid(2);
        scale2(
            scale2(self.mantissa, odd).sqrt(),
            self.exponent.div_euclid(2),
        )
    }
}

impl PartialEq for Dist2 {
    fn eq(&self, other: &Dist2) -> bool {
        self.cmp(other) == std::cmp::Ordering::Equal
    }
}

impl Eq for Dist2 {}

impl PartialOrd for Dist2 {
    fn partial_cmp(&self, other: &Dist2) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Dist2 {
    fn cmp(&self, other: &Dist2) -> std::cmp::Ordering {
        self.exponent
            .cmp(&other.exponent)
            .then(self.mantissa.total_cmp(&other.mantissa))
    }
}

/// Squared Euclidean distance.
pub fn dist2(a: Point, b: Point) -> f64 {
    let dx = a[0] - b[0];
    let dy = a[1] - b[1];
    dx * dx + dy * dy
}

/// Euclidean distance.
pub fn dist(a: Point, b: Point) -> f64 {
    dist2(a, b).sqrt()
}

/// A regular hexagon: corners at 0°, 60°, …, 300° from the centre (flat-topped: top and bottom
/// edges horizontal), all turned counter-clockwise by `turn`. The hex meshers' lattice and the
/// rhomb mesher's root are built on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hexagon {
    /// The centre, in input coordinates.
    pub center: Point,
    /// Distance from the centre to a corner (equal to the edge length).
    pub circumradius: f64,
    /// The rotation about the centre: `Turn::NONE` for the flat-topped hexagon (corners at 0°,
    /// 60°, …, 300°); `Hexagon::aligned` turns the hexagon of an elongated point set (the hex
    /// meshers' root, `hex::root_hexagon`).
    pub turn: Turn,
}

/// Offsets of the six corners (0°, 60°, …, 300°) of a hexagon of circumradius r from its
/// centre, in units of r/2 along its x axis and √3·r/2 along its y axis: in the (X, Y)
/// coordinates of `Lattice::grid_point`, relative to a cell's centre (3i, i + 2j).
pub(crate) const CORNER_X: [i64; 6] = [2, 1, -1, -2, -1, 1];
pub(crate) const CORNER_Y: [i64; 6] = [0, 1, 1, 0, -1, -1];

/// A rotation by θ about a hexagon's centre, as (cos θ, sin θ) (of unit length up to
/// rounding; the stored values are the ones every position is computed from).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turn {
    /// cos θ.
    pub cos: f64,
    /// sin θ (positive: counter-clockwise).
    pub sin: f64,
}

impl Turn {
    /// No rotation: corners at 0°, 60°, …, 300°.
    pub const NONE: Turn = Turn { cos: 1.0, sin: 0.0 };

    /// Whether this is `Turn::NONE` exactly (cos 1, sin 0 bit for bit).
    pub fn is_none(self) -> bool {
        self == Turn::NONE
    }

    /// The vector `v` turned back (by −θ): into the unturned frame of the hexagon.
    pub fn undo(self, v: [f64; 2]) -> [f64; 2] {
        [
            self.cos * v[0] + self.sin * v[1],
            self.cos * v[1] - self.sin * v[0],
        ]
    }
}

/// Points whose spread across their principal axis is at most this fraction of the spread
/// along it (standard deviations) are elongated, and `Hexagon::aligned` turns their hexagon.
pub const ELONGATED: f64 = 0.25;

/// The turn `Hexagon::aligned` gives the hexagon of `points`: none unless the points are
/// elongated (`ELONGATED`); then the one that takes the lattice direction at 30° (from a
/// centre to the neighbour across the upper-right edge) onto the points' principal axis.
///
/// Why: a band of refinement that runs along a lattice direction is bounded by straight rows
/// of MOVED_CENTER_2 hexagons (paper 000 Sec. 5.1), while one at another angle is a staircase
/// of MOVED_CENTER_1/2/3 hexagons whose rules (Sec. 5.2) refine more. The ten seeds of
/// `line-100` turned to 0°, 5°, 10°, 15°, 20.3°, 25°, 35°, 40°, 45°, 50°, 60° and 75° gave
/// mean `hex` counts of 19 886 to 20 871 triangles, and 18 132 and 18 126 at 30° and 90°,
/// along a lattice direction (with this turn, 18 147; unturned, at the dataset's 20.3°,
/// 20 343). The paper fixes only the inscribed
/// circle of the bounding hexagon (Sec. 4.1), not its rotation; every other input keeps the
/// flat-topped hexagon (corners at 0°, 60°, …, 300°).
///
/// Only +, −, ×, ÷ and square roots (correctly rounded in IEEE 754) make it, on sums taken in
/// input order, so it has the same bits on every machine.
pub fn principal_turn(points: &[Point]) -> Turn {
    let finite = || {
        points
            .iter()
            .filter(|p| p[0].is_finite() && p[1].is_finite())
    };
    let count = finite().count();
    if count < 2 {
        return Turn::NONE;
    }
    let n = count as f64;
    let mx = finite().map(|p| p[0]).sum::<f64>() / n;
    let my = finite().map(|p| p[1]).sum::<f64>() / n;
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in finite() {
        let (dx, dy) = (p[0] - mx, p[1] - my);
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    // The eigenvalues of the scatter matrix are (t ± d)/2; the principal axis is at φ with
    // (cos 2φ, sin 2φ) = (sxx − syy, 2·sxy)/d.
    let t = sxx + syy;
    let (a, b) = (sxx - syy, 2.0 * sxy);
    let d = (a * a + b * b).sqrt();
    let ratio = ELONGATED * ELONGATED;
    // λ_min ≤ ratio·λ_max ⇔ t − d ≤ ratio·(t + d).
    if !(t > 0.0 && d.is_finite() && t - d <= ratio * (t + d)) {
        return Turn::NONE;
    }
    let (c2, s2) = (a / d, b / d);
    let cos_phi = ((1.0 + c2) / 2.0).max(0.0).sqrt();
    let sin_phi = ((1.0 - c2) / 2.0).max(0.0).sqrt();
    let sin_phi = if s2 < 0.0 { -sin_phi } else { sin_phi };
    // θ = φ − 30°.
    let half_sqrt3 = 3f64.sqrt() / 2.0;
    let c = cos_phi * half_sqrt3 + sin_phi / 2.0;
    let s = sin_phi * half_sqrt3 - cos_phi / 2.0;
    // (cos φ, sin φ) is a unit vector up to rounding, so the norm is 1 within a few ulps.
    let norm = (c * c + s * s).sqrt();
    Turn {
        cos: c / norm,
        sin: s / norm,
    }
}

/// The least margin of a fitted hexagon's inscribed circle over the points' enclosing circle,
/// over the size of their coordinates (max(|cx|, |cy|) + r): 2^-34, some 2^16 roundings of a
/// coordinate. The relative 1e-9 alone is below an ulp where the points span far less than
/// their coordinates (a set 0.1 across at 1e7): a point on the circle then lay a few ulps
/// inside the hexagon's edge, and the triangles a mesher must fit between the two were too
/// small for f64 there (fuzz family "translated", case 1525, refused by `rhomb`). With the
/// margin the point lies at least 2^16 roundings inside, where a triangle spanning the gap
/// moves by rounding less than 1e-3°. Where the points span more than about 1/17 of their
/// distance from the origin (every dataset) the relative 1e-9 is the larger and decides.
pub const FIT_MARGIN: f64 = 1.0 / (1u64 << 34) as f64;

impl Hexagon {
    /// The hexagon whose inscribed circle has radius `inradius`.
    pub fn with_inradius(center: Point, inradius: f64) -> Hexagon {
        Hexagon {
            center,
            circumradius: inradius * 2.0 / 3f64.sqrt(),
            turn: Turn::NONE,
        }
    }

    /// The flat-topped hexagon of circumradius `circumradius` at `center`.
    pub fn new(center: Point, circumradius: f64) -> Hexagon {
        Hexagon {
            center,
            circumradius,
            turn: Turn::NONE,
        }
    }

    /// The lattice axes of the turned hexagon, [r·cos θ, √3·r·sin θ, r·sin θ, √3·r·cos θ]:
    /// the point at (X, Y) in units of r/2 and √3·r/2 along the unturned axes is
    /// `center + ((A·X − B·Y)·s, (C·X + D·Y)·s)` with s = 1/2 (`turned_point`).
    pub fn axes(&self) -> [f64; 4] {
        let r = self.circumradius;
        let sqrt3_r = r * 3f64.sqrt();
        let t = self.turn;
        [r * t.cos, sqrt3_r * t.sin, r * t.sin, sqrt3_r * t.cos]
    }

    /// Distance from the centre to the middle of an edge.
    pub fn inradius(&self) -> f64 {
        self.circumradius * 3f64.sqrt() / 2.0
    }

    /// The six corners, counter-clockwise, starting at angle 0.
    pub fn corners(&self) -> [Point; 6] {
        if !self.turn.is_none() {
            // The lattice's formula (`Lattice::grid_point` at level 0), so that the corners
            // it constructs are these bits.
            let axes = self.axes();
            return std::array::from_fn(|m| {
                turned_point(
                    self.center,
                    axes,
                    CORNER_X[m] as f64,
                    CORNER_Y[m] as f64,
                    0.5,
                )
            });
        }
        let r = self.circumradius;
        let h = r * 3f64.sqrt() / 2.0;
        let [cx, cy] = self.center;
        [
            [cx + r, cy],
            [cx + r / 2.0, cy + h],
            [cx - r / 2.0, cy + h],
            [cx - r, cy],
            [cx - r / 2.0, cy - h],
            [cx + r / 2.0, cy - h],
        ]
    }

    /// Area: 3√3/2 · r².
    pub fn area(&self) -> f64 {
        1.5 * 3f64.sqrt() * self.circumradius * self.circumradius
    }

    /// The bounding hexagon of a point set: its inscribed circle is the minimum enclosing
    /// circle of the points, enlarged by a relative 1e-9 or by `FIT_MARGIN` of the
    /// coordinates' size, whichever is more (and further, if rounding left any point outside
    /// a corner test).
    pub fn fitted(points: &[Point]) -> Hexagon {
        Hexagon::fitted_with(points, Turn::NONE)
    }

    /// `fitted`, turned onto the principal axis of elongated points (`principal_turn`): the
    /// root of the hex meshers for a point set (`hex::root_hexagon`).
    pub fn aligned(points: &[Point]) -> Hexagon {
        Hexagon::fitted_with(points, principal_turn(points))
    }

    fn fitted_with(points: &[Point], turn: Turn) -> Hexagon {
        // The least margin, FIT_MARGIN of the coordinates, decides only where the points span
        // less than about 1/17 of their distance from the origin (x ≈ 1e7, extent below 6e5).
        let (center, radius) = min_enclosing_circle(points);
        // A single point (or all points equal) has radius 0: fall back to a unit-size hexagon
        // scaled to the coordinates so that the hexagon is not degenerate.
        let base = if radius > 0.0 {
            radius
        } else {
            center[0].abs().max(center[1].abs()).max(1.0) * 1e-3
        };
        let scale = center[0].abs().max(center[1].abs()) + base;
        let inradius = (base * (1.0 + 1e-9)).max(base + FIT_MARGIN * scale);
        let mut hex = Hexagon {
            turn,
            ..Hexagon::with_inradius(center, inradius)
        };
        // Rounding can leave a point on the boundary; a few relative 1e-9 steps settle it.
        // Where the points lie far closer together than their coordinates' ulps allow
        // (two points 1e-11 of their coordinates apart), 1e-9 of the radius is below an ulp:
        // after 64 steps the step doubles until the corners move. Non-finite points (which
        // `Pslg::check` refuses) are never inside: skip them rather than loop.
        let finite = |p: &&Point| p[0].is_finite() && p[1].is_finite();
        for step in 0..128 {
            if points
                .iter()
                .filter(finite)
                .all(|&p| hex.contains_strictly(p))
            {
                break;
            }
            hex.circumradius *= 1.0 + 1e-9 * 2f64.powi((step - 63).max(0));
        }
        hex
    }

    /// True when `p` lies strictly inside the hexagon (exact orientation tests).
    pub fn contains_strictly(&self, p: Point) -> bool {
        let c = self.corners();
        (0..6).all(|i| orient2d(c[i], c[(i + 1) % 6], p) > 0.0)
    }
}

/// `center + ((A·x − B·y)·scale, (C·x + D·y)·scale)` for the axes [A, B, C, D] of
/// `Hexagon::axes`: the one formula of turned lattice positions. `scale` is a power of two.
/// Each coordinate is rounded once from a sum accurate to about
/// 2^-104 of its largest term, so its error is half an ulp of the coordinate itself (README
/// "Checks": a vertex near the origin must not carry the rounding of a centre far from it).
pub fn turned_point(center: Point, axes: [f64; 4], x: f64, y: f64, scale: f64) -> Point {
    let one = |o: f64, a: f64, b: f64| {
        // a·x + b·y as four exact parts, scaled exactly, then summed with o.
        let (p, pe) = two_product(a, x);
        let (q, qe) = two_product(b, y);
        accurate_sum([o, p * scale, q * scale, pe * scale, qe * scale])
    };
    [
        one(center[0], axes[0], -axes[1]),
        one(center[1], axes[2], axes[3]),
    ]
}

/// `o + step·n` rounded once (a fused multiply-add): a lattice coordinate whose error is half an
/// ulp of itself, whatever the size of `o`.
pub fn lattice_coordinate(o: f64, step: f64, n: f64) -> f64 {
    step.mul_add(n, o)
}

/// a·b as the rounded product and its exact error.
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// The sum of a few terms, accurate as in twice the working precision and rounded once
/// (Ogita, Rump and Oishi's Sum2: cascaded error-free additions).
fn accurate_sum<const N: usize>(terms: [f64; N]) -> f64 {
    let mut s = 0.0;
    let mut err = 0.0;
    for t in terms {
        let sum = s + t;
        let bv = sum - s;
        err += (s - (sum - bv)) + (t - bv);
        s = sum;
    }
    s + err
}

/// Minimum enclosing circle (centre, radius) of the finite points of a set by Welzl's randomized incremental
/// algorithm, with a fixed-seed shuffle so the result is the same on every run. Empty input
/// gives the origin with radius 0.
pub fn min_enclosing_circle(points: &[Point]) -> (Point, f64) {
    // Non-finite points (refused by `Pslg::check`) have no place in a circle: skip them.
    let mut pts: Vec<Point> = points
        .iter()
        .copied()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect();
    if pts.is_empty() {
        return ([0.0, 0.0], 0.0);
    }
    crate::shuffle::shuffle(&mut pts, 0x0068_6578_6d65_7368);
    let inside = |c: Point, r2: f64, p: Point| dist2(c, p) <= r2 * (1.0 + 1e-12);
    let mut c = pts[0];
    let mut r2 = 0.0;
    for i in 1..pts.len() {
        if inside(c, r2, pts[i]) {
            continue;
        }
        c = pts[i];
        r2 = 0.0;
        for j in 0..i {
            if inside(c, r2, pts[j]) {
                continue;
            }
            c = midpoint(pts[i], pts[j]);
            r2 = dist2(c, pts[i]);
            for k in 0..j {
                if inside(c, r2, pts[k]) {
                    continue;
                }
                match circumcenter(pts[i], pts[j], pts[k]) {
                    Some(cc) => {
                        c = cc;
                        r2 = dist2(cc, pts[i]);
                    }
                    None => {
                        // Collinear triple: the circle on the two farthest points.
                        let pairs = [(pts[i], pts[j]), (pts[i], pts[k]), (pts[j], pts[k])];
                        let (a, b) = pairs
                            .into_iter()
                            .max_by(|x, y| dist2(x.0, x.1).total_cmp(&dist2(y.0, y.1)))
                            .expect("three pairs");
                        c = midpoint(a, b);
                        r2 = dist2(c, a);
                    }
                }
            }
        }
    }
    // Make sure every point is inside despite rounding.
    let r2 = pts.iter().map(|&p| dist2(c, p)).fold(r2, f64::max);
    (c, r2.sqrt())
}

fn midpoint(a: Point, b: Point) -> Point {
    [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
}

/// Circumcentre of a triangle, `None` when the three points are collinear.
pub fn circumcenter(a: Point, b: Point, c: Point) -> Option<Point> {
    if orient2d(a, b, c) == 0.0 {
        return None;
    }
    let bx = b[0] - a[0];
    let by = b[1] - a[1];
    let cx = c[0] - a[0];
    let cy = c[1] - a[1];
    let d = 2.0 * (bx * cy - by * cx);
    let b2 = bx * bx + by * by;
    let c2 = cx * cx + cy * cy;
    Some([
        a[0] + (cy * b2 - by * c2) / d,
        a[1] + (bx * c2 - cx * b2) / d,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enclosing_circle_of_a_square_has_its_diagonal_as_diameter() {
        let (c, r) = min_enclosing_circle(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert!((c[0] - 0.5).abs() < 1e-12 && (c[1] - 0.5).abs() < 1e-12);
        assert!((r - 0.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn enclosing_circle_ignores_interior_points() {
        let mut pts = vec![[-1.0, 0.0], [1.0, 0.0]];
        pts.extend((0..50).map(|i| [0.01 * i as f64 - 0.25, 0.1]));
        let (c, r) = min_enclosing_circle(&pts);
        assert!(c[0].abs() < 1e-12 && c[1].abs() < 1e-12);
        assert!((r - 1.0).abs() < 1e-12);
    }

    #[test]
    fn fitting_a_hexagon_to_non_finite_points_returns() {
        let hex = Hexagon::fitted(&[[0.0, 0.0], [f64::NAN, 1.0], [1.0, f64::INFINITY]]);
        assert!(hex.contains_strictly([0.0, 0.0]));
        assert!(hex.circumradius.is_finite() && hex.circumradius > 0.0);
    }

    #[test]
    fn fitted_hexagon_contains_every_point_strictly() {
        let pts = [[0.0, 0.0], [1.0, 0.37], [0.5, 0.185], [0.25, 0.0925]];
        let hex = Hexagon::fitted(&pts);
        assert!(pts.iter().all(|&p| hex.contains_strictly(p)));
        let (_, r) = min_enclosing_circle(&pts);
        assert!((hex.inradius() - r).abs() <= r * 1e-8);
    }

    #[test]
    fn a_pair_far_closer_than_its_coordinates_ulps_allow_still_gets_a_fitted_hexagon() {
        // Found by the near-duplicates fuzz family at 1e-11 of the coordinates: 1e-9 of the
        // radius was below an ulp, and 64 such steps left the points on the boundary.
        for a in [0.0f64, 0.7, 1.9, 3.0] {
            let p = [0.849_768_232_370_818_4, 0.612_5];
            let q = [p[0] + 5e-12 * a.cos(), p[1] + 5e-12 * a.sin()];
            for hex in [Hexagon::fitted(&[p, q]), Hexagon::aligned(&[p, q])] {
                assert!(
                    hex.contains_strictly(p) && hex.contains_strictly(q),
                    "{hex:?}"
                );
                assert!(hex.circumradius < 1e-10, "{hex:?}");
            }
        }
    }

    /// The direction at 30° (centre to the neighbour across the upper-right edge) turned.
    fn turned_neighbour_direction(t: Turn) -> [f64; 2] {
        let (c30, s30) = (3f64.sqrt() / 2.0, 0.5);
        [t.cos * c30 - t.sin * s30, t.sin * c30 + t.cos * s30]
    }

    #[test]
    fn points_on_a_segment_turn_a_lattice_direction_onto_the_segment() {
        for dir in [
            [1.0, 0.37],
            [0.0, 1.0],
            [-2.0, 1.0],
            [1.0, -3.0],
            [1.0, 0.0],
        ] {
            let pts: Vec<Point> = [0.0, 0.11, 0.5, 0.52, 0.9, 1.0]
                .iter()
                .map(|&t| [3.0 + t * dir[0], -1.0 + t * dir[1]])
                .collect();
            let t = principal_turn(&pts);
            assert!((t.cos * t.cos + t.sin * t.sin - 1.0).abs() < 1e-15);
            let d = turned_neighbour_direction(t);
            let cross = d[0] * dir[1] - d[1] * dir[0];
            assert!(cross.abs() < 1e-12 * (dir[0] * dir[0] + dir[1] * dir[1]).sqrt());
            let hex = Hexagon::aligned(&pts);
            assert_eq!(hex.turn, t);
            assert!(pts.iter().all(|&p| hex.contains_strictly(p)));
            let (_, r) = min_enclosing_circle(&pts);
            assert!((hex.inradius() - r).abs() <= r * 1e-8);
        }
    }

    #[test]
    fn round_and_slightly_long_sets_keep_the_flat_topped_hexagon() {
        let square: Vec<Point> = (0..25).map(|i| [(i % 5) as f64, (i / 5) as f64]).collect();
        assert_eq!(principal_turn(&square), Turn::NONE);
        // Spread about 3.5 : 1 (standard deviations): not elongated enough (`ELONGATED` is 4 : 1).
        let band: Vec<Point> = (0..50)
            .map(|i| [(i % 10) as f64 * 3.0, (i / 10) as f64 * 2.0 * 3.0 / 3.5])
            .collect();
        assert_eq!(principal_turn(&band), Turn::NONE);
        assert_eq!(principal_turn(&[[1.0, 2.0]]), Turn::NONE);
        assert_eq!(Hexagon::aligned(&square), Hexagon::fitted(&square));
    }

    #[test]
    fn a_turned_hexagon_is_a_regular_hexagon_turned() {
        let pts = [[0.0, 0.0], [1.0, 0.37], [0.3, 0.111]];
        let hex = Hexagon::aligned(&pts);
        assert!(!hex.turn.is_none());
        let c = hex.corners();
        for m in 0..6 {
            let a = c[m];
            let b = c[(m + 1) % 6];
            assert!((dist(a, hex.center) - hex.circumradius).abs() < 1e-15);
            assert!((dist(a, b) - hex.circumradius).abs() < 1e-15);
        }
        // Corner 0 lies at θ: the turn of the flat-topped hexagon's corner at angle 0.
        let v = [c[0][0] - hex.center[0], c[0][1] - hex.center[1]];
        let back = hex.turn.undo(v);
        assert!((back[0] - hex.circumradius).abs() < 1e-15 && back[1].abs() < 1e-15);
    }
}
