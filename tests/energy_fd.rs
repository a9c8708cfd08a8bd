//! Finite-difference checks of every energy term's gradient and Hessian at random bent, twisted
//! and near-fold configurations. The gradient is compared with central differences of the
//! energy and the Hessian with central differences of the gradient (step 1e-6, truncation
//! error O(h²) ≈ 1e-12 and round-off ≈ 1e-10 relative), both to a relative error of 1e-6.

mod common;

use common::Rng;
use rodnet::energy::{
    bend::Bend, frame_bend::FrameBend, frame_twist::FrameTwist, point_load::PointLoad,
    rotational_spring::RotationalSpring, spring::Spring, stretch::Stretch, torque::Torque,
    twist::Twist, Term,
};
use rodnet::math::vec::*;
use rodnet::math::HD;
use rodnet::rod::frames::EdgeRef;
use rodnet::variables::Port;
use rodnet::variables::{FrameRef, State};

const H: f64 = 1e-6;
const TOL: f64 = 1e-6;

fn check<const N: usize, E: Term<N>>(term: &E, st: &State, x: [f64; N], what: &str) {
    let ad = term.eval(st, &HD::<N>::vars(&x));
    assert!((ad.v - term.eval::<f64>(st, &x)).abs() <= 1e-12 * ad.v.abs().max(1e-300));
    // The assembly path (reduced variables where a term has them) equals the full evaluation.
    let fast = term.derivatives(st, &x);
    let (fh, ah) = (fast.hessian(), ad.hessian());
    let scale = ah.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
    for i in 0..N {
        assert!(
            (fast.g[i] - ad.g[i]).abs() <= 1e-12 * scale.max(ad.g[i].abs()),
            "{what}: gradient paths differ"
        );
        for j in 0..N {
            assert!(
                (fh[i][j] - ah[i][j]).abs() <= 1e-11 * scale,
                "{what}: Hessian paths differ"
            );
        }
    }
    let hess = ad.hessian();
    let gmax = ad.g.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-12);
    let hmax = hess
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(1e-12);
    let mut gerr: f64 = 0.0;
    let mut herr: f64 = 0.0;
    for i in 0..N {
        let (mut xp, mut xm) = (x, x);
        xp[i] += H;
        xm[i] -= H;
        let fd = (term.eval::<f64>(st, &xp) - term.eval::<f64>(st, &xm)) / (2.0 * H);
        gerr = gerr.max((fd - ad.g[i]).abs() / gmax);
        let gp = term.eval(st, &HD::<N>::vars(&xp)).g;
        let gm = term.eval(st, &HD::<N>::vars(&xm)).g;
        for j in 0..N {
            let fd = (gp[j] - gm[j]) / (2.0 * H);
            herr = herr.max((fd - hess[j][i]).abs() / hmax);
        }
    }
    assert!(
        gerr < TOL,
        "{what}: gradient relative error {gerr:.3e} (max |g| {gmax:.3e})"
    );
    assert!(
        herr < TOL,
        "{what}: Hessian relative error {herr:.3e} (max |H| {hmax:.3e})"
    );
    assert!(
        hess.iter().flatten().all(|v| v.is_finite()),
        "{what}: non-finite Hessian"
    );
}

