//! Chebyshev net on a sphere, as used for hemispherical elastic gridshells
//! (Baek, Sageman-Furnas, Jawed & Reis, PNAS 2018).
//!
//! # The net
//!
//! A Chebyshev net `r(u, v)` has `|r_u| = |r_v| = 1`; the angle `ω` between `r_u` and `r_v`
//! obeys `ω_uv = −K sin ω` with `K = 1/R²` on a sphere of radius `R`. The sphere is centred at
//! the origin, the pole is `(0, 0, R)` and the generators are the great circles
//! `r(u, 0) = R(sin(u/R), 0, cos(u/R))` and `r(0, v) = R(0, sin(v/R), cos(v/R))`.
//! Mirror symmetries: `r(−u, v)` is `r(u, v)` with `x` negated, `r(u, −v)` is `r(u, v)` with `y`
//! negated, and `r(v, u)` is `r(u, v)` with `x` and `y` swapped ([`mirror_uv`]).
//!
//! # Construction (why an ODE and not a grid)
//!
//! The Goursat data are constant (`ω = π/2` on both axes), so `ω` depends on `uv` alone:
//! `ω(u, v) = f(uv/R²)` where `s f'' + f' + sin f = 0`, `f(0) = π/2` (the regular solution at the
//! singular point `s = 0`; `f(−s) = π − f(s)`). `f` is built once from Taylor series: the series
//! at `s = 0` (its recurrence needs no initial slope), then re-expansions every 0.25 up to
//! `s = 4`, each from the value and slope of the previous piece, 20 terms each. The series at 0
//! alone would not do: its radius of convergence is only about 2.9.
//!
//! Given `ω`, each net curve `v = const` is a curve on the sphere with known geodesic
//! curvature. With `T = r_u`, `N = r/R` and the tangent-plane normal `B = N × T`, one has
//! `r_v = cos ω T + sin ω B`, and differentiating `r_u · r_v = cos ω` gives
//! `κ_g = r_uu · B = −ω_u`, while the normal curvature of every sphere curve is `−1/R`. So, in
//! the unit-sphere variables `σ = u/R`, `τ = v/R`, `ρ = r/R`,
//! `ρ' = T`, `T' = −τ f'(στ) (ρ × T) − ρ`, starting at `ρ = (0, sin τ, cos τ)`, `T = (1, 0, 0)`
//! (at `u = 0`, `ω = π/2`, so `r_u` is the horizontal unit vector normal to the generator).
//! This is a smooth non-stiff ODE, integrated by Gragg–Bulirsch–Stoer extrapolation (modified
//! midpoint with 2, 4, …, 12 substeps, Neville extrapolation in `h²`) on fixed macro steps of
//! `0.2` in `σ` from a canonical grid `σ = 0, 0.2, 0.4, …`, plus one partial step to the
//! requested `σ`. Every query goes through that grid, so `crossing`, `point` and `rod_points`
//! agree bit for bit.
//!
//! The compass construction on a fine grid is kept as an independent check (see the tests): it
//! is second order before the fold, so Richardson extrapolation over three grids reproduces
//! the crossings of this module. It is not used for the net itself because it breaks down past
//! the fold line `uv = 1.8616 R²` (where `ω = 0` and its cells degenerate), whereas the ODE is
//! smooth through the fold, so `point` is accurate over the whole square `|u|, |v| ≤ 2R`. The
//! gridshell stays inside the fold: `uv` at the rod ends is below R² for every allowed n.
//!
//! # Accuracy
//!
//! * `f` and `f'` are exact to round-off on `[0, 4.25]` (checked against a high-precision
//!   reference in the tests).
//! * With `k` extrapolation levels the integration error goes as `step^(2k)`; the default
//!   scheme (step 0.2, 6 levels) leaves it below round-off of the deepest extrapolations, so
//!   positions and half-lengths are good to about 1e-13 R.
//! * `L_k`: Newton on `z` along the rod (quadratic, stops once the step is ≤ 1e-15), so its
//!   error is the integration error above.
//! * n = 12, R = 1: central rods `L_6 = L_7 = 1.55938886587633` (`half_lengths[5]`,
//!   `half_lengths[6]`), outermost `L_1 = L_12 = 0.58546225448273`; 112 crossings inside (the
//!   closest to the equator has `|z| = 0.014`).
//!
//! docs/gridshell.md ("Accuracy of the net") has the measured errors, orders and costs.
//!
//! # Conventions
//!
//! * `offsets[k] = c_k = −πR/2 + (k+1)·a`, `a = spacing = πR/(n+1)`, `k = 0 … n−1`, so
//!   `offsets[n−1−k] = −offsets[k]` exactly.
//! * Family-u rod `k` is the curve `v = c_k`, parametrised by arclength `u ∈ [−L_k, L_k]`.
//! * Family-v rod `k` is the curve `u = c_k`; it is the [`mirror_uv`] image of family-u rod `k`:
//!   `r(c_k, v) = mirror_uv(r(v, c_k))`, so its ends are `mirror_uv(end_point(k, ±))` and its
//!   half-length is `half_lengths[k]`.
//! * `crossing(i, j) = r(c_i, c_j)` lies on family-v rod `i` and family-u rod `j`;
//!   `crossing(j, i) = mirror_uv(crossing(i, j))`.

use std::f64::consts::{FRAC_PI_2, PI};

type Vec3 = [f64; 3];
/// Position and unit tangent of a net curve on the unit sphere.
type State = [f64; 6];

fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

