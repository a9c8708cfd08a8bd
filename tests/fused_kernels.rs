//! The fused bend-and-twist kernels (`FrameBendTwist` at a vertex frame, `BendTwist` at a rod's
//! interior vertex) against finite differences and against the separate terms they replace in
//! assembly, at bent, twisted and near-singular states: nearly antiparallel tangents (175°),
//! reference twist at ±π (where the raw angle wraps), frame increments of zero (as at every
//! committed iterate), small and large, hinge angles, both edge orientations. Finite
//! differences as in energy_fd.rs: step 1e-6, relative error 1e-6.

mod common;

use common::Rng;
use rodnet::energy::{
    bend::Bend, bend_twist::BendTwist, frame_bend::FrameBend, frame_bend_twist::FrameBendTwist,
    frame_twist::FrameTwist, twist::Twist, Category, Term,
};
use rodnet::math::vec::*;
use rodnet::math::HD;
use rodnet::rod::frames::EdgeRef;
use rodnet::variables::{FrameRef, Port, State};

const H: f64 = 1e-6;
const TOL: f64 = 1e-6;
const PI: f64 = std::f64::consts::PI;

/// One configuration: the state (twist slot 0), the fused term and its local variables.
struct Case<E> {
    st: State,
    term: E,
    x: [f64; 11],
    what: String,
}

/// A fused kernel and the two terms it sums.
trait Fused: Term<11> {
    fn separate_derivatives(&self, st: &State, x: &[f64; 11]) -> [HD<11>; 2];
    fn separate_energies(&self, st: &State) -> [f64; 2];
    fn twist_remembered(&self, st: &State) -> Option<(usize, f64)>;
}

impl Fused for FrameBendTwist {
    fn separate_derivatives(&self, st: &State, x: &[f64; 11]) -> [HD<11>; 2] {
        [self.bend.derivatives(st, x), self.twist.derivatives(st, x)]
    }
    fn separate_energies(&self, st: &State) -> [f64; 2] {
        [self.bend.energy(st), self.twist.energy(st)]
    }
    fn twist_remembered(&self, st: &State) -> Option<(usize, f64)> {
        self.twist.remembered(st)
    }
}

impl Fused for BendTwist {
    fn separate_derivatives(&self, st: &State, x: &[f64; 11]) -> [HD<11>; 2] {
        [self.bend.derivatives(st, x), self.twist.derivatives(st, x)]
    }
    fn separate_energies(&self, st: &State) -> [f64; 2] {
        [self.bend.energy(st), self.twist.energy(st)]
    }
    fn twist_remembered(&self, st: &State) -> Option<(usize, f64)> {
        self.twist.remembered(st)
    }
}

fn random_rotation(rng: &mut Rng) -> Frame {
    frame_rotate(
        rng.vec3(2.0),
        &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    )
}

/// Turns a frame about its third column by `beta`.
fn turn_about_tangent(f: Frame, beta: f64) -> Frame {
    [
        rotate_axis(f[2], beta, f[0]),
        rotate_axis(f[2], beta, f[1]),
        f[2],
    ]
}

