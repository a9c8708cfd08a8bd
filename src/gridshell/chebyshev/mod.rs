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

/// The scheme of [`HemisphereNet::points`]: macro steps of at most `step` between consecutive
/// points of one curve, each with `levels` extrapolation levels.
const MARCH_SCHEME: Scheme = Scheme {
    step: 0.1,
    levels: 5,
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

    /// The state at `to` from the state `y` at `from`, in equal macro steps of at most the
    /// scheme's step.
    fn march(&self, from: f64, y: &State, to: f64) -> State {
        let steps = ((to - from) / self.scheme.step).ceil().max(0.0) as usize;
        let h = (to - from) / steps.max(1) as f64;
        (0..steps).fold(*y, |y, k| self.advance(from + k as f64 * h, &y, h))
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

    /// `point(u, v)` for every (u, v) of `uv`, to round-off (not bit for bit: 1.8e-14 R apart
    /// on |u|, |v| ≤ 1.6 R in the tests). Each net curve is integrated once, from one of its
    /// points to the next in short steps (`MARCH_SCHEME`), instead of from its canonical grid
    /// to every point: a cap's nodes lie on few curves at short spacings, and the n = 12,
    /// K = 8 footprint's nodes take 4 times less. Every point is still taken on the curve of
    /// its smaller |parameter|, so the net's u↔v symmetry stays exact.
    pub fn points(&self, uv: &[[f64; 2]]) -> Vec<[f64; 3]> {
        let mut out = vec![[f64::NAN; 3]; uv.len()];
        // Points by the curve `point` integrates along (the smaller |parameter|, by its bits),
        // each with where on it they lie.
        let mut curves: std::collections::BTreeMap<u64, Vec<(f64, usize)>> = Default::default();
        for (i, &[u, v]) in uv.iter().enumerate() {
            let (sigma, tau) = (u / self.radius, v / self.radius);
            if marchable(sigma, tau) {
                let (a, b) = (sigma.abs(), tau.abs());
                curves
                    .entry(a.min(b).to_bits())
                    .or_default()
                    .push((a.max(b), i));
            }
        }
        for (near, mut on) in curves {
            on.sort_by(|x, y| x.0.total_cmp(&y.0));
            let curve = NetCurve::new(&self.profile, f64::from_bits(near), MARCH_SCHEME);
            let (mut at, mut y) = (0.0, curve.nodes[0]);
            for (far, i) in on {
                y = curve.march(at, &y, far);
                at = far;
                let [u, v] = uv[i];
                let (sigma, tau) = (u / self.radius, v / self.radius);
                let (a, b) = (sigma.abs(), tau.abs());
                out[i] = scaled(
                    finish(&y, a < b, a == b, sigma < 0.0, tau < 0.0),
                    self.radius,
                );
            }
        }
        out
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
mod tests;
