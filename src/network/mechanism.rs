//! Mechanisms: zero-stiffness modes of a structure that its loads excite.
//!
//! The solver hands over the zero-stiffness modes of the start of the path (the lowest
//! eigenvectors of the Hessian with eigenvalue ≈ 0). A mode is a mechanism when the rods that move
//! in it move rigidly (a legitimately soft bending mode of a very slender rod deforms its rod) and
//! a loaded or driven node moves in it. An unsupported structure's rigid rotations are gauge
//! modes, not mechanisms: they are projected out first (its translations are removed by the
//! gauge node, `build/gauge.rs`). A rigid turn about a held line that dead loads can only swing
//! down by at most a quarter turn is not one (`swings_down`). The description names the rods and, when they turn together as
//! one rigid body, the axis.

use crate::math::vec::{cross, dot, norm, scalef, sub};
use crate::network::info::RodInfo;
use crate::network::model::Model;
use crate::variables::VarKind;

/// Part of a mode's motion (W-norm) that must remain after removing gauge rotations.
const REMAINING: f64 = 1e-3;
/// Largest residual of a rigid-motion fit, relative to the motion, for a rod to move rigidly.
const RIGID: f64 = 1e-3;

/// The first mode that is an excited mechanism, described; `f` is the load vector over free
/// unknowns (the gradient change from λ = 0 to 1 at the current state).
pub fn describe(
    model: &Model,
    rods: &[RodInfo],
    gauge_node: Option<usize>,
    modes: &[Vec<f64>],
    f: &[f64],
) -> Option<String> {
    let w = weights(model);
    let gauges = gauge_modes(model, gauge_node);
    for mode in modes {
        let v = without_gauge(mode, &gauges, &w);
        if wdot(&v, &v, &w).sqrt() < REMAINING {
            continue;
        }
        if let Some(d) = mechanism(model, rods, &v, f) {
            return Some(d);
        }
    }
    None
}

/// The solver's metric W = diag(1/s²) (`Model::unknown_scales`).
fn weights(model: &Model) -> Vec<f64> {
    let mut scales = vec![1.0; model.n_free];
    model.unknown_scales(&mut scales);
    scales.iter().map(|s| 1.0 / (s * s)).collect()
}

/// `mode` with its components along the (W-orthonormal) gauge modes removed.
fn without_gauge(mode: &[f64], gauges: &[Vec<f64>], w: &[f64]) -> Vec<f64> {
    let mut v = mode.to_vec();
    for r in gauges {
        let c = wdot(&v, r, w);
        v.iter_mut().zip(r).for_each(|(x, r)| *x -= c * r);
    }
    v
}

/// The rigid rotations of an unsupported structure about its gauge node (none if supported).
pub fn gauge_modes(model: &Model, gauge_node: Option<usize>) -> Vec<Vec<f64>> {
    gauge_node.map_or_else(Vec::new, |g| rotations(model, g, &weights(model)))
}

/// The rigid turns of an unsupported structure about its gauge node to second order: for each
/// axis k, the first-order motion r_k (`turn`), and for each pair j ≤ k (in the order (0,0), (0,1), (0,2), (1,1), (1,2), (2,2)) the
/// positions' second-order motion ½(e_j × (e_k × x) + e_k × (e_j × x)). Dead loads have no
/// Hessian: their stiffness along a finite turn is in the second-order term only.
pub fn turn_paths(
    model: &Model,
    gauge_node: Option<usize>,
) -> Option<crate::solver::problem::TurnPaths> {
    let g = gauge_node?;
    let u = model.unknowns();
    let xg = model.position(g);
    let axis = |k: usize| -> [f64; 3] { std::array::from_fn(|j| f64::from(j == k)) };
    let first: Vec<Vec<f64>> = (0..3).map(|k| turn(model, xg, axis(k))).collect();
    let mut second = Vec::new();
    for j in 0..3 {
        for k in j..3 {
            let (a, b) = (axis(j), axis(k));
            let mut c = vec![0.0; model.n_free];
            for n in 0..model.layout.n_nodes() {
                let x = sub(model.position(n), xg);
                let (p, q) = (cross(a, cross(b, x)), cross(b, cross(a, x)));
                for i3 in 0..3 {
                    if let Some(i) = u.of_node(n, i3) {
                        c[i] = 0.5 * (p[i3] + q[i3]);
                    }
                }
            }
            second.push(c);
        }
    }
    Some(crate::solver::problem::TurnPaths { first, second })
}