/// A half-stencil whose edge leaves the frame tangent at angle `phi`, with frame increment of
/// size `wmag`, seeded so that every parameter is generic.
fn frame_case(rng: &mut Rng, phi: f64, wmag: f64, sign: f64, what: &str) -> Case<FrameBendTwist> {
    let fr = random_rotation(rng);
    let te = normalize(add(scalef(fr[2], phi.cos()), scalef(fr[0], phi.sin())));
    let xv = rng.vec3(1.0);
    let xo = add(xv, scalef(te, rng.range(0.5, 1.5)));
    let edge_t = scalef(te, sign);
    let tr = normalize(add(edge_t, rng.vec3(0.3)));
    let st = State {
        q: vec![],
        edges: vec![EdgeRef {
            t: tr,
            u: rotate_axis(tr, rng.range(-3.0, 3.0), any_perpendicular(tr)),
        }],
        frames: vec![FrameRef {
            rotation: random_rotation(rng),
            accumulated: rng.vec3(1.0),
        }],
        twist_prev: vec![0.0],
        load_factor: 0.7,
    };
    let port = Port {
        frame: 0,
        rest: random_rotation(rng),
        hinge_axis: normalize(rng.vec3(1.0)),
    };
    let w = scalef(normalize(rng.vec3(1.0)), wmag);
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
        rng.range(-1.0, 1.0),
    ];
    let vars = std::array::from_fn(|i| i);
    let voronoi = rng.range(0.2, 0.8);
    let bend = FrameBend {
        vars,
        port,
        edge: 0,
        sign,
        rest: [
            [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
            [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
        ],
        voronoi,
        ei: [rng.range(0.5, 2.0), rng.range(0.5, 2.0)],
    };
    let twist = FrameTwist {
        vars,
        port,
        edge: 0,
        sign,
        slot: 0,
        rest: rng.range(-1.0, 1.0),
        voronoi,
        gj: rng.range(0.5, 2.0),
    };
    let mut c = Case {
        st,
        term: FrameBendTwist::new(bend, twist),
        x,
        what: format!("{what}, |ω| = {wmag}, sign {sign}"),
    };
    // Unwrapped one turn up, so the twist energy sees the unwrapping.
    c.st.twist_prev[0] = frame_reference_twist(&c) + std::f64::consts::TAU;
    c
}

fn frame_reference_twist(c: &Case<FrameBendTwist>) -> f64 {
    c.term
        .twist
        .reference_twist::<f64>(&c.st, &FrameTwist::reduced(&c.x))
}

/// Sets the raw reference twist to `target` by `turn` (a rotation by β of one frame about its
/// tangent, to which the twist is affine with slope ±1, measured by a trial turn), and
/// remembers `target` as the last accepted twist.
fn set_reference_twist<E>(
    c: &mut Case<E>,
    target: f64,
    twist: impl Fn(&Case<E>) -> f64,
    turn: impl Fn(&mut Case<E>, f64),
) {
    c.st.twist_prev[0] = target;
    let raw = twist(c);
    turn(c, 0.1);
    let slope = (twist(c) - raw) / 0.1;
    turn(c, (target - raw) / slope - 0.1);
    let now = twist(c);
    assert!((now - target).abs() < 1e-9, "{now} vs {target}");
}

const ANGLES: [(f64, &str); 4] = [
    (0.3, "bent"),
    (1.7, "strongly bent"),
    (175.0 * PI / 180.0, "nearly antiparallel tangents (175°)"),
    (1e-9, "straight"),
];

const WRAPS: [(f64, &str); 3] = [
    (PI - 1e-3, "reference twist near π"),
    (-PI + 1e-3, "reference twist near −π"),
    (PI - 1e-9, "reference twist at the wrap (FD steps cross it)"),
];

fn frame_cases() -> Vec<Case<FrameBendTwist>> {
    let mut rng = Rng::new(17);
    let mut out = Vec::new();
    for (phi, what) in ANGLES {
        for (wmag, sign) in [
            (0.05, 1.0),
            (0.8, -1.0),
            (0.0, -1.0),
            (2.5, 1.0),
            (0.0, 1.0),
        ] {
            out.push(frame_case(&mut rng, phi, wmag, sign, what));
        }
    }
    for (target, what) in WRAPS {
        for sign in [1.0, -1.0] {
            let mut c = frame_case(&mut rng, 0.9, 0.6, sign, what);
            set_reference_twist(&mut c, target, frame_reference_twist, |c, beta| {
                for p in [&mut c.term.bend.port, &mut c.term.twist.port] {
                    p.rest = turn_about_tangent(p.rest, beta);
                }
            });
            out.push(c);
        }
    }
    out
}

/// A rod stencil with turning angle `phi` at its vertex, edges oriented by `signs`.
fn rod_case(rng: &mut Rng, phi: f64, signs: [f64; 2], what: &str) -> Case<BendTwist> {
    let fr = random_rotation(rng);
    let (l0, l1) = (rng.range(0.5, 1.5), rng.range(0.5, 1.5));
    let x1 = rng.vec3(1.0);
    let x0 = sub(x1, scalef(fr[0], l0));
    let t1 = add(scalef(fr[0], phi.cos()), scalef(fr[1], phi.sin()));
    let x2 = add(x1, scalef(t1, l1));
    let near = |rng: &mut Rng, t: [f64; 3]| {
        let tr = normalize(add(t, rng.vec3(0.3)));
        EdgeRef {
            t: tr,
            u: rotate_axis(tr, rng.range(-3.0, 3.0), any_perpendicular(tr)),
        }
    };
    let st = State {
        q: vec![],
        edges: vec![
            near(rng, scalef(fr[0], signs[0])),
            near(rng, scalef(t1, signs[1])),
        ],
        frames: vec![],
        twist_prev: vec![0.0],
        load_factor: 0.7,
    };
    let mut x = [0.0; 11];
    for (k, p) in [x0, x1, x2].iter().enumerate() {
        x[3 * k..3 * k + 3].copy_from_slice(p);
    }
    x[9] = rng.range(-5.0, 5.0);
    x[10] = rng.range(-5.0, 5.0);
    let (vars, voronoi) = (std::array::from_fn(|i| i), rng.range(0.5, 1.5));
    let bend = Bend {
        vars,
        edges: [0, 1],
        signs,
        rest: [
            [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
            [rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)],
        ],
        voronoi,
        ei: [
            [rng.range(0.5, 2.0), rng.range(0.5, 2.0)],
            [rng.range(0.5, 2.0), rng.range(0.5, 2.0)],
        ],
    };
    let twist = Twist {
        vars,
        edges: [0, 1],
        signs,
        slot: 0,
        rest: rng.range(-1.0, 1.0),
        voronoi,
        gj: rng.range(0.5, 2.0),
    };
    let mut c = Case {
        st,
        term: BendTwist::new(bend, twist),
        x,
        what: format!("rod stencil, {what}, signs {signs:?}"),
    };
    c.st.twist_prev[0] = rod_reference_twist(&c) - std::f64::consts::TAU;
    c
}

fn rod_reference_twist(c: &Case<BendTwist>) -> f64 {
    c.term
        .twist
        .reference_twist::<f64>(&c.st, &Twist::reduced(&c.x))
}

/// The rod stencils (every turning angle and wrap, all four orientations), each passed
/// through `prepare` after it is made (before its reference twist is set near a wrap).
fn rod_cases_with(seed: u64, prepare: impl Fn(&mut Case<BendTwist>)) -> Vec<Case<BendTwist>> {
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    let signs = [[1.0, 1.0], [-1.0, 1.0], [1.0, -1.0], [-1.0, -1.0]];
    for (phi, what) in ANGLES {
        for s in signs {
            let mut c = rod_case(&mut rng, phi, s, what);
            prepare(&mut c);
            out.push(c);
        }
    }
    for (target, what) in WRAPS {
        for s in signs {
            let mut c = rod_case(&mut rng, 0.9, s, what);
            prepare(&mut c);
            // Turning a director about its own tangent keeps a committed edge committed.
            set_reference_twist(&mut c, target, rod_reference_twist, |c, beta| {
                let r = &mut c.st.edges[1];
                r.u = rotate_axis(r.t, beta, r.u);
            });
            out.push(c);
        }
    }
    out
}

fn rod_cases() -> Vec<Case<BendTwist>> {
    rod_cases_with(18, |_| {})
}

/// Moves the case's edge reference frames onto its edges, as `Model::commit` does after an
/// accepted iterate (where Newton assembles Hessians: the kernel's closed-form path).
fn commit(c: &mut Case<BendTwist>) {
    for j in 0..2 {
        let a = [c.x[3 * j], c.x[3 * j + 1], c.x[3 * j + 2]];
        let b = [c.x[3 * j + 3], c.x[3 * j + 4], c.x[3 * j + 5]];
        let t = normalize(scalef(sub(b, a), c.term.bend.signs[j]));
        let r = &mut c.st.edges[j];
        r.u = normalize(transport(r.t, t, r.u));
        r.t = t;
    }
    c.st.twist_prev[0] = rod_reference_twist(c) + std::f64::consts::TAU;
}

/// The rod cases at committed reference frames.
fn committed_rod_cases() -> Vec<Case<BendTwist>> {
    rod_cases_with(19, |c| {
        commit(c);
        c.what += ", committed";
    })
}

fn max_abs<'a>(v: impl IntoIterator<Item = &'a f64>) -> f64 {
    v.into_iter().fold(1e-300f64, |m, x| m.max(x.abs()))
}

