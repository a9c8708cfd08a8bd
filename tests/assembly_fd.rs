//! The assembled sparse Hessian (pattern, slot map, duplicate handling) against central
//! differences of the assembled gradient along random directions, on networks with every kind
//! of term: interior stencils, clamps, joints, hinges, loads and torques.

mod common;

use common::*;
use rodnet::network::assembly::{Assembly, HessianOut};
use rodnet::network::build::build;
use rodnet::network::model::Model;
use rodnet::scene::types::*;
use rodnet::solver::linalg::SparseCholesky;

fn grad(m: &Model) -> Vec<f64> {
    let mut g = vec![0.0; m.n_free];
    m.assemble(&mut Assembly {
        grad: &mut g,
        full_grad: None,
        hess: None,
    });
    g
}

fn check_model(mut m: Model, seed: u64) {
    let mut rng = Rng::new(seed);
    // A deformed, committed state, then a further displacement so that tangents differ from
    // their references.
    let n = m.n_free;
    let d0: Vec<f64> = (0..n).map(|_| rng.range(-0.05, 0.05)).collect();
    m.displace(&d0, 1.0);
    m.commit();
    let d1: Vec<f64> = (0..n).map(|_| rng.range(-0.02, 0.02)).collect();
    m.displace(&d1, 1.0);
    let pairs = m.hessian_pattern();
    let (mut chol, slots) = SparseCholesky::new(n, &pairs);
    let hs = m.hessian_slots(&slots);
    let mut g = vec![0.0; n];
    m.assemble(&mut Assembly {
        grad: &mut g,
        full_grad: None,
        hess: Some(HessianOut {
            values: &mut chol.values,
            slots: &hs,
        }),
    });
    for trial in 0..3 {
        let v: Vec<f64> = (0..n).map(|_| rng.range(-1.0, 1.0)).collect();
        let mut hv = vec![0.0; n];
        chol.multiply(&v, &mut hv);
        let h = 1e-6;
        m.displace(&v, h);
        let gp = grad(&m);
        m.displace(&v, -2.0 * h);
        let gm = grad(&m);
        m.displace(&v, h);
        let scale = hv.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let err = (0..n)
            .map(|i| ((gp[i] - gm[i]) / (2.0 * h) - hv[i]).abs())
            .fold(0.0, f64::max)
            / scale;
        println!("trial {trial}: relative error of H·v {err:.3e} (|Hv| {scale:.3e})");
        assert!(err < 1e-6, "assembled Hessian differs from FD: {err:.3e}");
    }
}

#[test]
fn cantilever_assembly_matches_fd() {
    let mut s = cantilever(8, 1.0);
    s.loads.push(Load::Torque {
        rod: "beam".into(),
        vertex: 1,
        torque: [0.1, 0.2, 0.3],
    });
    check_model(build(&s).unwrap().model, 11);
}

#[test]
fn network_assembly_matches_fd() {
    let mut s = scene(
        material_ei(1.0, 1e-2, 0.3),
        vec![
            rod(
                "a",
                vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.2, 0.0]],
                3,
            ),
            rod(
                "b",
                vec![[1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.3]],
                3,
            ),
            rod("c", vec![[2.0, 0.2, 0.0], [2.5, 1.0, 0.5]], 2),
            rod(
                "d",
                vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 1.5, 0.0]],
                2,
            ),
        ],
    );
    s.joints.push(Joint {
        name: "x".into(),
        at: vec![("a".into(), 1), ("b".into(), 1)],
        kind: JointKind::Hinge,
        normal: None,
    });
    s.joints.push(Joint {
        name: "r".into(),
        at: vec![("a".into(), 2), ("c".into(), 0)],
        kind: JointKind::Rigid,
        normal: None,
    });
    s.joints.push(Joint {
        name: "o".into(),
        at: vec![("a".into(), 0), ("d".into(), 0)],
        kind: JointKind::Ball,
        normal: None,
    });
    s.supports.push(support("b", 0, SupportKind::Clamp));
    s.supports.push(support("d", 2, SupportKind::Pin));
    s.loads.push(Load::Gravity {
        g: [0.0, 0.0, -9.81],
    });
    s.loads.push(Load::Torque {
        rod: "c".into(),
        vertex: 1,
        torque: [0.0, 0.1, 0.0],
    });
    check_model(build(&s).unwrap().model, 12);
}