/// Whether every mode lies in the span of an unsupported structure's rigid rotations.
pub fn gauge_only(model: &Model, gauge_node: Option<usize>, modes: &[Vec<f64>]) -> bool {
    if gauge_node.is_none() {
        return false;
    }
    let w = weights(model);
    let gauges = gauge_modes(model, gauge_node);
    modes.iter().all(|mode| {
        let v = without_gauge(mode, &gauges, &w);
        wdot(&v, &v, &w).sqrt() < REMAINING
    })
}

fn wdot(a: &[f64], b: &[f64], w: &[f64]) -> f64 {
    a.iter().zip(b).zip(w).map(|((x, y), w)| w * x * y).sum()
}

/// The three rigid rotations about the gauge node (`turn`), W-orthonormalized.
fn rotations(model: &Model, gauge: usize, w: &[f64]) -> Vec<Vec<f64>> {
    let xg = model.position(gauge);
    let mut out: Vec<Vec<f64>> = Vec::new();
    for k in 0..3 {
        let mut omega = [0.0; 3];
        omega[k] = 1.0;
        let mut r = turn(model, xg, omega);
        for q in &out {
            let c = wdot(&r, q, w);
            r.iter_mut().zip(q).for_each(|(x, q)| *x -= c * q);
        }
        let nr = wdot(&r, &r, w).sqrt();
        if nr > 1e-12 {
            r.iter_mut().for_each(|x| *x /= nr);
            out.push(r);
        }
    }
    out
}

/// The rigid turn ω about `xg` over the free unknowns, to first order: positions
/// ω × (x − xg), edge angles ω·t (they are measured from parallel-transported references,
/// which do not turn about the edge), vertex frames ω.
fn turn(model: &Model, xg: [f64; 3], omega: [f64; 3]) -> Vec<f64> {
    let u = model.unknowns();
    let mut r = vec![0.0; model.n_free];
    for n in 0..model.layout.n_nodes() {
        let m = cross(omega, sub(model.position(n), xg));
        for (j, mj) in m.iter().enumerate() {
            if let Some(i) = u.of_node(n, j) {
                r[i] = *mj;
            }
        }
    }
    for (e, [a, b]) in model.edge_nodes.iter().enumerate() {
        if let Some(i) = u.of(model.layout.theta(e)) {
            let t = sub(model.position(*b), model.position(*a));
            r[i] = dot(omega, t) / norm(t).max(f64::MIN_POSITIVE);
        }
    }
    for f in 0..model.layout.n_frames() {
        for (j, v) in model.layout.frame(f).into_iter().enumerate() {
            if let Some(i) = u.of(v) {
                r[i] = omega[j];
            }
        }
    }
    r
}

/// Motion of node `n` in mode `v` (zero for fixed coordinates).
fn motion(model: &Model, v: &[f64], n: usize) -> [f64; 3] {
    let u = model.unknowns();
    std::array::from_fn(|k| u.of_node(n, k).map_or(0.0, |i| v[i]))
}

