//! Cross-section properties: stretching, bending and torsional rigidities.
//!
//! Conventions: material axis m1 is the section's first axis (`Ellipse::a`, `Rectangle::width`
//! lie along m1). κ1 = κb·m2 is the curvature that moves the centreline along m1, so it pairs with
//! EI1 = E ∫ y1² dA; κ2 pairs with EI2 = E ∫ y2² dA.
//!
//! Torsion constants J (GJ is the twisting rigidity):
//! - circle of radius r: J = π r⁴ / 2 (exact);
//! - ellipse with semi-axes a, b: J = π a³ b³ / (a² + b²) (exact Saint-Venant solution,
//!   Timoshenko & Goodier, Theory of Elasticity, §106);
//! - rectangle w × h with t = min, s = max: J = s t³ [1/3 − 0.21 (t/s)(1 − t⁴/(12 s⁴))]
//!   (Roark's Formulas for Stress and Strain, Table 10.7 case 4; within 0.5 % of the series
//!   solution for every aspect ratio).

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Section {
    Circle { radius: f64 },
    Ellipse { a: f64, b: f64 },
    Rectangle { width: f64, height: f64 },
}

/// Rigidities of one rod: EA (N), EI1, EI2 (N·m²), GJ (N·m²), mass per length (kg/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stiffness {
    pub ea: f64,
    pub ei1: f64,
    pub ei2: f64,
    pub gj: f64,
    pub mass_per_length: f64,
    /// Largest distance from the centreline to the section's surface (for stresses, contact).
    pub outer_radius: f64,
}

impl Section {
    pub fn area(&self) -> f64 {
        match *self {
            Section::Circle { radius } => std::f64::consts::PI * radius * radius,
            Section::Ellipse { a, b } => std::f64::consts::PI * a * b,
            Section::Rectangle { width, height } => width * height,
        }
    }

    /// Second moments (I1 about m2 axis, for κ1; I2 about m1, for κ2).
    pub fn second_moments(&self) -> (f64, f64) {
        use std::f64::consts::PI;
        match *self {
            Section::Circle { radius } => {
                let i = PI * radius.powi(4) / 4.0;
                (i, i)
            }
            Section::Ellipse { a, b } => (PI * a.powi(3) * b / 4.0, PI * a * b.powi(3) / 4.0),
            Section::Rectangle { width, height } => {
                (height * width.powi(3) / 12.0, width * height.powi(3) / 12.0)
            }
        }
    }

    pub fn torsion_constant(&self) -> f64 {
        use std::f64::consts::PI;
        match *self {
            Section::Circle { radius } => PI * radius.powi(4) / 2.0,
            Section::Ellipse { a, b } => PI * a.powi(3) * b.powi(3) / (a * a + b * b),
            Section::Rectangle { width, height } => {
                let (s, t) = (width.max(height), width.min(height));
                s * t.powi(3)
                    * (1.0 / 3.0 - 0.21 * (t / s) * (1.0 - t.powi(4) / (12.0 * s.powi(4))))
            }
        }
    }

    pub fn outer_radius(&self) -> f64 {
        match *self {
            Section::Circle { radius } => radius,
            Section::Ellipse { a, b } => a.max(b),
            Section::Rectangle { width, height } => 0.5 * (width * width + height * height).sqrt(),
        }
    }

    /// Half-extents along (m1, m2), used for extreme-fibre bending stress.
    pub fn half_extents(&self) -> (f64, f64) {
        match *self {
            Section::Circle { radius } => (radius, radius),
            Section::Ellipse { a, b } => (a, b),
            Section::Rectangle { width, height } => (0.5 * width, 0.5 * height),
        }
    }

    /// Largest |normal stress| over the section under axial force `n` (N, tension positive) and
    /// bending moment `moment` = (M·m1, M·m2) (N·m). The stress at y1 m1 + y2 m2 is
    /// σ = n/A + (M·m1) y2/I2 − (M·m2) y1/I1, so its largest magnitude is |n|/A plus the largest
    /// bending part over the boundary: r|M|/I (circle), √((b M·m1/I2)² + (a M·m2/I1)²)
    /// (ellipse), at a corner (w/2)|M·m2|/I1 + (h/2)|M·m1|/I2 (rectangle).
    pub fn max_normal_stress(&self, n: f64, moment: [f64; 2]) -> f64 {
        let (i1, i2) = self.second_moments();
        let (c1, c2) = self.half_extents();
        // Bending stresses at the ends of each axis: (M·m2) acts along y1, (M·m1) along y2.
        let (s1, s2) = (moment[1] * c1 / i1, moment[0] * c2 / i2);
        let bending = match self {
            Section::Circle { .. } | Section::Ellipse { .. } => (s1 * s1 + s2 * s2).sqrt(),
            Section::Rectangle { .. } => s1.abs() + s2.abs(),
        };
        n.abs() / self.area() + bending
    }

