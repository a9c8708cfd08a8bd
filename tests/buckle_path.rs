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

/// A fixed-base portal (columns 3 m, beam 4 m, steel tubes r = 5 cm, rigid corners) under a
/// 10 kN lateral load at a corner: the load puts the columns in ±H·h/L of axial force, about 1 %
/// of their Euler loads even at the linear factor (3.18), so the stiffness hardly changes along
/// the path (the lowest eigenvalue moves by under 0.1 %): "no_buckling", no critical factor (a
/// 0.03 % dip is no imperfect bifurcation). A column whose axial load carries a small
/// lateral one, by contrast, is softened to a fraction of its stiffness before its path turns:
/// "imperfect_bifurcation".
#[test]
fn a_stiffness_the_loads_barely_touch_is_no_buckling_and_a_real_dip_is_imperfect() {
    let steel = |r: f64| Material {
        young_modulus: 2.1e11,
        poisson_ratio: Some(0.3),
        shear_modulus: None,
        density: 0.0,
        section: Section::Circle { radius: r },
        yield_strength: None,
    };
    let mut s = scene(
        steel(0.05),
        vec![
            rod("left", vec![[0.0; 3], [0.0, 0.0, 3.0]], 20),
            rod("beam", vec![[0.0, 0.0, 3.0], [4.0, 0.0, 3.0]], 20),
            rod("right", vec![[4.0, 0.0, 0.0], [4.0, 0.0, 3.0]], 20),
        ],
    );
    let joint = |name: &str, a: (&str, usize), b: (&str, usize)| Joint {
        name: name.into(),
        at: vec![(a.0.into(), a.1), (b.0.into(), b.1)],
        kind: JointKind::Rigid,
        normal: None,
    };
    s.joints = vec![
        joint("a", ("left", 1), ("beam", 0)),
        joint("b", ("beam", 1), ("right", 1)),
    ];
    let force = |rod: &str, f: [f64; 3]| Load::Force {
        rod: rod.into(),
        vertex: 1,
        force: f,
    };
    s.supports = vec![
        support("left", 0, SupportKind::Clamp),
        support("right", 0, SupportKind::Clamp),
    ];
    s.loads = vec![force("left", [1e4, 0.0, 0.0])];
    let b = buckle(&s, 2, false, None, &Limits::NONE).unwrap_or_else(|_| panic!());
    let path = b.json.path.as_ref().unwrap();
    println!("portal: {path:?}");
    assert_eq!(path.kind, "no_buckling", "{path:?}");
    assert!(path.critical_load_factor.is_none());
    let start = path.samples[0][1];
    assert!(
        path.samples
            .iter()
            .all(|s| (s[1] / start - 1.0).abs() < 1e-3),
        "{path:?}"
    );

    let mut c = scene(
        steel(0.005),
        vec![rod("c", vec![[0.0; 3], [0.0, 0.0, 1.0]], 32)],
    );
    c.supports = vec![support("c", 0, SupportKind::Clamp)];
    c.loads = vec![force("c", [0.5, 0.0, -200.0])];
    let b = buckle(&c, 2, false, None, &Limits::NONE).unwrap_or_else(|_| panic!());
    let path = b.json.path.as_ref().unwrap();
    println!("imperfect column: {path:?}");
    assert_eq!(path.kind, "imperfect_bifurcation", "{path:?}");
    let least = path
        .samples
        .iter()
        .map(|s| s[1])
        .fold(f64::INFINITY, f64::min);
    assert!(least < 0.5 * path.samples[0][1], "{path:?}");
}
