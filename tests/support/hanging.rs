//! Heavy wires hanging between two pins at one height: the inextensible catenary, and the
//! inextensible heavy elastica (bending stiffness EI) with a rigid corner at midspan, shot from
//! a pin to the middle.

use super::ode::integrate;
use super::roots::bisect_increasing;

/// The steel wire of the issue-36 scenes: 10 m long between two pins 9 m apart, r = 1 mm,
/// under gravity (SI units).
pub mod wire {
    pub const LENGTH: f64 = 10.0;
    pub const SPAN: f64 = 9.0;
    pub const E: f64 = 2.1e11;
    pub const RADIUS: f64 = 1e-3;
    pub const DENSITY: f64 = 7850.0;
    pub const G: f64 = 9.81;
}

/// The inextensible catenary of length `length` over `span`: its parameter a from
/// L = 2a sinh(S/(2a)) (L decreases with a), and its sag a (cosh(S/(2a)) − 1).
pub fn catenary_sag(length: f64, span: f64) -> (f64, f64) {
    let a = bisect_increasing(
        |a| length - 2.0 * a * (span / (2.0 * a)).sinh(),
        0.1 * span,
        100.0 * span,
    );
    (a, a * ((span / (2.0 * a)).cosh() - 1.0))
}

/// Sag of an inextensible heavy elastica (weight `w` per length, bending stiffness `ei`) of
/// length `length` pinned (no moment) at two points `span` apart at one height, whose rest
/// shape turns by 2ψ at its midpoint (a corner, straight elsewhere). A rest curvature
/// concentrated at a point makes the tangent jump there by exactly its rest turn whatever the
/// moment (EI(κ − κ₀) = M stays finite), so by symmetry the left half ends at θ = −ψ.
/// Over the left half in arc length s, state (x, z, θ, M) with θ' = M/EI and M' = −t × N,
/// N(s) = (H, ws − wL/2) the force the rest of the wire exerts across s (the pins carry half
/// the weight each); at the pin x = z = M = 0, at the middle x = S/2 and θ = −ψ.
///
/// Near the pins the tension makes bending boundary layers of length ℓ = √(EI/H): single
/// shooting over L/2 amplifies errors by e^(L/2ℓ) (1.6e6 for the steel wire) and diverges, so
/// this is multiple shooting over `SEGMENTS` pieces (e^(L/(2·SEGMENTS·ℓ)) each), Newton on the
/// pin's θ and H and each later piece's starting state, from the catenary; continued in ψ
/// from 0 (the straight rest shape).
pub fn kinked_sag(length: f64, span: f64, w: f64, ei: f64, psi: f64) -> f64 {
    const SEGMENTS: usize = 20;
    let half = 0.5 * length;
    let ds = half / SEGMENTS as f64;
    let n = 2 + 4 * (SEGMENTS - 1);
    // Unknowns: θ(0), H, then (x, z, θ, M) at the start of pieces 1.. .
    let piece = |u: &[f64], k: usize| -> [f64; 4] {
        let h = u[1];
        let f = |s: f64, y: &[f64; 4]| {
            let (c, sn) = (y[2].cos(), y[2].sin());
            [c, sn, y[3] / ei, -(c * w * (s - half) - sn * h)]
        };
        let y0 = if k == 0 {
            [0.0, 0.0, u[0], 0.0]
        } else {
            std::array::from_fn(|i| u[2 + 4 * (k - 1) + i])
        };
        integrate(&f, y0, k as f64 * ds, (k + 1) as f64 * ds, 20)
    };
    let residual = |u: &[f64], target: f64| -> Vec<f64> {
        let mut r = Vec::with_capacity(n);
        for k in 0..SEGMENTS {
            let y = piece(u, k);
            if k + 1 < SEGMENTS {
                (0..4).for_each(|i| r.push(y[i] - u[2 + 4 * k + i]));
            } else {
                r.push(y[0] - 0.5 * span);
                r.push(y[2] - target);
            }
        }
        r
    };
    // The catenary z = a (cosh((x − S/2)/a) − cosh(S/(2a))) at arc lengths k·ds.
    let (a, _) = catenary_sag(length, span);
    let mut u = vec![-(span / (2.0 * a)).sinh().atan(), w * a];
    for k in 1..SEGMENTS {
        let sinh_x = (k as f64 * ds - half) / a; // sinh((x − S/2)/a) = (s − L/2)/a
        let xi = sinh_x.asinh();
        let z = a * (xi.cosh() - (span / (2.0 * a)).cosh());
        u.extend([0.5 * span + a * xi, z, sinh_x.atan(), 0.0]);
    }
    let scale: Vec<f64> = (0..n).map(|i| if i == 1 { w * a } else { 1.0 }).collect();
    let steps = 10;
    for step in 0..=steps {
        let target = -psi * step as f64 / steps as f64;
        let mut converged = false;
        for _ in 0..50 {
            let r = residual(&u, target);
            if r.iter().all(|x| x.abs() < 1e-12) {
                converged = true;
                break;
            }
            let mut jac = vec![vec![0.0; n + 1]; n];
            for j in 0..n {
                let d = 1e-7 * scale[j];
                let (mut up, mut um) = (u.clone(), u.clone());
                up[j] += d;
                um[j] -= d;
                let (rp, rm) = (residual(&up, target), residual(&um, target));
                (0..n).for_each(|i| jac[i][j] = (rp[i] - rm[i]) / (2.0 * d));
            }
            (0..n).for_each(|i| jac[i][n] = -r[i]);
            let du = solve_dense(jac);
            u.iter_mut().zip(&du).for_each(|(u, d)| *u += d);
        }
        assert!(converged, "kinked_sag: no convergence at step {step}");
    }
    let y = piece(&u, SEGMENTS - 1);
    -y[1]
}

/// Gaussian elimination with partial pivoting of an augmented n × (n + 1) system.
fn solve_dense(mut m: Vec<Vec<f64>>) -> Vec<f64> {
    let n = m.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&a, &b| m[a][c].abs().total_cmp(&m[b][c].abs()))
            .unwrap();
        m.swap(c, p);
        let (top, rest) = m.split_at_mut(c + 1);
        let pivot = &top[c];
        for row in rest {
            let f = row[c] / pivot[c];
            row.iter_mut()
                .zip(pivot)
                .skip(c)
                .for_each(|(x, p)| *x -= f * p);
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| m[r][k] * x[k]).sum();
        x[r] = (m[r][n] - s) / m[r][r];
    }
    x
}