fn scaled(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Swaps x and y: the sphere isometry that exchanges the two rod families (`u ↔ v`).
pub fn mirror_uv(p: [f64; 3]) -> [f64; 3] {
    [p[1], p[0], p[2]]
}

// The nearest complex singularities of f are about 2.9 away, so 20 terms leave a truncation
// of (0.25/2.9)^20 ≈ 5e-22 even over the 0.25-long hop that seeds the next piece. The
// recurrence about a centre s_c > 0 amplifies rounding by about 1/s_c per order, which hops
// no longer than s_c keep harmless; hence the short, uniform spacing.
const PROFILE_TERMS: usize = 20;
const PROFILE_SPACING: f64 = 0.25;
const PROFILE_LAST_CENTER: f64 = 4.0;

type Series = [f64; PROFILE_TERMS];

/// The universal angle profile `f` with `ω(u, v) = f(uv/R²)`, as piecewise Taylor series.
#[derive(Clone, Debug)]
struct AngleProfile {
    /// Piece `p` is the expansion about `s = p · PROFILE_SPACING`.
    pieces: Vec<Series>,
}

/// Next coefficients of `sin f` and `cos f`, from `(sin f)' = cos f · f'` and
/// `(cos f)' = −sin f · f'`; needs `c[1..=m]`.
fn sin_cos_coefficient(c: &Series, s: &mut Series, co: &mut Series, m: usize) {
    let mut ss = 0.0;
    let mut cc = 0.0;
    for j in 1..=m {
        let jc = j as f64 * c[j];
        ss += jc * co[m - j];
        cc -= jc * s[m - j];
    }
    s[m] = ss / m as f64;
    co[m] = cc / m as f64;
}

/// At the singular point the coefficient of `t^k` in `s f'' + f' + sin f` is
/// `(k+1)² c_{k+1} + S_k`, which fixes every coefficient from `f(0) = π/2` alone.
fn taylor_at_origin() -> Series {
    let mut c = [0.0; PROFILE_TERMS];
    let mut s = [0.0; PROFILE_TERMS];
    let mut co = [0.0; PROFILE_TERMS];
    c[0] = FRAC_PI_2;
    // Exact values: cos(FRAC_PI_2) would leave a 6e-17 seed of the even part of f.
    s[0] = 1.0;
    co[0] = 0.0;
    for k in 0..PROFILE_TERMS - 1 {
        let k1 = (k + 1) as f64;
        c[k + 1] = -s[k] / (k1 * k1);
        sin_cos_coefficient(&c, &mut s, &mut co, k + 1);
    }
    c
}

/// About `center > 0` the coefficient of `t^k` is
/// `center (k+1)(k+2) c_{k+2} + (k+1)² c_{k+1} + S_k`.
fn taylor_at(center: f64, f0: f64, f1: f64) -> Series {
    let mut c = [0.0; PROFILE_TERMS];
    let mut s = [0.0; PROFILE_TERMS];
    let mut co = [0.0; PROFILE_TERMS];
    c[0] = f0;
    c[1] = f1;
    (s[0], co[0]) = f0.sin_cos();
    for k in 0..PROFILE_TERMS - 2 {
        let k1 = (k + 1) as f64;
        let k2 = (k + 2) as f64;
        c[k + 2] = -(k1 * k1 * c[k + 1] + s[k]) / (center * k1 * k2);
        sin_cos_coefficient(&c, &mut s, &mut co, k + 1);
    }
    c
}

fn horner(c: &Series, t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * t + ck)
}

fn horner_derivative(c: &Series, t: f64) -> f64 {
    (1..PROFILE_TERMS)
        .rev()
        .fold(0.0, |acc, k| acc * t + k as f64 * c[k])
}

impl AngleProfile {
    fn new() -> AngleProfile {
        let count = (PROFILE_LAST_CENTER / PROFILE_SPACING).round() as usize + 1;
        let mut pieces = Vec::with_capacity(count);
        pieces.push(taylor_at_origin());
        for p in 1..count {
            let prev = &pieces[p - 1];
            let (f0, f1) = (
                horner(prev, PROFILE_SPACING),
                horner_derivative(prev, PROFILE_SPACING),
            );
            pieces.push(taylor_at(p as f64 * PROFILE_SPACING, f0, f1));
        }
        AngleProfile { pieces }
    }

    /// Piece and local variable for `a ≥ 0`; beyond the last piece this extrapolates.
    fn locate(&self, a: f64) -> (&Series, f64) {
        let p = ((a / PROFILE_SPACING).round() as usize).min(self.pieces.len() - 1);
        (&self.pieces[p], a - p as f64 * PROFILE_SPACING)
    }

    fn value(&self, s: f64) -> f64 {
        let (c, t) = self.locate(s.abs());
        let v = horner(c, t);
        if s < 0.0 {
            PI - v
        } else {
            v
        }
    }

    /// `f'` is even because `f(−s) = π − f(s)`.
    fn slope(&self, s: f64) -> f64 {
        let (c, t) = self.locate(s.abs());
        horner_derivative(c, t)
    }
}

#[derive(Clone, Copy, Debug)]
struct Scheme {
    /// Macro step in `σ = u/R`.
    step: f64,
    /// Extrapolation levels; substep counts are 2, 4, …, 2·levels.
    levels: usize,
}

const MAX_LEVELS: usize = 12;
const DEFAULT_SCHEME: Scheme = Scheme {
    step: 0.2,
    levels: 6,
};

/// The net curve `τ = const` (unit sphere), with its states on the canonical grid cached.
struct NetCurve<'a> {
    profile: &'a AngleProfile,
    tau: f64,
    scheme: Scheme,
    nodes: Vec<State>,
}