    /// Largest torsional shear stress over the section under torque `t` (N·m):
    /// - circle: |t| r / J;
    /// - ellipse, semi-axes a ≥ b: 2|t|/(π a b²), at the ends of the minor axis (Roark's Formulas
    ///   for Stress and Strain, Table 10.7 case 2);
    /// - rectangle, sides 2a ≥ 2b: 3|t|/(8 a b²) · [1 + 0.6095 β + 0.8865 β² − 1.8023 β³ +
    ///   0.9100 β⁴], β = b/a, at the middle of the long sides (Table 10.7 case 4, the same case
    ///   as the torsion constant J).
    pub fn max_torsion_stress(&self, t: f64) -> f64 {
        use std::f64::consts::PI;
        let t = t.abs();
        match *self {
            Section::Circle { radius } => t * radius / self.torsion_constant(),
            Section::Ellipse { a, b } => {
                let (a, b) = (a.max(b), a.min(b));
                2.0 * t / (PI * a * b * b)
            }
            Section::Rectangle { width, height } => {
                let (a, b) = (0.5 * width.max(height), 0.5 * width.min(height));
                let r = b / a;
                3.0 * t / (8.0 * a * b * b)
                    * (1.0 + 0.6095 * r + 0.8865 * r * r - 1.8023 * r.powi(3) + 0.91 * r.powi(4))
            }
        }
    }

    pub fn stiffness(&self, young: f64, shear: f64, density: f64) -> Stiffness {
        let (i1, i2) = self.second_moments();
        Stiffness {
            ea: young * self.area(),
            ei1: young * i1,
            ei2: young * i2,
            gj: shear * self.torsion_constant(),
            mass_per_length: density * self.area(),
            outer_radius: self.outer_radius(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipse_with_equal_axes_is_the_circle() {
        let c = Section::Circle { radius: 0.3 };
        let e = Section::Ellipse { a: 0.3, b: 0.3 };
        assert!((c.torsion_constant() - e.torsion_constant()).abs() < 1e-15);
        assert!((c.second_moments().0 - e.second_moments().1).abs() < 1e-15);
    }

    #[test]
    fn square_torsion_constant_matches_series() {
        // Saint-Venant series for a square of side a: J = 0.1406 a⁴ (Timoshenko & Goodier).
        let j = Section::Rectangle {
            width: 1.0,
            height: 1.0,
        }
        .torsion_constant();
        assert!((j - 0.1406).abs() / 0.1406 < 5e-3, "{j}");
        // Thin strip: J → w t³ / 3.
        let j = Section::Rectangle {
            width: 100.0,
            height: 1.0,
        }
        .torsion_constant();
        assert!((j - (100.0 / 3.0 - 0.21)).abs() < 1e-9, "{j}");
    }

    #[test]
    fn torsion_stresses_match_the_classical_values() {
        let t = 2.0;
        // Circle: τ = T r / J = 2T/(π r³); the ellipse with equal axes is the circle.
        let c = Section::Circle { radius: 0.1 }.max_torsion_stress(t);
        assert!((c - 2.0 * t / (std::f64::consts::PI * 1e-3)).abs() < 1e-9 * c);
        let e = Section::Ellipse { a: 0.1, b: 0.1 }.max_torsion_stress(t);
        assert!((c - e).abs() < 1e-12 * c);
        // Square of side s: τ = T/(0.208 s³) (Timoshenko & Goodier).
        let sq = Section::Rectangle {
            width: 1.0,
            height: 1.0,
        }
        .max_torsion_stress(t);
        assert!((sq - t / 0.208).abs() / sq < 2e-3, "{sq}");
        // Thin strip s × t: τ → 3T/(s t²).
        let strip = Section::Rectangle {
            width: 1000.0,
            height: 1.0,
        }
        .max_torsion_stress(t);
        assert!((strip - 3.0 * t / 1000.0).abs() / strip < 1e-3, "{strip}");
    }

    #[test]
    fn normal_stress_peaks_at_the_extreme_fibre() {
        // Rectangle w × h: n/A + 6|M·m2|/(h w²) + 6|M·m1|/(w h²).
        let r = Section::Rectangle {
            width: 0.2,
            height: 0.1,
        };
        let s = r.max_normal_stress(-3.0, [5.0, -7.0]);
        let want = 3.0 / 0.02 + 6.0 * 7.0 / (0.1 * 0.04) + 6.0 * 5.0 / (0.2 * 0.01);
        assert!((s - want).abs() < 1e-9 * want, "{s} vs {want}");
        // Circle: n/A + 4|M|/(π r³).
        let c = Section::Circle { radius: 0.1 };
        let s = c.max_normal_stress(0.0, [3.0, 4.0]);
        let want = 4.0 * 5.0 / (std::f64::consts::PI * 1e-3);
        assert!((s - want).abs() < 1e-9 * want);
    }
}