fn mechanism(model: &Model, rods: &[RodInfo], v: &[f64], f: &[f64]) -> Option<String> {
    let nn = model.layout.n_nodes();
    let moves: Vec<f64> = (0..nn).map(|n| norm(motion(model, v, n))).collect();
    let loads: Vec<f64> = (0..nn).map(|n| norm(motion(model, f, n))).collect();
    let (vmax, fmax) = (max(&moves), max(&loads));
    let angles = || {
        model.free.iter().enumerate().filter_map(|(var, &i)| {
            (i != crate::variables::FIXED && model.kind(var) == VarKind::Angle)
                .then_some(i as usize)
        })
    };
    // Torques count as loads too (a rod spun about its axis by a torque alone).
    let tmax = angles().map(|i| f[i].abs()).fold(0.0, f64::max);
    let size = fmax * model.length_scale + tmax;
    if size == 0.0 {
        return None;
    }
    // Excited: a loaded (or driven) node moves, or a loaded angle (a torque) turns.
    let angle_loaded = angles().any(|i| f[i].abs() > 1e-12 * size && v[i].abs() > 1e-6);
    let turn = angles().map(|i| v[i].abs()).fold(0.0, f64::max);
    // No node moves (to round-off of the angles' motion, counted as ē·θ): rods spinning
    // about their own centrelines.
    if vmax <= 1e-9 * turn * model.mean_edge() {
        return spin(model, rods, v, turn).filter(|_| angle_loaded);
    }
    let moving = |n: usize| moves[n] > 1e-3 * vmax;
    let node_loaded = (0..nn).any(|n| moving(n) && loads[n] > 1e-9 * fmax);
    if !(node_loaded || angle_loaded) {
        return None;
    }
    let moving_rods: Vec<&RodInfo> = rods
        .iter()
        .filter(|r| r.nodes.iter().any(|&n| moving(n)))
        .collect();
    // Every moving rod moves rigidly: otherwise this is a soft elastic mode, not a mechanism.
    if !moving_rods.iter().all(|r| moves_rigidly(model, v, r)) {
        return None;
    }
    let body: Vec<usize> = moving_rods
        .iter()
        .flat_map(|r| r.nodes.iter().copied())
        .collect();
    if !angle_loaded && swings_down(model, v, f, &body, vmax) {
        return None;
    }
    let names: Vec<String> = moving_rods
        .iter()
        .map(|r| format!("\"{}\"", r.name))
        .collect();
    let nodes: Vec<usize> = (0..nn).filter(|&n| moving(n)).collect();
    let rods_text = format!(
        "rod{} {}",
        if names.len() == 1 { "" } else { "s" },
        names.join(", ")
    );
    let what = match rigid_fit(model, v, &nodes) {
        Some(((t, omega, c), res)) if res <= RIGID => axis_text(t, omega, c, vmax, &rods_text),
        _ => format!("rigid motions of {rods_text} (a linkage)"),
    };
    Some(format!(
        "{what}: it costs no elastic energy and the loads act on it (add supports or joints that \
         resist it)"
    ))
}

/// The rods that spin rigidly about their own centrelines in mode `v`, which moves no node
/// (every edge angle of a moving rod turns alike: an isotropic rod's spin costs no energy),
/// described; None if some moving rod twists instead. `turn` is the largest angle motion.
fn spin(model: &Model, rods: &[RodInfo], v: &[f64], turn: f64) -> Option<String> {
    let u = model.unknowns();
    let angle = |e: usize| u.of(model.layout.theta(e)).map_or(0.0, |i| v[i]);
    let mut names = Vec::new();
    for r in rods {
        let t: Vec<f64> = r.edges.iter().map(|&e| angle(e)).collect();
        if t.iter().all(|a| a.abs() <= 1e-3 * turn) {
            continue;
        }
        let mean = t.iter().sum::<f64>() / t.len() as f64;
        if t.iter().any(|a| (a - mean).abs() > RIGID * turn) {
            return None;
        }
        names.push(format!("\"{}\"", r.name));
    }
    if names.is_empty() {
        return None;
    }
    let s = if names.len() == 1 { "" } else { "s" };
    Some(format!(
        "spin of rod{s} {} about {} own centreline{s}: it costs no elastic energy and a torque \
         acts on it (add supports or joints that hold the rod's turn about its axis, e.g. a \
         Clamp)",
        names.join(", "),
        if names.len() == 1 { "its" } else { "their" }
    ))
}

