//! Shared helpers for integration tests: a deterministic random source and scene builders.
#![allow(dead_code)]

pub mod cli;

use std::collections::BTreeMap;

use rodnet::scene::types::*;

/// xorshift64*: deterministic, dependency-free randomness for test configurations.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E3779B97F4A7C15) | 1)
    }
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545F4914F6CDD1D);
        (v >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }
    pub fn vec3(&mut self, s: f64) -> [f64; 3] {
        [self.range(-s, s), self.range(-s, s), self.range(-s, s)]
    }
}

/// A material whose circular section has bending stiffness `ei` and radius `r` (E adjusted).
pub fn material_ei(ei: f64, r: f64, nu: f64) -> Material {
    let e = 4.0 * ei / (std::f64::consts::PI * r.powi(4));
    Material {
        young_modulus: e,
        poisson_ratio: Some(nu),
        shear_modulus: None,
        density: 0.0,
        section: Section::Circle { radius: r },
        yield_strength: None,
    }
}

pub fn rod(name: &str, points: Vec<[f64; 3]>, subdivide: usize) -> Rod {
    Rod {
        name: name.into(),
        material: "m".into(),
        points,
        subdivide,
        closed: false,
        normal: None,
        end_correction: true,
    }
}

pub fn support(rod: &str, vertex: usize, kind: SupportKind) -> Support {
    Support {
        rod: rod.into(),
        vertex,
        kind,
        move_to: None,
        rotate_by: None,
    }
}

pub fn scene(material: Material, rods: Vec<Rod>) -> Scene {
    let mut materials = BTreeMap::new();
    materials.insert("m".to_string(), material);
    Scene {
        materials,
        rods,
        joints: vec![],
        supports: vec![],
        loads: vec![],
        obstacles: vec![],
        bounds: vec![],
        target: None,
        reference: None,
        solver: Solver::default(),
        stages: vec![],
    }
}

/// Cantilever of length 1 along x clamped at the origin, EI = 1, slender (r = 1e-3 so that
/// EA/EI = 4e6 and extensibility is below 1e-6 of the answers), tip load −p ŷ.
pub fn cantilever(n: usize, p: f64) -> Scene {
    let mut s = scene(
        material_ei(1.0, 1e-3, 0.5),
        vec![rod("beam", vec![[0.0; 3], [1.0, 0.0, 0.0]], n)],
    );
    s.supports.push(support("beam", 0, SupportKind::Clamp));
    s.loads.push(Load::Force {
        rod: "beam".into(),
        vertex: 1,
        force: [0.0, -p, 0.0],
    });
    s
}

/// Weak-axis bending stiffness of `column`'s 4 × 2 mm section, E = 1 GPa (N·m²).
pub const COLUMN_EI: f64 = 1e9 * 0.004 * 0.002 * 0.002 * 0.002 / 12.0;

/// A column of length 1 m along z, 4 × 2 mm, E = 1 GPa, ν = 0.3, clamped at its foot, `n`
/// edges, under the dead axial load `p` (N) at its top; Euler's load π²·COLUMN_EI/4.
pub fn column(p: f64, n: usize) -> Scene {
    let mat = Material {
        young_modulus: 1e9,
        poisson_ratio: Some(0.3),
        shear_modulus: None,
        density: 0.0,
        section: Section::Rectangle {
            width: 0.004,
            height: 0.002,
        },
        yield_strength: None,
    };
    let mut r = rod("column", vec![[0.0; 3], [0.0, 0.0, 1.0]], n);
    r.normal = Some([1.0, 0.0, 0.0]);
    let mut s = scene(mat, vec![r]);
    s.supports.push(support("column", 0, SupportKind::Clamp));
    s.loads.push(Load::Force {
        rod: "column".into(),
        vertex: 1,
        force: [0.0, 0.0, -p],
    });
    s
}