impl<'a> NetCurve<'a> {
    fn new(profile: &'a AngleProfile, tau: f64, scheme: Scheme) -> NetCurve<'a> {
        let (s, c) = tau.sin_cos();
        NetCurve {
            profile,
            tau,
            scheme,
            nodes: vec![[0.0, s, c, 1.0, 0.0, 0.0]],
        }
    }

    fn deriv(&self, sigma: f64, y: &State) -> State {
        let rho = [y[0], y[1], y[2]];
        let kg = -self.tau * self.profile.slope(sigma * self.tau);
        let b = cross(rho, [y[3], y[4], y[5]]);
        [
            y[3],
            y[4],
            y[5],
            kg * b[0] - rho[0],
            kg * b[1] - rho[1],
            kg * b[2] - rho[2],
        ]
    }

    /// One Gragg–Bulirsch–Stoer step of length `h` (any sign) from `(s0, y0)`.
    fn advance(&self, s0: f64, y0: &State, h: f64) -> State {
        let f0 = self.deriv(s0, y0);
        let levels = self.scheme.levels;
        let mut prev = [[0.0; 6]; MAX_LEVELS];
        let mut cur = [[0.0; 6]; MAX_LEVELS];
        for j in 0..levels {
            let nsub = 2 * (j + 1);
            let hh = h / nsub as f64;
            let mut z0 = *y0;
            let mut z1: State = std::array::from_fn(|q| y0[q] + hh * f0[q]);
            for m in 1..nsub {
                let d = self.deriv(s0 + m as f64 * hh, &z1);
                let z2: State = std::array::from_fn(|q| z0[q] + 2.0 * hh * d[q]);
                z0 = z1;
                z1 = z2;
            }
            // Gragg's smoothing damps the midpoint rule's parasitic oscillation; with an even
            // substep count the error is a series in hh², which the Neville table removes.
            let d = self.deriv(s0 + h, &z1);
            cur[0] = std::array::from_fn(|q| 0.5 * (z1[q] + z0[q] + hh * d[q]));
            for k in 1..=j {
                let r = nsub as f64 / (2 * (j - k + 1)) as f64;
                let den = r * r - 1.0;
                cur[k] =
                    std::array::from_fn(|q| cur[k - 1][q] + (cur[k - 1][q] - prev[k - 1][q]) / den);
            }
            std::mem::swap(&mut prev, &mut cur);
        }
        prev[levels - 1]
    }

    fn node(&mut self, m: usize) -> State {
        while self.nodes.len() <= m {
            let k = self.nodes.len() - 1;
            let next = self.advance(
                k as f64 * self.scheme.step,
                &self.nodes[k],
                self.scheme.step,
            );
            self.nodes.push(next);
        }
        self.nodes[m]
    }

    /// State at `sigma ≥ 0`: the canonical grid node below it plus one partial step.
    fn at(&mut self, sigma: f64) -> State {
        let m = (sigma / self.scheme.step).floor().max(0.0) as usize;
        let base = self.node(m);
        let s0 = m as f64 * self.scheme.step;
        let dt = sigma - s0;
        if dt == 0.0 {
            base
        } else {
            self.advance(s0, &base, dt)
        }
    }

    /// Arclength `σ > 0` where the curve meets the equator, and the (unit) end point there.
    fn equator_crossing(&mut self) -> (f64, Vec3) {
        let h = self.scheme.step;
        let mut m = 1;
        // The bound only guards against an endless loop on nonsense input; every rod
        // offset |τ| < π/2 meets the equator well before σ = π/2 + 0.2.
        while self.node(m)[2] > 0.0 && (m as f64) * h < 2.0 * PI {
            m += 1;
        }
        let y0 = self.node(m - 1);
        let y1 = self.node(m);
        let s0 = (m - 1) as f64 * h;
        let mut dt = h * y0[2] / (y0[2] - y1[2]);
        let mut y = self.advance(s0, &y0, dt);
        for _ in 0..30 {
            // dz/dσ is the tangent's z component.
            let delta = y[2] / y[5];
            dt -= delta;
            y = self.advance(s0, &y0, dt);
            if delta.abs() <= 1e-15 {
                break;
            }
        }
        let p = [y[0], y[1], 0.0];
        (s0 + dt, scaled(p, 1.0 / norm(p)))
    }
}

/// Whether `point` should integrate to `(σ, τ)`; false for NaN and infinities too.
fn marchable(sigma: f64, tau: f64) -> bool {
    const MAX_PARAMETER: f64 = 64.0;
    sigma.abs() <= MAX_PARAMETER && tau.abs() <= MAX_PARAMETER
}

/// Maps a state of the octant `σ ≥ τ ≥ 0` to the requested octant, on the unit sphere.
fn finish(y: &State, swapped: bool, diagonal: bool, flip_x: bool, flip_y: bool) -> Vec3 {
    let mut p = [y[0], y[1], y[2]];
    if swapped {
        p = mirror_uv(p);
    }
    if diagonal {
        // On u = v the net lies in the plane x = y; enforce it so the u↔v symmetry is exact.
        let m = 0.5 * (p[0] + p[1]);
        p[0] = m;
        p[1] = m;
    }
    p = scaled(p, 1.0 / norm(p));
    if flip_x {
        p[0] = -p[0];
    }
    if flip_y {
        p[1] = -p[1];
    }
    p
}

/// Chebyshev net on the sphere of radius `radius` generated by two orthogonal great circles
/// through the pole (0,0,radius); sphere centre at the origin.
///
/// See the module documentation for the construction, the conventions and the accuracy
/// (about 1e-13 R for every position and half-length).
#[derive(Clone, Debug)]
pub struct HemisphereNet {
    pub radius: f64,
    /// Rods per family.
    pub n: usize,
    /// `πR/(n+1)`: the net arclength between neighbouring crossings.
    pub spacing: f64,
    /// `offsets[k] = −πR/2 + (k+1)·spacing`, evaluated as `R·((k+1) − (n+1)/2)·π/(n+1)` so
    /// that `offsets[n−1−k] == −offsets[k]` exactly.
    pub offsets: Vec<f64>,
    /// `half_lengths[k]`: net arclength from the rod's midpoint `u = 0` to its equator end.
    pub half_lengths: Vec<f64>,
    profile: AngleProfile,
    scheme: Scheme,
    crossings: Vec<Vec3>,
    ends: Vec<Vec3>,
}

impl HemisphereNet {
    /// Builds the net and tabulates crossings, half-lengths and ends.
    ///
    /// # Panics
    /// If `n == 0` or `radius` is not positive and finite.
    pub fn new(radius: f64, n: usize) -> HemisphereNet {
        Self::with_scheme(radius, n, DEFAULT_SCHEME)
    }