/// Whether mode `v` turns one rigid body (the nodes `body`) about a line held by a fixed node,
/// under dead loads (`f`, the gradient's rate of change: minus the loads) that can only swing it
/// down by at most a quarter turn. Along a finite turn θ about a held line the elastic energy
/// stays constant and the dead loads' potential is V(θ) = −P cos θ − Q sin θ, with
/// P = Σ F·r⊥ (r⊥ the node's offset from the line; P > 0: the loads pull the body away from
/// the line, a hanging pendulum) and Q = Σ F·(a × r⊥) (their moment about the line, a × r⊥ being
/// the motion per unit turn): bounded, with its minimum at the θ* where
/// (cos θ*, sin θ*) ∝ (P, Q). The turn cannot run away; where the minimum is within a quarter
/// turn (P ≥ 0) the body hangs from the line as drawn or swings down to hang (a wire drawn
/// sagging sideways), and Newton's steps get there. Drawn above the line (P < 0: a pinned
/// portal or arch under a vertical load, an inverted pendulum) its only stable state is turned
/// over, which is not the structure that was drawn: a mechanism. Prescribed motions and
/// torques are not dead forces on the body's nodes: not judged here.
fn swings_down(model: &Model, v: &[f64], f: &[f64], body: &[usize], vmax: f64) -> bool {
    let driven = model.prescribed.iter().any(|p| p.start != p.end)
        || model
            .prescribed_rotations
            .iter()
            .any(|r| r.rotation != [0.0; 3])
        || !model.staged.is_empty();
    let Some(((t, omega, c), res)) = rigid_fit(model, v, body).filter(|_| !driven) else {
        return false;
    };
    let w = norm(omega);
    // One body turning (no slide along its axis: a screw is not a turn about a fixed line).
    if res > RIGID || w == 0.0 {
        return false;
    }
    let a = scalef(omega, 1.0 / w);
    if dot(t, a).abs() > RIGID * vmax {
        return false;
    }
    let t_perp = sub(t, scalef(a, dot(t, a)));
    let p = crate::math::vec::add(c, scalef(cross(omega, t_perp), 1.0 / (w * w)));
    let u = model.unknowns();
    let offset = |n: usize| {
        let r = sub(model.position(n), p);
        sub(r, scalef(a, dot(r, a)))
    };
    // Held: a node of the body fixed in all three coordinates lies on the line.
    let held = body
        .iter()
        .any(|&n| (0..3).all(|k| u.of_node(n, k).is_none()) && w * norm(offset(n)) <= RIGID * vmax);
    if !held {
        return false;
    }
    let (mut pp, mut q, mut size) = (0.0, 0.0, 0.0);
    let mut seen = vec![false; model.layout.n_nodes()];
    for &n in body {
        if std::mem::replace(&mut seen[n], true) {
            continue;
        }
        let load = scalef(motion(model, f, n), -1.0);
        let r = offset(n);
        pp += dot(load, r);
        q += dot(load, cross(a, r));
        size += norm(load) * norm(r);
    }
    // Neither pulling nor turning (loads along the line): neutral, left to the other tests.
    // Level with the line (P = 0 to round-off: a body drawn in the horizontal plane through
    // its hinge line) it swings down by a quarter turn.
    pp.hypot(q) > 1e-9 * size && pp >= -1e-9 * size
}

/// Whether some rod that moves in mode `v` does not move rigidly (a rod's spin about its own
/// axis, which moves no node, counts as rigid).
pub fn deforms(model: &Model, rods: &[RodInfo], v: &[f64]) -> bool {
    let nn = model.layout.n_nodes();
    let moves: Vec<f64> = (0..nn).map(|n| norm(motion(model, v, n))).collect();
    let vmax = max(&moves);
    if vmax == 0.0 {
        return false;
    }
    rods.iter()
        .filter(|r| r.nodes.iter().any(|&n| moves[n] > 1e-3 * vmax))
        .any(|r| !moves_rigidly(model, v, r))
}

/// Whether rod `r` moves rigidly in mode `v` (a rigid-motion fit with residual within RIGID).
fn moves_rigidly(model: &Model, v: &[f64], r: &RodInfo) -> bool {
    rigid_fit(model, v, &r.nodes).is_some_and(|(_, res)| res <= RIGID)
}

fn max(v: &[f64]) -> f64 {
    v.iter().cloned().fold(0.0, f64::max)
}

type Rigid = ([f64; 3], [f64; 3], [f64; 3]);

