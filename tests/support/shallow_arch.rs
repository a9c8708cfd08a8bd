//! The clamped–clamped shallow cosine arch (Euler–Bernoulli bending plus the uniform axial
//! strain of a span held by its clamps): its equilibria without load and the first instability
//! of a push at its centre, in closed form.
//!
//! Rest shape w₀(x) = (h/2)(1 − cos 2πx/L), stress-free; energy
//! U = EI/2 ∫(w'' − w₀'')² + EA/(8L) (∫ w'² − w₀'²)². w is expanded in the clamped–clamped
//! buckling modes φ_k: symmetric 1 − cos(N x/L), N = 2πk, and antisymmetric
//! 1 − 2x/L − cos(N x/L) + 2 sin(N x/L)/N with tan(N/2) = N/2 (N₂ = 8.9868…). They are
//! orthogonal in ∫φ'φ' and in ∫φ''φ'', with ∫φ''² = (N/L)² ∫φ'², so with a compressive axial
//! force P = −EA ε, ε = (1/2L) ∫(w'² − w₀'²), each coefficient obeys
//! (P_k − P) a_k = P_k a₀_k + (load), P_k = EI N_k²/L² (P₁ = 4π²EI/L², P₂ = 2.0457 P₁):
//!
//! * inverted (symmetric) states, a₁ = −a·h/2: P = P₁(1 + 1/a) and the strain condition give
//!   a(1 − a) = 16 r²/h² = 4/(3Q²) (r² = I/A, Q = h/t with t² = 12 r²): two states when
//!   Q > √(16/3) = 2.309 (Qiu, Lang & Slocum 2004); the larger root a₊ is stable against
//!   mode 1, and against the antisymmetric mode 2 only while P < P₂, i.e. a₊ > a* = P₁/(P₂ − P₁)
//!   = 0.95630, i.e. Q > Q* = √(4/(3 a*(1 − a*))) = 5.6456. Between 2.31 and 5.65 the inverted
//!   state has index 1 (the single arch is not bistable); 2.31 is the threshold only when mode 2
//!   is suppressed (Qiu's double beam). Its energy: EI h² π⁴ (1 + a)²/L³ + P² L/(2EA);
//! * asymmetric (S-shaped) states, a₂ ≠ 0: P = P₂, so a₁ = −a*·h/2, and
//!   a₂² ∫φ₂'² = (h²/4)(1 − a*²)(2π²/L) − 2LP₂/EA > 0 exactly when Q > Q*: a mirror pair of
//!   index-1 saddles, born from the inverted state at Q*, the barrier between it and rest.
//!   Energy: EI h² π⁴ (1 + a*)²/L³ + ½ P₂ a₂²∫φ₂'² + P₂² L/(2EA).
//!
//! `examples/shallow_arch.py` finds every stationary point of the same energy by Galerkin
//! (16 modes, quadrature, Newton from random starts): it agrees with these to all digits printed.

use std::f64::consts::PI;

/// A shallow arch: span `l` (m), bending stiffness `ei` (N·m²), axial stiffness `ea` (N), rise
/// `h` (m).
#[derive(Debug, Clone, Copy)]
pub struct ShallowArch {
    pub l: f64,
    pub ei: f64,
    pub ea: f64,
    pub h: f64,
}

/// An equilibrium: total energy (J), the crown's height w(L/2) (m), the compression P (N).
#[derive(Debug, Clone, Copy)]
pub struct ArchState {
    pub energy: f64,
    pub crown: f64,
    pub compression: f64,
}

/// N₂ of the first antisymmetric mode: tan(N/2) = N/2, by bisection of sin z − z cos z on
/// (π, 3π/2) (z = N/2).
pub fn n2() -> f64 {
    let (mut lo, mut hi) = (PI + 1e-9, 1.5 * PI);
    let f = |z: f64| z.sin() - z * z.cos();
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) * f(lo) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo + hi
}

/// a* = P₁/(P₂ − P₁): the inverted state's mode-1 amplitude (over h/2) where it meets mode 2.
pub fn a_star() -> f64 {
    let ratio = (n2() / (2.0 * PI)).powi(2);
    1.0 / (ratio - 1.0)
}

/// The rise-over-thickness Q = h/t above which the inverted state is stable (mode 2 free).
pub fn bistable_threshold() -> f64 {
    let a = a_star();
    (4.0 / (3.0 * a * (1.0 - a))).sqrt()
}

impl ShallowArch {
    /// Q = h/t, t² = 12 I/A.
    pub fn q(&self) -> f64 {
        self.h / (12.0 * self.ei / self.ea).sqrt()
    }
    pub fn p1(&self) -> f64 {
        self.ei * (2.0 * PI / self.l).powi(2)
    }
    pub fn p2(&self) -> f64 {
        self.ei * (n2() / self.l).powi(2)
    }