    fn with_scheme(radius: f64, n: usize, scheme: Scheme) -> HemisphereNet {
        assert!(n >= 1, "a gridshell needs at least one rod per family");
        assert!(
            radius.is_finite() && radius > 0.0,
            "sphere radius must be positive and finite, got {radius}"
        );
        let profile = AngleProfile::new();
        let unit_spacing = PI / (n + 1) as f64;
        let middle = (n + 1) as f64 / 2.0;
        // Small integers and halves are exact, so offsets[n-1-k] == -offsets[k] bit for bit.
        let unit_offsets: Vec<f64> = (0..n)
            .map(|k| ((k + 1) as f64 - middle) * unit_spacing)
            .collect();
        let first_nonnegative = n / 2;
        let canonical = |k: usize| {
            if unit_offsets[k] < 0.0 {
                n - 1 - k
            } else {
                k
            }
        };

        // raw[i][j] for offsets c_i ≥ c_j ≥ 0: curve τ = c_j evaluated at σ = c_i.
        let mut raw = vec![[0.0; 6]; n * n];
        let mut unit_half = vec![0.0; n];
        let mut ends = vec![[0.0; 3]; n];
        for j in first_nonnegative..n {
            let mut curve = NetCurve::new(&profile, unit_offsets[j], scheme);
            for i in j..n {
                raw[i * n + j] = curve.at(unit_offsets[i]);
            }
            let (l, e) = curve.equator_crossing();
            for k in [j, n - 1 - j] {
                unit_half[k] = l;
                let flip = if unit_offsets[k] < 0.0 { -1.0 } else { 1.0 };
                ends[k] = [e[0], flip * e[1], 0.0];
            }
        }
        let mut crossings = vec![[0.0; 3]; n * n];
        for i in 0..n {
            for j in 0..n {
                let (ci, cj) = (canonical(i), canonical(j));
                let (a, b) = (unit_offsets[ci], unit_offsets[cj]);
                let y = if a >= b {
                    &raw[ci * n + cj]
                } else {
                    &raw[cj * n + ci]
                };
                let p = finish(
                    y,
                    a < b,
                    a == b,
                    unit_offsets[i] < 0.0,
                    unit_offsets[j] < 0.0,
                );
                crossings[i * n + j] = scaled(p, radius);
            }
        }
        HemisphereNet {
            radius,
            n,
            spacing: radius * unit_spacing,
            offsets: unit_offsets.iter().map(|c| radius * c).collect(),
            half_lengths: unit_half.iter().map(|l| radius * l).collect(),
            profile,
            scheme,
            crossings,
            ends: ends.iter().map(|p| scaled(*p, radius)).collect(),
        }
    }

    /// Net point at the crossing of family-u rod j (`v = offsets[j]`) and family-v rod i
    /// (`u = offsets[i]`), i.e. `r(offsets[i], offsets[j])`; identical to that `point` call.
    pub fn crossing(&self, i: usize, j: usize) -> [f64; 3] {
        self.crossings[i * self.n + j]
    }

    /// Whether crossing (i, j) is strictly above the equator.
    pub fn crossing_inside(&self, i: usize, j: usize) -> bool {
        self.crossing(i, j)[2] > 0.0
    }

    /// Equator end of family-u rod k on the +u side: `r(half_lengths[k], offsets[k])`; the −u end
    /// is its mirror in x. Its z is set to exactly 0 (`z(point(L_k, c_k))` is ≤ 4.2e-15 R) and
    /// it lies on the sphere to round-off. Family-v rod k ends at `mirror_uv` of these.
    pub fn end_point(&self, k: usize, positive: bool) -> [f64; 3] {
        let p = self.ends[k];
        if positive {
            p
        } else {
            [-p[0], p[1], p[2]]
        }
    }

    /// Net point at arbitrary (u, v), accurate to about 1e-13 R for `|u|, |v| ≤ 2R`, a region
    /// that contains every rod (`L_k < πR/2`) and the fold line `uv = 1.8616 R²`. Farther out
    /// the angle profile is extrapolated and accuracy degrades. Gives NaN for non-finite input
    /// and for `|u|` or `|v|` above 64R, where the march would only waste time and memory.
    pub fn point(&self, u: f64, v: f64) -> [f64; 3] {
        let (sigma, tau) = (u / self.radius, v / self.radius);
        if !marchable(sigma, tau) {
            return [f64::NAN; 3];
        }
        let (a, b) = (sigma.abs(), tau.abs());
        // Always integrating along the curve of the smaller |parameter| makes the u↔v
        // symmetry exact instead of true only to integration error.
        let y = if a >= b {
            NetCurve::new(&self.profile, b, self.scheme).at(a)
        } else {
            NetCurve::new(&self.profile, a, self.scheme).at(b)
        };
        scaled(
            finish(&y, a < b, a == b, sigma < 0.0, tau < 0.0),
            self.radius,
        )
    }