/// Least-squares rigid motion v(x) = t + ω × (x − c) of `nodes` (c their centroid), and the
/// residual relative to the motion.
fn rigid_fit(model: &Model, v: &[f64], nodes: &[usize]) -> Option<(Rigid, f64)> {
    if nodes.is_empty() {
        return None;
    }
    let k = nodes.len() as f64;
    let c = nodes.iter().fold([0.0; 3], |a, &n| {
        let p = model.position(n);
        [a[0] + p[0] / k, a[1] + p[1] / k, a[2] + p[2] / k]
    });
    let t = nodes.iter().fold([0.0; 3], |a, &n| {
        let m = motion(model, v, n);
        [a[0] + m[0] / k, a[1] + m[1] / k, a[2] + m[2] / k]
    });
    // ω from Σ r × (v − t) = J ω, J = Σ (|r|² I − r rᵀ) (the inertia tensor of the nodes).
    let mut j = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for &n in nodes {
        let r = sub(model.position(n), c);
        let m = sub(motion(model, v, n), t);
        let rr = dot(r, r);
        for a in 0..3 {
            for e in 0..3 {
                j[a][e] += if a == e { rr } else { 0.0 } - r[a] * r[e];
            }
        }
        let x = cross(r, m);
        (0..3).for_each(|a| b[a] += x[a]);
    }
    let omega = solve3(j, b);
    let (mut res, mut tot) = (0.0, 0.0);
    for &n in nodes {
        let r = sub(model.position(n), c);
        let fit = crate::math::vec::add(t, cross(omega, r));
        let m = motion(model, v, n);
        res += dot(sub(m, fit), sub(m, fit));
        tot += dot(m, m);
    }
    Some(((t, omega, c), (res / tot.max(f64::MIN_POSITIVE)).sqrt()))
}

/// Solves the 3×3 system J ω = b in least squares (a line of nodes leaves rotation about
/// itself undetermined: the pseudo-inverse drops it).
fn solve3(j: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let tr = j[0][0] + j[1][1] + j[2][2];
    let mut m = j;
    // Tikhonov with a tiny fraction of the trace: the undetermined part stays zero.
    (0..3).for_each(|a| m[a][a] += 1e-12 * tr.max(f64::MIN_POSITIVE));
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(&m);
    if d == 0.0 {
        return [0.0; 3];
    }
    std::array::from_fn(|k| {
        let mut mk = m;
        (0..3).for_each(|a| mk[a][k] = b[a]);
        det(&mk) / d
    })
}

/// "rotation of rods … about the line through P along D", or a translation.
fn axis_text(t: [f64; 3], omega: [f64; 3], c: [f64; 3], vmax: f64, rods: &str) -> String {
    let w = norm(omega);
    // -0.0000 reads as a different number: print zeros as zeros.
    let fmt = |p: [f64; 3]| {
        let z = |x: f64| if x.abs() < 5e-5 { 0.0 } else { x };
        format!("({:.4}, {:.4}, {:.4})", z(p[0]), z(p[1]), z(p[2]))
    };
    // Deterministic sign of a direction: its largest component positive.
    let signed = |d: [f64; 3]| {
        let k = (0..3)
            .max_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()))
            .unwrap_or(0);
        if d[k] < 0.0 {
            scalef(d, -1.0)
        } else {
            d
        }
    };
    // A rotation whose largest motion over the nodes is negligible against the translation.
    let reach = vmax.max(norm(t));
    if w == 0.0 || w * 1e9 < reach {
        let d = signed(scalef(t, 1.0 / norm(t).max(f64::MIN_POSITIVE)));
        return format!("translation of {rods} along {}", fmt(d));
    }
    // The axis: points where the motion is along ω only, p = c + ω × t_⊥ / |ω|².
    let axis = scalef(omega, 1.0 / w);
    let t_perp = sub(t, scalef(axis, dot(t, axis)));
    let p = crate::math::vec::add(c, scalef(cross(omega, t_perp), 1.0 / (w * w)));
    format!(
        "rotation of {rods} about the line through {} along {}",
        fmt(p),
        fmt(signed(axis))
    )
}