fn matches_finite_differences<E: Term<11>>(c: &Case<E>) {
    let (t, st, x) = (&c.term, &c.st, c.x);
    let d = t.derivatives(st, &x);
    assert!(
        (d.v - t.eval::<f64>(st, &x)).abs() <= 1e-12 * d.v.abs(),
        "{}",
        c.what
    );
    let h = d.hessian();
    let (gmax, hmax) = (max_abs(&d.g), max_abs(h.iter().flatten()));
    let (mut gerr, mut herr) = (0.0f64, 0.0f64);
    for i in 0..11 {
        let (mut xp, mut xm) = (x, x);
        xp[i] += H;
        xm[i] -= H;
        let fd = (t.eval::<f64>(st, &xp) - t.eval::<f64>(st, &xm)) / (2.0 * H);
        gerr = gerr.max((fd - d.g[i]).abs() / gmax);
        let (gp, gm) = (t.derivatives(st, &xp).g, t.derivatives(st, &xm).g);
        for j in 0..11 {
            herr = herr.max(((gp[j] - gm[j]) / (2.0 * H) - h[j][i]).abs() / hmax);
        }
    }
    assert!(gerr < TOL, "{}: gradient relative error {gerr:.3e}", c.what);
    assert!(herr < TOL, "{}: Hessian relative error {herr:.3e}", c.what);
    assert!(h.iter().flatten().all(|v| v.is_finite()), "{}", c.what);
}