    /// `point(u, offsets[k])` for every `u` in `us`, bit for bit, integrating the rod once
    /// instead of once per point. Family-v rod `k` is `mirror_uv` of the result.
    pub fn rod_points(&self, k: usize, us: &[f64]) -> Vec<[f64; 3]> {
        let tau = self.offsets[k] / self.radius;
        let b = tau.abs();
        let mut rod = NetCurve::new(&self.profile, b, self.scheme);
        us.iter()
            .map(|&u| {
                let sigma = u / self.radius;
                let a = sigma.abs();
                if !marchable(sigma, tau) {
                    [f64::NAN; 3]
                } else if a >= b {
                    let y = rod.at(a);
                    scaled(
                        finish(&y, false, a == b, sigma < 0.0, tau < 0.0),
                        self.radius,
                    )
                } else {
                    self.point(u, self.offsets[k])
                }
            })
            .collect()
    }

    /// Angle between the net curves at (u, v), in radians (pi/2 at the pole): the angle from
    /// `r_u` to `r_v`, positive towards the outward normal, which is `f(uv/R²)` in every
    /// quadrant. It lies in `(0, π)` up to the fold line `|uv| = 1.8616 R²`; beyond it the net
    /// folds over and the angle leaves that range (below 0 where `uv > 0`, above π where
    /// `uv < 0`). Accurate to 2.2e-16 for `|uv| ≤ 4.25 R²`.
    pub fn angle(&self, u: f64, v: f64) -> f64 {
        self.profile.value((u / self.radius) * (v / self.radius))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn max_abs_diff(p: Vec3, q: Vec3) -> f64 {
        (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f64::max)
    }

    fn distance(p: Vec3, q: Vec3) -> f64 {
        norm([p[0] - q[0], p[1] - q[1], p[2] - q[2]])
    }

    fn mirror_x(p: Vec3) -> Vec3 {
        [-p[0], p[1], p[2]]
    }

    fn mirror_y(p: Vec3) -> Vec3 {
        [p[0], -p[1], p[2]]
    }

    /// Deterministic sample of parameters in [-span, span].
    fn samples(count: usize, span: f64) -> Vec<(f64, f64)> {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * span - span
        };
        (0..count).map(|_| (next(), next())).collect()
    }

    #[test]
    fn gridshell_counts_and_half_lengths() {
        let net = HemisphereNet::new(1.0, 12);
        let inside = (0..12)
            .flat_map(|i| (0..12).map(move |j| (i, j)))
            .filter(|&(i, j)| net.crossing_inside(i, j))
            .count();
        assert_eq!(inside, 112);

        let mut ends = 0;
        for k in 0..12 {
            for positive in [true, false] {
                for p in [
                    net.end_point(k, positive),
                    mirror_uv(net.end_point(k, positive)),
                ] {
                    assert!((norm(p) - 1.0).abs() <= 1e-15, "end off the sphere: {p:?}");
                    if p[2] == 0.0 {
                        ends += 1;
                    }
                }
            }
            // The ends come from a root find along the rod, so compare with the point()
            // path at the same parameters: both are accurate to ~5e-14.
            let p = net.point(net.half_lengths[k], net.offsets[k]);
            assert!(p[2].abs() <= 1e-13, "rod {k}: z = {:e}", p[2]);
            assert!(max_abs_diff(p, net.end_point(k, true)) <= 1e-13);
        }
        assert_eq!(ends, 48);

        for k in [5, 6] {
            assert!((net.half_lengths[k] - 1.559389).abs() < 1e-6);
        }
        for k in [0, 11] {
            assert!((net.half_lengths[k] - 0.585462).abs() < 1e-6);
        }
    }

    #[test]
    fn all_points_lie_on_the_sphere() {
        for radius in [1.0, 0.37, 2.5] {
            for n in [1, 2, 7, 12, 16] {
                let net = HemisphereNet::new(radius, n);
                let off = |p: Vec3| (norm(p) - radius).abs() / radius;
                for i in 0..n {
                    for j in 0..n {
                        assert!(off(net.crossing(i, j)) <= 1e-12);
                    }
                    assert!(off(net.end_point(i, true)) <= 1e-12);
                    assert!(off(net.end_point(i, false)) <= 1e-12);
                }
                for (u, v) in samples(20, 2.0 * radius) {
                    assert!(off(net.point(u, v)) <= 1e-12);
                }
            }
        }
    }

    #[test]
    fn generators_are_the_great_circles() {
        let radius = 1.7;
        let net = HemisphereNet::new(radius, 12);
        for (t, _) in samples(20, 2.0 * radius) {
            let (s, c) = (t / radius).sin_cos();
            let expected_u = [radius * s, 0.0, radius * c];
            let expected_v = [0.0, radius * s, radius * c];
            assert!(max_abs_diff(net.point(t, 0.0), expected_u) <= 1e-13 * radius);
            assert!(max_abs_diff(net.point(0.0, t), expected_v) <= 1e-13 * radius);
            assert_eq!(net.angle(t, 0.0), FRAC_PI_2);
            assert_eq!(net.angle(0.0, t), FRAC_PI_2);
        }
    }

    /// Polyline length of rod `k` over `[from, to]`. A chord misses `κ²h³/24 + O(h⁵)` of its
    /// arc, so the sum has an even error expansion in `1/m`; two Richardson steps over `m`,
    /// `2m`, `4m` chords leave `O(m⁻⁶)`.
    fn rod_arclength(net: &HemisphereNet, k: usize, from: f64, to: f64, m: usize) -> f64 {
        let chord_sum = |m: usize| {
            let us: Vec<f64> = (0..=m)
                .map(|q| from + (to - from) * q as f64 / m as f64)
                .collect();
            let pts = net.rod_points(k, &us);
            pts.windows(2).map(|w| distance(w[0], w[1])).sum::<f64>()
        };
        richardson2(chord_sum(m), chord_sum(2 * m), chord_sum(4 * m))
    }