    /// Bending energy of a symmetric state with a₁ = −a·h/2 (plus nothing of mode 2).
    fn bending(&self, a: f64) -> f64 {
        self.ei * self.h * self.h * PI.powi(4) * (1.0 + a).powi(2) / self.l.powi(3)
    }

    fn symmetric(&self, a: f64) -> ArchState {
        let p = self.p1() * (1.0 + 1.0 / a);
        ArchState {
            energy: self.bending(a) + p * p * self.l / (2.0 * self.ea),
            crown: -a * self.h,
            compression: p,
        }
    }

    /// The inverted symmetric states (a₊ first, then the nearly flat a₋), when Q > 2.309.
    pub fn inverted(&self) -> Option<[ArchState; 2]> {
        let disc = 1.0 - 16.0 / (3.0 * self.q().powi(2));
        (disc > 0.0).then(|| {
            [
                self.symmetric(0.5 * (1.0 + disc.sqrt())),
                self.symmetric(0.5 * (1.0 - disc.sqrt())),
            ]
        })
    }

    /// The S-shaped saddle (one of the mirror pair), when Q > Q*.
    pub fn saddle(&self) -> Option<ArchState> {
        let a = a_star();
        let p2 = self.p2();
        let l = self.l;
        let x = 0.25 * self.h * self.h * (1.0 - a * a) * 2.0 * PI * PI / l - 2.0 * l * p2 / self.ea;
        (x > 0.0).then(|| ArchState {
            energy: self.bending(a) + 0.5 * p2 * x + p2 * p2 * l / (2.0 * self.ea),
            crown: -a * self.h,
            compression: p2,
        })
    }

    /// The centre pushed down by a displacement-controlled indenter: the depth (m) and force
    /// (N) where the symmetric path loses stability to mode 2 (P reaches P₂; the held centre
    /// leaves the antisymmetric modes free). With a point force F at the centre the symmetric
    /// modes N = 2πk, k odd (φ(L/2) = 2), take a_k = α_k − β_k F with
    /// β_k = 2/(G_k (P_k − P₂)), G_k = ∫φ_k'² = N_k²/2L, α₁ = P₁ (h/2)/(P₁ − P₂); the strain
    /// condition Σ G_k (a_k² − a₀_k²) = −2LP₂/EA is a quadratic in F, whose root of smaller
    /// depth h − Σ 2a_k is the first crossing. Series summed to k = 200001 (the depth's terms
    /// fall as 1/k⁴).
    pub fn centre_push_bifurcation(&self) -> (f64, f64) {
        self.centre_push().0
    }

    /// The force's slope along the depth (N/m) on the S-shaped branch of the centre push that
    /// follows the bifurcation: P stays P₂ there, so every symmetric coefficient is linear in F
    /// (a_k = α_k − β_k F as above) and the crown h − depth = Σ 2a_k: dF/d(depth) = 1/Σ 2β_k,
    /// negative (β₁ < 0 dominates).
    pub fn s_branch_slope(&self) -> f64 {
        self.centre_push().1
    }

    /// (bifurcation depth and force, S-branch slope) of [`Self::centre_push_bifurcation`] and
    /// [`Self::s_branch_slope`].
    fn centre_push(&self) -> ((f64, f64), f64) {
        let (l, h, p1, p2) = (self.l, self.h, self.p1(), self.p2());
        let alpha1 = p1 * 0.5 * h / (p1 - p2);
        let g = |k: f64| (2.0 * PI * k).powi(2) / (2.0 * l);
        let pk = |k: f64| self.ei * (2.0 * PI * k / l).powi(2);
        let beta = |k: f64| 2.0 / (g(k) * (pk(k) - p2));
        let (mut c2, mut sum_beta) = (0.0, 0.0);
        for k in (1..=200_001).step_by(2) {
            let k = k as f64;
            c2 += g(k) * beta(k).powi(2);
            sum_beta += beta(k);
        }
        let c1 = -2.0 * g(1.0) * alpha1 * beta(1.0);
        let c0 = g(1.0) * (alpha1 * alpha1 - 0.25 * h * h) + 2.0 * l * p2 / self.ea;
        let root = (c1 * c1 - 4.0 * c2 * c0).sqrt();
        let first = [(-c1 - root) / (2.0 * c2), (-c1 + root) / (2.0 * c2)]
            .into_iter()
            .map(|f| (h - 2.0 * alpha1 + 2.0 * sum_beta * f, f))
            .filter(|&(d, _)| d > 0.0)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .expect("a bifurcation on the symmetric path");
        (first, 1.0 / (2.0 * sum_beta))
    }
}