/// The fused derivatives are the separate terms' (each through its own assembly path), and
/// its energies by category, its generic evaluation and its remembered twist are theirs too.
fn equals_the_separate_terms<E: Fused>(c: &Case<E>) {
    let (t, st, x) = (&c.term, &c.st, c.x);
    let [b, w] = t.separate_derivatives(st, &x);
    let f = t.derivatives(st, &x);
    let sum = b + w;
    let (hs, hf) = (sum.hessian(), f.hessian());
    let scale = max_abs(hs.iter().flatten().chain(&sum.g));
    assert!((f.v - sum.v).abs() <= 1e-12 * sum.v.abs(), "{}", c.what);
    for i in 0..11 {
        assert!(
            (f.g[i] - sum.g[i]).abs() <= 1e-12 * scale,
            "{}: g{i} {} vs {}",
            c.what,
            f.g[i],
            sum.g[i]
        );
        for j in 0..11 {
            assert!(
                (hf[i][j] - hs[i][j]).abs() <= 1e-12 * scale,
                "{}: h{i}{j} {} vs {}",
                c.what,
                hf[i][j],
                hs[i][j]
            );
        }
    }
    let generic = t.eval(st, &HD::<11>::vars(&x));
    assert!((generic.v - f.v).abs() <= 1e-12 * f.v.abs(), "{}", c.what);
    for i in 0..11 {
        assert!((generic.g[i] - f.g[i]).abs() <= 1e-12 * scale, "{}", c.what);
    }
    let mut st_q = st.clone();
    st_q.q = x.to_vec();
    let mut parts = [0.0; 2];
    t.energies_by_category(&st_q, &mut parts);
    assert_eq!(E::CATEGORIES, [Category::Bend, Category::Twist]);
    for (p, e) in parts.iter().zip(t.separate_energies(&st_q)) {
        assert!((p - e).abs() <= 1e-12 * e.abs(), "{}: {p} vs {e}", c.what);
    }
    assert_eq!(t.remembered(&st_q), t.twist_remembered(&st_q), "{}", c.what);
}

#[test]
fn frame_kernel_matches_finite_differences() {
    frame_cases().iter().for_each(matches_finite_differences);
}

#[test]
fn frame_kernel_equals_frame_bend_plus_frame_twist() {
    frame_cases().iter().for_each(equals_the_separate_terms);
}

#[test]
fn rod_kernel_matches_finite_differences() {
    rod_cases().iter().for_each(matches_finite_differences);
}

#[test]
fn rod_kernel_equals_bend_plus_twist() {
    rod_cases().iter().for_each(equals_the_separate_terms);
}

#[test]
fn rod_kernel_at_committed_frames_matches_finite_differences() {
    committed_rod_cases()
        .iter()
        .for_each(matches_finite_differences);
}

#[test]
fn rod_kernel_at_committed_frames_equals_bend_plus_twist() {
    committed_rod_cases()
        .iter()
        .for_each(equals_the_separate_terms);
}