    /// Eliminates the `h²` and `h⁴` terms from values at `h`, `h/2`, `h/4`.
    fn richardson2(coarse: f64, mid: f64, fine: f64) -> f64 {
        let a = (4.0 * mid - coarse) / 3.0;
        let b = (4.0 * fine - mid) / 3.0;
        (16.0 * b - a) / 15.0
    }

    #[test]
    fn crossings_are_one_spacing_apart_along_every_rod() {
        // The polyline error left after Richardson is O(m⁻⁶), negligible; what remains is the
        // position error (≤ 6e-14): along a smooth error field the chord sum changes by about
        // the error at the two ends, so ≤ 1.2e-13, times ≈ 2 for the Richardson weights.
        let net = HemisphereNet::new(1.0, 12);
        let mut worst: f64 = 0.0;
        for k in 0..12 {
            for i in 0..11 {
                let len = rod_arclength(&net, k, net.offsets[i], net.offsets[i + 1], 16);
                worst = worst.max((len - net.spacing).abs());
            }
            // The rod is arclength-parametrised all the way to its equator ends.
            let half = rod_arclength(&net, k, 0.0, net.half_lengths[k], 64);
            worst = worst.max((half - net.half_lengths[k]).abs());
        }
        assert!(worst <= 1e-12, "arclength error {worst:e}");
    }

    #[test]
    fn symmetries_are_exact() {
        // Only one octant is ever integrated and the rest is sign flips and swaps, so these
        // hold bit for bit (stricter than a 1e-12 tolerance would check).
        for n in [7, 12] {
            let net = HemisphereNet::new(1.3, n);
            for i in 0..n {
                for j in 0..n {
                    let p = net.crossing(i, j);
                    assert_eq!(p, mirror_uv(net.crossing(j, i)));
                    assert_eq!(p, mirror_x(net.crossing(n - 1 - i, j)));
                    assert_eq!(p, mirror_y(net.crossing(i, n - 1 - j)));
                }
                assert_eq!(net.crossing(i, i)[0], net.crossing(i, i)[1]);
                assert_eq!(net.offsets[n - 1 - i], -net.offsets[i]);
                assert_eq!(net.half_lengths[n - 1 - i], net.half_lengths[i]);
                assert_eq!(net.end_point(i, false), mirror_x(net.end_point(i, true)));
                assert_eq!(
                    net.end_point(n - 1 - i, true),
                    mirror_y(net.end_point(i, true))
                );
            }
            for (u, v) in samples(30, 2.0 * 1.3) {
                let p = net.point(u, v);
                assert_eq!(p, mirror_uv(net.point(v, u)));
                assert_eq!(p, mirror_x(net.point(-u, v)));
                assert_eq!(p, mirror_y(net.point(u, -v)));
                assert_eq!(net.angle(u, v), net.angle(v, u));
                assert!((net.angle(-u, v) - (PI - net.angle(u, v))).abs() <= 1e-15);
            }
        }
    }

    #[test]
    fn crossings_and_rod_points_are_the_point_function() {
        let net = HemisphereNet::new(1.0, 12);
        for i in 0..12 {
            for j in 0..12 {
                assert_eq!(
                    net.crossing(i, j),
                    net.point(net.offsets[i], net.offsets[j])
                );
            }
        }
        let us: Vec<f64> = (-40..=40).map(|q| q as f64 * 0.04).collect();
        for k in [0, 3, 6, 11] {
            let pts = net.rod_points(k, &us);
            for (p, &u) in pts.iter().zip(&us) {
                assert_eq!(*p, net.point(u, net.offsets[k]));
            }
        }
    }

    /// Signed area of the spherical polygon with geodesic edges through `pts` (unit sphere),
    /// summed over triangles fanned from the normalised vertex mean.
    fn polygon_area(pts: &[Vec3]) -> f64 {
        let mut c = [0.0; 3];
        for p in pts {
            c = [c[0] + p[0], c[1] + p[1], c[2] + p[2]];
        }
        let c = scaled(c, 1.0 / norm(c));
        let mut area = 0.0;
        for (q, &a) in pts.iter().enumerate() {
            let b = pts[(q + 1) % pts.len()];
            let triple = dot(c, cross(a, b));
            area += 2.0 * triple.atan2(1.0 + dot(c, a) + dot(a, b) + dot(b, c));
        }
        area
    }

    /// Area of the net quadrilateral `[u0,u1]×[v0,v1]` on the unit sphere, from its boundary
    /// sampled at `m`, `2m` and `4m` points per side. The geodesic polygon misses
    /// `κ_g h³/12 + O(h⁵)` per edge: an even expansion, so Richardson applies.
    fn net_quad_area(net: &HemisphereNet, u: (f64, f64), v: (f64, f64), m: usize) -> f64 {
        let area = |m: usize| {
            let mut pts = Vec::with_capacity(4 * m);
            let t = |q: usize| q as f64 / m as f64;
            pts.extend((0..m).map(|q| net.point(u.0 + (u.1 - u.0) * t(q), v.0)));
            pts.extend((0..m).map(|q| net.point(u.1, v.0 + (v.1 - v.0) * t(q))));
            pts.extend((0..m).map(|q| net.point(u.1 + (u.0 - u.1) * t(q), v.1)));
            pts.extend((0..m).map(|q| net.point(u.0, v.1 + (v.0 - v.1) * t(q))));
            polygon_area(&pts)
        };
        richardson2(area(m), area(2 * m), area(4 * m))
    }

