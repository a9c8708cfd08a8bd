//! Target meshes of the validation surfaces (docs/gridshell.md): hemisphere, paraboloid cap,
//! spheroidal dome, quarter-sphere + half-cylinder vault and saddle, as OBJ text, at a chosen
//! resolution. Disk-like shapes use concentric rings of 6k vertices (no pole, nearly uniform
//! triangles); the others a parameter grid.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write;

/// Vertices and triangles.
pub type Mesh = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// A disk of `rings` rings mapped by `f(r, φ)`, r ∈ [0, 1]; ring k has 6k vertices.
pub fn disk(rings: usize, f: &dyn Fn(f64, f64) -> [f64; 3]) -> Mesh {
    let mut v = vec![f(0.0, 0.0)];
    let mut start = vec![0usize];
    for k in 1..=rings {
        start.push(v.len());
        let count = 6 * k;
        for i in 0..count {
            v.push(f(
                k as f64 / rings as f64,
                2.0 * PI * i as f64 / count as f64,
            ));
        }
    }
    let mut t = Vec::new();
    for k in 1..=rings {
        let (inner, outer) = (ring(&start, k - 1), ring(&start, k));
        let (ni, no) = (inner.len(), outer.len());
        let (mut i, mut o) = (0, 0);
        // Walk both rings by angle, always advancing the one whose next vertex comes first;
        // the centre (a ring of one) only fans.
        while o < no || (ni > 1 && i < ni) {
            let next_inner = (i + 1) as f64 / ni as f64;
            let next_outer = (o + 1) as f64 / no as f64;
            if o < no && (ni == 1 || i == ni || next_outer <= next_inner) {
                t.push([inner[i % ni], outer[o], outer[(o + 1) % no]]);
                o += 1;
            } else {
                t.push([inner[i % ni], outer[o % no], inner[(i + 1) % ni]]);
                i += 1;
            }
        }
    }
    (v, t)
}

fn ring(start: &[usize], k: usize) -> Vec<u32> {
    let count = if k == 0 { 1 } else { 6 * k };
    (0..count).map(|i| (start[k] + i) as u32).collect()
}

/// A grid of `nu` × `nv` quads over [0, 1]² mapped by `f`, each split along alternating
/// diagonals.
pub fn grid(nu: usize, nv: usize, f: &dyn Fn(f64, f64) -> [f64; 3]) -> Mesh {
    let mut v = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            v.push(f(i as f64 / nu as f64, j as f64 / nv as f64));
        }
    }
    let id = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    let mut t = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                t.extend([[a, b, c], [a, c, d]]);
            } else {
                t.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    (v, t)
}

/// The upper half of the sphere of radius `r` about the origin, boundary on z = 0.
pub fn hemisphere(r: f64, rings: usize) -> Mesh {
    spheroid(r, r, rings)
}

/// The upper half of the spheroid with equatorial semi-axis `a` and polar semi-axis `c`.
pub fn spheroid(a: f64, c: f64, rings: usize) -> Mesh {
    disk(rings, &|rho, phi| {
        let th = rho * FRAC_PI_2;
        [
            a * th.sin() * phi.cos(),
            a * th.sin() * phi.sin(),
            c * th.cos(),
        ]
    })
}

/// z = h (1 − (r/b)²) over the disk of radius `b`.
pub fn paraboloid(b: f64, h: f64, rings: usize) -> Mesh {
    disk(rings, &|rho, phi| {
        [
            b * rho * phi.cos(),
            b * rho * phi.sin(),
            h * (1.0 - rho * rho),
        ]
    })
}

/// z = (x² − y²)/(2 r) over the square [−w, w]².
pub fn saddle(w: f64, r: f64, n: usize) -> Mesh {
    grid(n, n, &|s, t| {
        let (x, y) = (w * (2.0 * s - 1.0), w * (2.0 * t - 1.0));
        [x, y, (x * x - y * y) / (2.0 * r)]
    })
}

/// A half-cylinder of radius `r` along x from 0 to `length`, closed at x = 0 by a quarter
/// sphere; the boundary lies on z = 0. `n` sets the resolution (3n quads around, n per r
/// along).
pub fn vault(r: f64, length: f64, n: usize) -> Mesh {
    let along = ((length / r) * n as f64).ceil().max(1.0) as usize;
    // 3n quads around the half circle meet the quarter sphere's outer ring of 6n vertices.
    let (mut v, mut t) = grid(3 * n, along, &|s, u| {
        let phi = PI * s;
        [length * u, r * phi.cos(), r * phi.sin()]
    });
    // The quarter sphere: rings of latitude from the pole (−r, 0, 0) to the seam x = 0.
    let (cap_v, cap_t) = disk(n, &|rho, phi| {
        let psi = rho * FRAC_PI_2;
        // φ runs clockwise seen from −x, so that the normals point outward like the
        // cylinder's.
        [
            -r * psi.cos(),
            r * psi.sin() * phi.cos(),
            -r * psi.sin() * phi.sin(),
        ]
    });
    // Keep the half with z ≥ 0: triangles whose corners all have z ≥ 0.
    let base = v.len() as u32;
    let keep: Vec<bool> = cap_v.iter().map(|p| p[2] >= -1e-12 * r).collect();
    v.extend(cap_v);
    for tri in cap_t {
        if tri.iter().all(|&i| keep[i as usize]) {
            t.push(tri.map(|i| i + base));
        }
    }
    weld(&mut v, &mut t, 1e-9 * r);
    (v, t)
}

/// Merges vertices closer than `tol` (by rounding to a grid of `tol`) and drops the
/// triangles that then repeat a vertex.
fn weld(v: &mut Vec<[f64; 3]>, t: &mut Vec<[u32; 3]>, tol: f64) {
    let mut seen = std::collections::HashMap::new();
    let mut kept = Vec::new();
    let map: Vec<u32> = v
        .iter()
        .map(|p| {
            let key = p.map(|x| (x / tol).round() as i64);
            *seen.entry(key).or_insert_with(|| {
                kept.push(*p);
                (kept.len() - 1) as u32
            })
        })
        .collect();
    *v = kept;
    *t = t
        .iter()
        .map(|tri| tri.map(|i| map[i as usize]))
        .filter(|tri| tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2])
        .collect();
}

pub fn to_obj(mesh: &Mesh) -> String {
    let mut s = String::new();
    for p in &mesh.0 {
        let _ = writeln!(s, "v {:.17e} {:.17e} {:.17e}", p[0], p[1], p[2]);
    }
    for t in &mesh.1 {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::Surface;

    #[test]
    fn every_shape_passes_the_mesh_checks_with_its_curvature() {
        for (name, mesh) in [
            ("hemisphere", hemisphere(1.0, 12)),
            ("spheroid", spheroid(1.0, 0.6, 10)),
            ("paraboloid", paraboloid(1.0, 0.5, 10)),
            ("saddle", saddle(1.0, 2.0, 10)),
            ("vault", vault(1.0, 2.0, 8)),
        ] {
            let s = Surface::from_obj(name, &to_obj(&mesh)).unwrap();
            assert_eq!(s.flipped, 0, "{name}: consistently wound");
            let total: f64 = s.angle_defects().iter().sum();
            if name == "hemisphere" {
                // Gauss–Bonnet: the interior vertices carry about 2π of the hemisphere's 2π.
                assert!((total - 2.0 * PI).abs() < 0.6, "{name}: {total}");
            }
        }
    }
}