fn random_rotation(rng: &mut Rng) -> Frame {
    let w = rng.vec3(2.0);
    frame_rotate(w, &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
}

/// A reference frame near (but not at) the tangent `t`, as after a Newton step.
fn nearby_ref(rng: &mut Rng, t: [f64; 3]) -> EdgeRef {
    let tr = normalize(add(t, rng.vec3(0.3)));
    let u0 = any_perpendicular(tr);
    let u = rotate_axis(tr, rng.range(-3.0, 3.0), u0);
    EdgeRef { t: tr, u }
}

fn state(edges: Vec<EdgeRef>, frames: Vec<FrameRef>, twist_prev: Vec<f64>) -> State {
    State {
        q: vec![],
        edges,
        frames,
        twist_prev,
        load_factor: 0.7,
    }
}

/// Three nodes with turning angle `phi` at the middle one, randomly placed and scaled.
fn three_nodes(rng: &mut Rng, phi: f64) -> [[f64; 3]; 3] {
    let r = random_rotation(rng);
    let rot = |v: [f64; 3]| {
        add(
            add(scalef(r[0], v[0]), scalef(r[1], v[1])),
            scalef(r[2], v[2]),
        )
    };
    let (l0, l1) = (rng.range(0.5, 1.5), rng.range(0.5, 1.5));
    let x1 = rng.vec3(1.0);
    let x0 = sub(x1, rot([l0, 0.0, 0.0]));
    let x2 = add(x1, rot([l1 * phi.cos(), l1 * phi.sin(), 0.0]));
    [x0, x1, x2]
}

fn stencil_x(n: [[f64; 3]; 3], t0: f64, t1: f64) -> [f64; 11] {
    let mut x = [0.0; 11];
    for k in 0..3 {
        x[3 * k..3 * k + 3].copy_from_slice(&n[k]);
    }
    x[9] = t0;
    x[10] = t1;
    x
}

const ANGLES: [(f64, &str); 4] = [
    (0.3, "bent"),
    (1.7, "strongly bent"),
    (175.0 * std::f64::consts::PI / 180.0, "near fold (175°)"),
    (1e-9, "straight"),
];

#[test]
fn stretch_fd() {
    let mut rng = Rng::new(1);
    for k in 0..5 {
        let t = Stretch {
            vars: [0, 1, 2, 3, 4, 5],
            edge: 0,
            rest_length: rng.range(0.3, 2.0),
            ea: rng.range(1.0, 10.0),
        };
        let a = rng.vec3(1.0);
        let b = add(a, rng.vec3(1.0));
        let x = [a[0], a[1], a[2], b[0], b[1], b[2]];
        check(
            &t,
            &state(vec![], vec![], vec![]),
            x,
            &format!("stretch {k}"),
        );
    }
}

#[test]
fn bend_fd() {
    let mut rng = Rng::new(2);
    for (phi, what) in ANGLES {
        for _ in 0..3 {
            let n = three_nodes(&mut rng, phi);
            let t0 = normalize(sub(n[1], n[0]));
            let t1 = normalize(sub(n[2], n[1]));
            let st = state(
                vec![nearby_ref(&mut rng, t0), nearby_ref(&mut rng, t1)],
                vec![],
                vec![],
            );
            let signs = [
                if rng.uniform() < 0.5 { 1.0 } else { -1.0 },
                if rng.uniform() < 0.5 { 1.0 } else { -1.0 },
            ];
            let t = Bend {
                vars: std::array::from_fn(|i| i),
                edges: [0, 1],
                signs,
                rest: [
                    [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
                    [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
                ],
                voronoi: rng.range(0.5, 1.5),
                ei: [
                    [rng.range(0.5, 2.0), rng.range(0.5, 2.0)],
                    [rng.range(0.5, 2.0), rng.range(0.5, 2.0)],
                ],
            };
            let x = stencil_x(n, rng.range(-4.0, 4.0), rng.range(-4.0, 4.0));
            check(&t, &st, x, &format!("bend, {what}, signs {signs:?}"));
        }
    }
}

#[test]
fn twist_fd() {
    let mut rng = Rng::new(3);
    for (phi, what) in ANGLES {
        for k in 0..3 {
            let n = three_nodes(&mut rng, phi);
            let t0 = normalize(sub(n[1], n[0]));
            let t1 = normalize(sub(n[2], n[1]));
            let mut st = state(
                vec![nearby_ref(&mut rng, t0), nearby_ref(&mut rng, t1)],
                vec![],
                vec![0.0],
            );
            let signs = [
                if k == 1 { -1.0 } else { 1.0 },
                if k == 2 { -1.0 } else { 1.0 },
            ];
            let mut t = Twist {
                vars: std::array::from_fn(|i| i),
                edges: [0, 1],
                signs,
                slot: 0,
                rest: rng.range(-1.0, 1.0),
                voronoi: rng.range(0.5, 1.5),
                gj: rng.range(0.5, 2.0),
            };
            let x = stencil_x(n, rng.range(-9.0, 9.0), rng.range(-9.0, 9.0));
            // Unwrapping onto another branch (accumulated full turns) must not change derivatives.
            st.twist_prev[0] = t.reference_twist::<f64>(&st, &Twist::reduced(&x))
                + (k as f64 - 1.0) * std::f64::consts::TAU;
            t.rest += st.twist_prev[0];
            check(&t, &st, x, &format!("twist, {what}"));
        }
    }
}

/// Half-stencil configurations: frame ω both inside (|ω|² < 0.1) and outside the Rodrigues
/// series branch, a hinge angle, and both edge orientations.
fn frame_cases(rng: &mut Rng) -> Vec<(State, Port, f64, [f64; 11], String)> {
    let mut out = Vec::new();
    for (phi, what) in ANGLES {
        for (k, wmag) in [0.05, 0.8].into_iter().enumerate() {
            let sign = if k == 0 { 1.0 } else { -1.0 };
            let xv = rng.vec3(1.0);
            let len = rng.range(0.5, 1.5);
            // Frame tangent (pointing into the edge) and the edge's outward tangent at angle phi.
            let fr = random_rotation(rng);
            let tf = fr[2];
            let te = normalize(add(scalef(tf, phi.cos()), scalef(fr[0], phi.sin())));
            let xo = add(xv, scalef(te, len));
            let edge_t = scalef(te, sign);
            let w = scalef(normalize(rng.vec3(1.0)), wmag);
            let alpha = rng.range(-1.0, 1.0);
            let port = Port {
                frame: 0,
                rest: random_rotation(rng),
                hinge_axis: normalize(rng.vec3(1.0)),
            };
            let st = State {
                q: vec![],
                edges: vec![nearby_ref(rng, edge_t)],
                frames: vec![FrameRef {
                    rotation: random_rotation(rng),
                    accumulated: rng.vec3(1.0),
                }],
                twist_prev: vec![0.0],
                load_factor: 0.7,
            };
            let x = [
                xv[0],
                xv[1],
                xv[2],
                xo[0],
                xo[1],
                xo[2],
                rng.range(-5.0, 5.0),
                w[0],
                w[1],
                w[2],
                alpha,
            ];
            out.push((
                st,
                port,
                sign,
                x,
                format!("{what}, |ω| = {wmag}, sign {sign}"),
            ));
        }
    }
    out
}

#[test]
fn frame_bend_fd() {
    let mut rng = Rng::new(4);
    for (st, port, sign, x, what) in frame_cases(&mut rng) {
        let t = FrameBend {
            vars: std::array::from_fn(|i| i),
            port,
            edge: 0,
            sign,
            rest: [
                [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
                [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
            ],
            voronoi: rng.range(0.2, 0.8),
            ei: [rng.range(0.5, 2.0), rng.range(0.5, 2.0)],
        };
        check(&t, &st, x, &format!("frame bend, {what}"));
    }
}

#[test]
fn frame_twist_fd() {
    let mut rng = Rng::new(5);
    for (mut st, port, sign, x, what) in frame_cases(&mut rng) {
        let mut t = FrameTwist {
            vars: std::array::from_fn(|i| i),
            port,
            edge: 0,
            sign,
            slot: 0,
            rest: rng.range(-1.0, 1.0),
            voronoi: rng.range(0.2, 0.8),
            gj: rng.range(0.5, 2.0),
        };
        st.twist_prev[0] =
            t.reference_twist::<f64>(&st, &Twist::reduced(&x)) + std::f64::consts::TAU;
        t.rest += st.twist_prev[0];
        check(&t, &st, x, &format!("frame twist, {what}"));
    }
}

#[test]
fn external_loads_fd() {
    let mut rng = Rng::new(6);
    let st = State {
        q: vec![],
        edges: vec![],
        frames: vec![FrameRef {
            rotation: random_rotation(&mut rng),
            accumulated: rng.vec3(1.0),
        }],
        twist_prev: vec![],
        load_factor: 0.7,
    };
    let f = PointLoad {
        vars: [0, 1, 2],
        force: rng.vec3(3.0),
    };
    check(&f, &st, rng.vec3(1.0), "point load");
    let t = Torque {
        vars: [0, 1, 2],
        frame: 0,
        torque: rng.vec3(3.0),
    };
    check(&t, &st, rng.vec3(0.5), "torque");
    // An elastic support with anisotropic stiffness and a moving anchor (λ = 0.7), far from
    // and close to its anchor.
    let sp = Spring {
        vars: [0, 1, 2],
        stiffness: [3.0e4, 0.0, 7.5e2],
        axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        anchor: [rng.vec3(1.0), rng.vec3(1.0)],
    };
    check(&sp, &st, rng.vec3(2.0), "spring");
    check(
        &sp,
        &st,
        add(sp.anchor_at(0.7), [1e-7, -2e-7, 3e-7]),
        "spring at its anchor",
    );
    // The load's gradient is exactly −λ f.
    let g = f.eval(&st, &HD::<3>::vars(&[0.1, 0.2, 0.3])).g;
    for (gk, fk) in g.iter().zip(f.force) {
        assert_eq!(*gk, -0.7 * fk);
    }
}

/// The bending measure stays bounded: at 175° the integrated curvature 2 sin(φ/2) is below 2,
/// where DER's 2 tan(φ/2) would be 22.9.
#[test]
fn bending_measure_is_bounded_near_fold() {
    use rodnet::rod::frames::curvature_binormal;
    let phi = 175.0f64.to_radians();
    let kb = curvature_binormal([1.0, 0.0, 0.0], [phi.cos(), phi.sin(), 0.0]);
    assert!((norm(kb) - 2.0 * (phi / 2.0).sin()).abs() < 1e-12);
    assert!(norm(kb) < 2.0);
}

#[test]
fn joint_terms_fd() {
    use rodnet::energy::{joint_rotation::JointRotation, joint_translation::JointTranslation};
    let mut rng = Rng::new(7);
    for wmag in [0.05, 0.9] {
        let st = State {
            q: vec![],
            edges: vec![],
            frames: vec![
                FrameRef {
                    rotation: random_rotation(&mut rng),
                    accumulated: [0.0; 3],
                },
                FrameRef {
                    rotation: random_rotation(&mut rng),
                    accumulated: [0.0; 3],
                },
            ],
            twist_prev: vec![],
            load_factor: 1.0,
        };
        let a = normalize(rng.vec3(1.0));
        let b = normalize(cross(a, rng.vec3(1.0)));
        let t = JointRotation {
            vars: std::array::from_fn(|i| i),
            port_frame: 0,
            joint_frame: 1,
            rest: random_rotation(&mut rng),
            axes: [a, b, cross(a, b)],
            stiffness: [
                rng.range(0.5, 2.0),
                rng.range(0.5, 2.0),
                rng.range(0.5, 2.0),
            ],
        };
        let w1 = scalef(normalize(rng.vec3(1.0)), wmag);
        let w2 = scalef(normalize(rng.vec3(1.0)), wmag);
        check(
            &t,
            &st,
            [w1[0], w1[1], w1[2], w2[0], w2[1], w2[2]],
            &format!("joint rotation |ω| = {wmag}"),
        );
        // Equal frames: no relative rotation and no energy, whatever the rest orientation.
        let same = State {
            frames: vec![st.frames[0]; 2],
            ..st.clone()
        };
        assert!(t.eval::<f64>(&same, &[0.0; 6]).abs() < 1e-28);
        let s = JointTranslation {
            vars: std::array::from_fn(|i| i),
            stiffness: 3.0,
        };
        let x = rng.vec3(1.0);
        let y = rng.vec3(1.0);
        check(
            &s,
            &st,
            [x[0], x[1], x[2], y[0], y[1], y[2]],
            "joint translation",
        );
    }
}

/// Orthonormal axes turned by a random rotation.
fn random_axes(rng: &mut Rng) -> [[f64; 3]; 3] {
    random_rotation(rng)
}

#[test]
fn spring_along_oblique_axes_fd() {
    let mut rng = Rng::new(11);
    let st = State {
        q: vec![],
        edges: vec![],
        frames: vec![],
        twist_prev: vec![],
        load_factor: 0.4,
    };
    let sp = Spring {
        vars: [0, 1, 2],
        stiffness: [2.0e3, 5.0e1, 0.0],
        axes: random_axes(&mut rng),
        anchor: [rng.vec3(1.0), rng.vec3(1.0)],
    };
    let x = rng.vec3(2.0);
    check(&sp, &st, x, "oblique spring");
    // Its reported force is minus its gradient, and it has none along the free axis.
    let g = sp.eval(&st, &HD::<3>::vars(&x)).g;
    let f = sp.force(x, 0.4);
    for k in 0..3 {
        assert!((f[k] + g[k]).abs() <= 1e-12 * norm(g));
    }
    assert!(dot(f, sp.axes[2]).abs() <= 1e-12 * norm(f));
}

fn rotational_state(q: Frame, lambda: f64) -> State {
    State {
        q: vec![],
        edges: vec![],
        frames: vec![FrameRef {
            rotation: q,
            accumulated: [0.0; 3],
        }],
        twist_prev: vec![],
        load_factor: lambda,
    }
}

/// Bent (a general turn, a turned anchor), near-singular (turns of 1e-4 and 1e-3 rad, where the
/// series for θ/sin θ hands over to the closed form) and large (2.5 and 3.0 rad) states.
#[test]
fn rotational_spring_fd() {
    let mut rng = Rng::new(12);
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let spring = |rng: &mut Rng, rotate_by: [f64; 3]| RotationalSpring {
        vars: [0, 1, 2],
        frame: 0,
        axes: random_axes(rng),
        stiffness: [
            rng.range(0.5, 2.0),
            rng.range(0.5, 2.0),
            rng.range(0.5, 2.0),
        ],
        rotate_by,
    };
    // A general state: the frame's reference turned, an increment on top, the anchor turning.
    let reference = random_rotation(&mut rng);
    let st = rotational_state(reference, 0.7);
    let turn = rng.vec3(0.8);
    let t = spring(&mut rng, turn);
    check(&t, &st, rng.vec3(0.3), "rotational spring, general");
    // Relative turns of a given angle about a random axis (reference at rest, anchor fixed).
    for angle in [1e-4, 9.99e-4, 1.001e-3, 0.3, 2.5, 3.0] {
        let st = rotational_state(identity, 1.0);
        let t = spring(&mut rng, [0.0; 3]);
        let w = scalef(normalize(rng.vec3(1.0)), angle);
        check(
            &t,
            &st,
            w,
            &format!("rotational spring, turned {angle} rad"),
        );
        // The energy is exactly ½ Σ kᵢ (θ a·eᵢ)² (the logarithm, not sin θ).
        let want: f64 = (0..3)
            .map(|i| 0.5 * t.stiffness[i] * dot(w, t.axes[i]).powi(2))
            .sum();
        let got = t.eval::<f64>(&st, &w);
        assert!(
            (got - want).abs() <= 1e-12 * want,
            "turned {angle} rad: energy {got:.15e}, want {want:.15e}"
        );
    }
    // The same relative turn reached by turning the frame's reference instead of its increment.
    let w = [0.4, -1.1, 0.7];
    let st = rotational_state(frame_rotate(w, &identity), 1.0);
    let t = spring(&mut rng, [0.0; 3]);
    let want: f64 = (0..3)
        .map(|i| 0.5 * t.stiffness[i] * dot(w, t.axes[i]).powi(2))
        .sum();
    assert!((t.eval::<f64>(&st, &[0.0; 3]) - want).abs() <= 1e-12 * want);
    check(&t, &st, [0.0; 3], "rotational spring, reference turned");
    // An anchor turned by the frame's own turn holds no energy.
    let t = RotationalSpring { rotate_by: w, ..t };
    assert!(t.eval::<f64>(&st, &[0.0; 3]).abs() < 1e-25);
}