    #[test]
    fn hazzidakis_area_equals_angle_excess() {
        // K·Area = ∫∫ K sin ω du dv = −∫∫ ω_uv du dv = ω(u1,v0) + ω(u0,v1) − ω(u0,v0) − ω(u1,v1).
        // The interior angles are ω at (u0,v0) and (u1,v1), where both edges leave along
        // +r_u, +r_v or −r_u, −r_v, and π − ω at the other two corners, so this is
        // K·Area = 2π − Σ interior angles (the opposite sign of a geodesic polygon's excess).
        // Bound: position error (≤ 6e-14) times the perimeter (≤ 5), times ≈ 2
        // for the Richardson weights, plus 4 angle errors of 2e-16: ≤ 6e-13.
        let net = HemisphereNet::new(1.0, 12);
        let c = &net.offsets;
        let quads = [
            ((c[5], c[6]), (c[5], c[6])), // the cell around the pole
            ((c[6], c[7]), (c[8], c[9])),
            ((c[2], c[3]), (c[9], c[10])),
            ((c[0], c[1]), (c[4], c[5])),
            ((c[9], c[10]), (c[1], c[2])),
            ((-0.4, 0.9), (0.1, 1.2)),
        ];
        for &(u, v) in &quads {
            let area = net_quad_area(&net, u, v, 32);
            let w = |a: f64, b: f64| net.angle(a, b);
            let hazzidakis = w(u.1, v.0) + w(u.0, v.1) - w(u.0, v.0) - w(u.1, v.1);
            let interior = w(u.0, v.0) + (PI - w(u.1, v.0)) + w(u.1, v.1) + (PI - w(u.0, v.1));
            assert!(area > 0.0);
            assert!(
                (area - hazzidakis).abs() <= 1e-12,
                "quad {u:?}x{v:?}: area {area} vs {hazzidakis}"
            );
            assert!((area - (2.0 * PI - interior)).abs() <= 1e-12);
        }
    }

    #[test]
    fn angle_matches_the_geometry() {
        // Central differences with one Richardson step (δ = 1e-3): truncation ~δ⁴|r⁽⁵⁾|/30
        // ≈ 1e-13, but the position error (≤ 6e-14, not smooth across grid nodes) is amplified
        // by ≈ 1.5/δ, so up to ≈ 1e-10, including points past the fold.
        let net = HemisphereNet::new(1.0, 12);
        let d = 1e-3;
        let derivative = |f: &dyn Fn(f64) -> Vec3| -> Vec3 {
            let (p1, m1, p2, m2) = (f(d), f(-d), f(2.0 * d), f(-2.0 * d));
            std::array::from_fn(|c| {
                (4.0 * (p1[c] - m1[c]) / (2.0 * d) - (p2[c] - m2[c]) / (4.0 * d)) / 3.0
            })
        };
        let mut pts = samples(12, 1.5);
        pts.extend([(1.5, 1.5), (1.2, -1.6), (0.3, 0.2)]);
        for (u, v) in pts {
            let ru = derivative(&|t| net.point(u + t, v));
            let rv = derivative(&|t| net.point(u, v + t));
            let normal = net.point(u, v);
            let signed = dot(cross(ru, rv), normal).atan2(dot(ru, rv));
            // atan2 gives (−π, π]; past the fold with uv < 0 the profile exceeds π.
            let wrap = (signed - net.angle(u, v) + PI).rem_euclid(2.0 * PI) - PI;
            assert!((norm(ru) - 1.0).abs() <= 1e-10 && (norm(rv) - 1.0).abs() <= 1e-10);
            assert!(
                wrap.abs() <= 1e-10,
                "({u}, {v}): geometric {signed} vs {}",
                net.angle(u, v)
            );
        }
    }

    #[test]
    fn scaling_by_two_is_exact() {
        let one = HemisphereNet::new(1.0, 12);
        let two = HemisphereNet::new(2.0, 12);
        let double = |p: Vec3| scaled(p, 2.0);
        assert_eq!(two.spacing, 2.0 * one.spacing);
        for i in 0..12 {
            assert_eq!(two.offsets[i], 2.0 * one.offsets[i]);
            assert_eq!(two.half_lengths[i], 2.0 * one.half_lengths[i]);
            assert_eq!(two.end_point(i, true), double(one.end_point(i, true)));
            for j in 0..12 {
                assert_eq!(two.crossing(i, j), double(one.crossing(i, j)));
            }
        }
        for (u, v) in samples(20, 2.0) {
            assert_eq!(two.point(2.0 * u, 2.0 * v), double(one.point(u, v)));
            assert_eq!(two.angle(2.0 * u, 2.0 * v), one.angle(u, v));
        }
    }

    /// Discrete compass net on the unit sphere, `(nmax+1)²` nodes of step `h`: each new node
    /// is the mirror image of the opposite corner in the plane through the centre and its two
    /// neighbours, i.e. the other point at equal chord distance from both.
    fn compass_net(h: f64, nmax: usize) -> Vec<Vec3> {
        let w = nmax + 1;
        let mut g = vec![[0.0; 3]; w * w];
        for i in 0..w {
            let (s, c) = (i as f64 * h).sin_cos();
            g[i * w] = [s, 0.0, c];
            g[i] = [0.0, s, c];
        }
        for i in 1..w {
            for j in 1..w {
                let o = g[(i - 1) * w + j - 1];
                let nrm = cross(g[i * w + j - 1], g[(i - 1) * w + j]);
                let k = 2.0 * dot(o, nrm) / dot(nrm, nrm);
                g[i * w + j] = [o[0] - k * nrm[0], o[1] - k * nrm[1], o[2] - k * nrm[2]];
            }
        }
        g
    }

