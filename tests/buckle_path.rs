//! `rodnet buckle`'s check along the nonlinear path (issue 37, item 3): a clean bifurcation is
//! reported with its path value, and a linear factor that is no buckling load of the path is
//! said to be one and not headlined as critical.
//!
//! Scene: a cantilever, L = 1 m, rectangle 2 × 20 mm, E = 1 GPa, ν = 0.3, 40 edges, a tip
//! load along the section's height (strong axis) or its width (weak axis).

mod common;

use common::*;
use rodnet::jobs::buckle;
use rodnet::pipeline::Limits;
use rodnet::rod::section::Section;
use rodnet::scene::types::*;

const SECTION: Section = Section::Rectangle {
    width: 0.002,
    height: 0.02,
};

fn cantilever(normal: [f64; 3]) -> Scene {
    let mat = Material {
        young_modulus: 1e9,
        poisson_ratio: Some(0.3),
        shear_modulus: None,
        density: 0.0,
        section: SECTION,
        yield_strength: None,
    };
    let mut r = rod("c", vec![[0.0; 3], [1.0, 0.0, 0.0]], 40);
    r.normal = Some(normal);
    let mut s = scene(mat, vec![r]);
    s.supports.push(support("c", 0, SupportKind::Clamp));
    s.loads.push(Load::Force {
        rod: "c".into(),
        vertex: 1,
        force: [0.0, 0.0, -1.0],
    });
    s
}

/// Lateral–torsional buckling of the cantilever loaded about its strong axis: Timoshenko &
/// Gere's P = 4.0126·√(EI_y·GJ)/L² for a tip load at the centroid, with the Kirchhoff–Michell
/// correction for the in-plane curvature before buckling, 1/√((1 − EI_y/EI_x)(1 − GJ/EI_x))
/// (+1.2 % here). The path check finds the path's state turning unstable: a clean bifurcation,
/// 6.520e-2 N against 6.503e-2 N (+0.26 %; before: "imperfect bifurcation", no value). Loaded
/// about its weak axis, the same rod has linear factors (2.7e-5…) but its path never loses
/// stability: "no_buckling", no critical factor.
#[test]
fn a_clean_bifurcation_has_its_path_value_and_a_stable_path_none() {
    let (iy, ix) = SECTION.second_moments();
    let (e, g) = (1e9, 1e9 / 2.6);
    let gj = g * SECTION.torsion_constant();
    let (eiy, eix) = (e * iy, e * ix);
    let exact = 4.0126 * (eiy * gj).sqrt() / ((1.0 - eiy / eix) * (1.0 - gj / eix)).sqrt();
    let b = buckle(&cantilever([0.0, 1.0, 0.0]), 2, false, None, &Limits::NONE)
        .unwrap_or_else(|_| panic!());
    let path = b.json.path.as_ref().unwrap();
    println!(
        "strong axis: {:?} at {:?}, exact {exact:.6e}",
        path.kind, path.critical_load_factor
    );
    assert_eq!(path.kind, "bifurcation", "{path:?}");
    let f = path.critical_load_factor.unwrap();
    assert!((f / exact - 1.0).abs() < 5e-3, "{f} vs {exact}");

    let b = buckle(&cantilever([0.0, 0.0, 1.0]), 2, false, None, &Limits::NONE)
        .unwrap_or_else(|_| panic!());
    let path = b.json.path.as_ref().unwrap();
    println!(
        "weak axis: {:?}, linear {:?}",
        path.kind, b.json.critical_load_factors
    );
    assert_eq!(path.kind, "no_buckling", "{path:?}");
    assert!(path.critical_load_factor.is_none());
}