    #[test]
    fn independent_compass_construction_agrees() {
        // The compass error is second order, so two Richardson steps over h = a/8, a/16, a/32
        // leave the next term of the expansion and the compass round-off (which grows with the
        // cell count), both below the tolerance.
        let n = 12;
        let net = HemisphereNet::new(1.0, n);
        let a = PI / (n + 1) as f64;
        let quadrant: Vec<usize> = (n / 2..n).collect();
        let mut levels = Vec::new();
        for m in [8usize, 16, 32] {
            let nmax = (2 * n - n - 1) * m / 2;
            let g = compass_net(a / m as f64, nmax);
            let node = |k: usize| (2 * (k + 1) - (n + 1)) * m / 2;
            let values: Vec<Vec3> = quadrant
                .iter()
                .flat_map(|&i| quadrant.iter().map(move |&j| (i, j)))
                .map(|(i, j)| g[node(i) * (nmax + 1) + node(j)])
                .collect();
            levels.push(values);
        }
        let exact: Vec<Vec3> = quadrant
            .iter()
            .flat_map(|&i| quadrant.iter().map(move |&j| (i, j)))
            .map(|(i, j)| net.crossing(i, j))
            .collect();
        let error = |vals: &[Vec3]| {
            vals.iter()
                .zip(&exact)
                .map(|(p, q)| max_abs_diff(*p, *q))
                .fold(0.0, f64::max)
        };
        let order = (error(&levels[0]) / error(&levels[1])).log2();
        assert!((order - 2.0).abs() < 0.01, "compass order {order}");
        let combine = |fine: &[Vec3], coarse: &[Vec3], f: f64| -> Vec<Vec3> {
            fine.iter()
                .zip(coarse)
                .map(|(p, q)| std::array::from_fn(|c| (f * p[c] - q[c]) / (f - 1.0)))
                .collect()
        };
        let r01 = combine(&levels[1], &levels[0], 4.0);
        let r12 = combine(&levels[2], &levels[1], 4.0);
        let r = combine(&r12, &r01, 16.0);
        assert!(
            error(&r) <= 1e-11,
            "compass/Richardson disagrees by {:e}",
            error(&r)
        );
    }

    #[test]
    fn angle_profile_matches_high_precision_reference() {
        // 40-digit values (rounded to f64) from the power series at s = 0 (s ≤ 2.25) and 80-term
        // re-expansions (s ≥ 3.5), computed independently with mpmath.
        let reference = [
            (0.3, 1.2722869479746892, -0.9851558430415446),
            (1.0, 0.6227635630548913, -0.8507241336855917),
            (1.5, 0.2334159451765729, -0.7027823575902886),
            (2.25, -0.20496092513869799, -0.4683465323070939),
            (3.5, -0.581202344658288, -0.15440441145467665),
            (4.0, -0.6348639994258749, -0.06331701338385444),
        ];
        let profile = AngleProfile::new();
        for (s, f, df) in reference {
            assert!((profile.value(s) - f).abs() <= 1e-15, "f({s})");
            assert!((profile.slope(s) - df).abs() <= 1e-15, "f'({s})");
        }
        assert!(profile.value(1.86159167731546).abs() <= 1e-15);
        assert_eq!(profile.value(0.0), FRAC_PI_2);
    }

    #[test]
    fn integration_error_is_below_the_stated_tolerance() {
        // The scheme with half the step and two more levels is ~2^12 times more accurate in
        // truncation, so the difference measures the default's error, at crossings and
        // half-lengths and over |u|, |v| ≤ 2 (fold included).
        let net = HemisphereNet::new(1.0, 12);
        let fine = HemisphereNet::with_scheme(
            1.0,
            12,
            Scheme {
                step: 0.1,
                levels: 8,
            },
        );
        for i in 0..12 {
            assert!((net.half_lengths[i] - fine.half_lengths[i]).abs() <= 1e-13);
            assert!(max_abs_diff(net.end_point(i, true), fine.end_point(i, true)) <= 1e-13);
            for j in 0..12 {
                assert!(max_abs_diff(net.crossing(i, j), fine.crossing(i, j)) <= 1e-13);
            }
        }
        for (u, v) in samples(200, 2.0) {
            assert!(
                max_abs_diff(net.point(u, v), fine.point(u, v)) <= 1e-13,
                "({u}, {v})"
            );
        }
    }

    #[test]
    fn smallest_nets_are_the_generators() {
        let net = HemisphereNet::new(3.0, 1);
        assert_eq!(net.offsets, vec![0.0]);
        assert_eq!(net.crossing(0, 0), [0.0, 0.0, 3.0]);
        assert!((net.half_lengths[0] - 1.5 * PI).abs() <= 1e-13 * 3.0);
        assert!(max_abs_diff(net.end_point(0, true), [3.0, 0.0, 0.0]) <= 1e-13 * 3.0);

        let net = HemisphereNet::new(1.0, 2);
        assert!((net.offsets[1] - PI / 6.0).abs() <= 1e-16);
        assert!(net.crossing_inside(0, 1) && net.crossing_inside(1, 1));
    }

    #[test]
    fn unreachable_parameters_give_nan() {
        let net = HemisphereNet::new(1.0, 4);
        for (u, v) in [
            (f64::NAN, 0.0),
            (0.0, f64::INFINITY),
            (1e9, 0.3),
            (0.2, -65.0),
        ] {
            assert!(net.point(u, v).iter().all(|c| c.is_nan()));
        }
        let pts = net.rod_points(1, &[0.1, f64::NEG_INFINITY, 1e12]);
        assert!(pts[0].iter().all(|c| c.is_finite()));
        assert!(pts[1..].iter().flatten().all(|c| c.is_nan()));
    }

    #[test]
    #[should_panic(expected = "at least one rod")]
    fn zero_rods_panics() {
        let _ = HemisphereNet::new(1.0, 0);
    }

    #[test]
    #[should_panic(expected = "positive and finite")]
    fn non_positive_radius_panics() {
        let _ = HemisphereNet::new(0.0, 3);
    }

    #[test]
    #[should_panic(expected = "positive and finite")]
    fn non_finite_radius_panics() {
        let _ = HemisphereNet::new(f64::NAN, 3);
    }
}
