//! Multiple equilibria (`rodnet states`): from the scene's own equilibrium, the network's
//! deflection from rest is reversed, it is mirrored through its supports' plane, and it is
//! pushed along its lowest eigenmodes, both ways and by the amplitudes of [`AMPLITUDES`];
//! Newton (which leaves saddles along negative curvature) settles each start; states not seen
//! before are kept and searched from in turn, breadth first. These reach local minima (and the
//! scene's own equilibrium whatever its index); unstable equilibria are then sought by Newton
//! on the residual alone from the rest state, from the minima's mirror images, from midpoints
//! between them, and from where the holding force changes sign on the displacement-controlled
//! path between two of them (`network/drag.rs`).

use crate::math::vec::{cross, dist, dot, norm, normalize, scale, sub};
use crate::network::drag;
use crate::network::stability::analyse;
use crate::network::Network;
use crate::solver::{NewtonReport, NewtonSettings};
use crate::variables::State;

/// One equilibrium found.
#[derive(Debug, Clone)]
pub struct Found {
    pub state: State,
    pub report: NewtonReport,
    /// No negative eigenvalue and no zero one but the gauge's, among the lowest computed.
    pub stable: bool,
    /// Negative eigenvalues among the lowest computed (a lower bound when `index_at_least`).
    pub index: usize,
    pub index_at_least: bool,
    /// The lowest eigenvalue, N/m.
    pub lowest_eigenvalue: f64,
    /// How it was reached: "scene" or "state k, mode j, ±, amplitude".
    pub found_by: String,
    /// Its lowest modes (over the free unknowns), the directions searched from it.
    pub modes: Vec<Vec<f64>>,
    /// An earlier state this one is a copy of under a symmetry (a reflection or turn: every
    /// node at the same distances from the others, to 1e-6 of the structure's size).
    pub symmetric_to: Option<usize>,
    /// Largest node distance from the first state (the scene's own), m.
    pub distance_to_first: f64,
}

/// Eigenmodes pushed along from each state.
pub const MODES: usize = 4;
/// Push amplitudes: the largest node motion over the structure's bounding-box diagonal.
pub const AMPLITUDES: [f64; 3] = [0.05, 0.2, 0.5];

/// Searches from the network's current equilibrium (`first` its solve) for up to `max` states;
/// `rest` is the network's state before that solve.
pub fn search(
    net: &mut Network,
    settings: &NewtonSettings,
    first: NewtonReport,
    rest: &State,
    max: usize,
) -> Result<Vec<Found>, String> {
    let size = diagonal(net);
    let mut found = vec![describe(net, first, "scene".into())?];
    let mut next = 0;
    let settle = |net: &mut Network| {
        crate::network::solve(&mut net.model, &settings.clone().equilibrate_only(true))
    };
    while next < found.len() && found.len() < max {
        let from = found[next].state.clone();
        let modes = std::mem::take(&mut found[next].modes);
        // First the state's deflection from rest reversed: where a structure buckled one way,
        // the other way is the first state to look for (a snap-through needs a push past the
        // saddle between them, which pushes along the lowest modes may not reach).
        // Then its mirror image through the plane of the supports: a curved structure at rest
        // (a shallow arch, a dome) has no deflection to reverse, and its inverted state is
        // there (for a straight or flat rest shape the two starts are one).
        let mut starts = vec![("reversed", reversed(net, &from, rest))];
        if let Some(m) = mirrored(net, &from, size) {
            starts.push(("mirrored through its supports' plane", m));
        }
        for (how, start) in starts {
            net.model.state = start;
            net.model.commit();
            let r = settle(net);
            if r.converged && !found.iter().any(|f| same(net, &f.state, size)) {
                found.push(describe(net, r, format!("state {next} {how}"))?);
            }
        }
        if found.len() >= max {
            found.truncate(max);
            break;
        }
        'modes: for (j, mode) in modes.iter().enumerate() {
            for sign in [1.0, -1.0] {
                for &amp in &AMPLITUDES {
                    if found.len() >= max {
                        break 'modes;
                    }
                    net.model.state = from.clone();
                    push(net, mode, sign * amp * size);
                    let r = settle(net);
                    if !r.converged {
                        continue;
                    }
                    if found.iter().any(|f| same(net, &f.state, size)) {
                        continue;
                    }
                    let sign_name = if sign > 0.0 { "+" } else { "-" };
                    let how = format!("state {next}, mode {j}, {sign_name}{amp}");
                    found.push(describe(net, r, how)?);
                }
            }
        }
        next += 1;
    }
    saddles(net, settings, rest, &mut found, size, max)?;
    for j in 1..found.len() {
        found[j].symmetric_to =
            (0..j).find(|&i| congruent(net, &found[i].state, &found[j].state, size));
        let l = &net.model.layout;
        found[j].distance_to_first = (0..l.n_nodes())
            .map(|n| {
                dist(
                    &l.position(&found[0].state.q, n),
                    &l.position(&found[j].state.q, n),
                )
            })
            .fold(0.0, f64::max);
    }
    net.model.state = found[0].state.clone();
    Ok(found)
}

/// Unstable equilibria the pushes cannot settle on (Newton leaves them): residual Newton
/// (`solver::saddle`) from the rest state at the full load (a column held straight, a shell
/// held flat), from each stable state's mirror image (an inverted arch that is not stable),
/// from the midpoint of each pair of stable states found (the symmetric state between mirror
/// images), and from where the force changes sign on the displacement-controlled path between
/// each pair (`network/drag.rs`: the barrier between them, an S-shaped arch on its way
/// through).
fn saddles(
    net: &mut Network,
    settings: &NewtonSettings,
    rest: &State,
    found: &mut Vec<Found>,
    size: f64,
    max: usize,
) -> Result<(), String> {
    let stable: Vec<usize> = (0..found.len()).filter(|&i| found[i].stable).collect();
    let mut starts = vec![(rest.clone(), "residual Newton from rest".to_string())];
    for &i in &stable {
        if let Some(m) = mirrored(net, &found[i].state, size) {
            starts.push((m, format!("residual Newton from state {i} mirrored")));
        }
    }
    let mut pairs = Vec::new();
    for (a, &i) in stable.iter().enumerate() {
        for &j in &stable[a + 1..] {
            let mut mid = found[i].state.clone();
            let other = &found[j].state;
            for v in net.model.layout.positions() {
                mid.q[v] = 0.5 * (mid.q[v] + other.q[v]);
            }
            starts.push((mid, format!("residual Newton between states {i} and {j}")));
            pairs.push((i, j));
        }
    }
    for (k, (start, how)) in starts.into_iter().enumerate() {
        if found.len() >= max {
            return Ok(());
        }
        // From rest the loads and motions are followed in steps, each from the last state (a
        // support moved at once would tear its edge); the other starts are near their states.
        let path: Vec<f64> = match k {
            0 => (1..=RESIDUAL_STEPS)
                .map(|i| i as f64 / RESIDUAL_STEPS as f64)
                .collect(),
            _ => vec![1.0],
        };
        settle_any(net, settings, start, &path, how, found, size)?;
    }
    for (i, j) in pairs {
        let (a, b) = (found[i].state.clone(), found[j].state.clone());
        let Some(var) = drag::coordinate(net, &a, &b) else {
            continue;
        };
        let node = net.model.layout.node_of(var).unwrap_or(0);
        let axis = ["x", "y", "z"][var - net.model.layout.node_coord(node, 0)];
        for c in drag::crossings(net, &a, &b, var, settings) {
            if found.len() >= max {
                return Ok(());
            }
            let how = format!(
                "residual Newton from the path between states {i} and {j} (node {node} held \
                 along {axis}; its force changes sign at {axis} = {:.6e} m)",
                c.at
            );
            settle_any(net, settings, c.state, &[1.0], how, found, size)?;
        }
    }
    Ok(())
}

/// Residual Newton from `start` along `path`; a new equilibrium is described and kept.
fn settle_any(
    net: &mut Network,
    settings: &NewtonSettings,
    start: State,
    path: &[f64],
    how: String,
    found: &mut Vec<Found>,
    size: f64,
) -> Result<(), String> {
    net.model.state = start;
    net.model.commit();
    let mut p = crate::network::problem::NetworkProblem::new(&mut net.model);
    let analyses = p.model.analyses.clone();
    let r = crate::solver::saddle::converge_any(&mut p, settings, path, &analyses);
    drop(p);
    if r.converged && !found.iter().any(|f| same(net, &f.state, size)) {
        found.push(describe(net, r, how)?);
    }
    Ok(())
}

/// Load steps of the residual-Newton path from rest.
const RESIDUAL_STEPS: usize = 8;

fn describe(net: &mut Network, report: NewtonReport, found_by: String) -> Result<Found, String> {
    let st = analyse(net, MODES)?;
    Ok(Found {
        state: net.model.state.clone(),
        report,
        stable: st.stable,
        index: st.negative,
        index_at_least: st.negative_at_least,
        lowest_eigenvalue: st.eigenvalues.first().copied().unwrap_or(f64::NAN),
        found_by,
        modes: st.modes,
        symmetric_to: None,
        distance_to_first: 0.0,
    })
}

/// Whether `a` and `b` are one shape placed differently (node by node: a reflection or turn of
/// it): every node's distances to eight nodes spread over the numbering agree to 1e-6 of the
/// structure's size. Distinct states of one structure differ in some such distance.
fn congruent(net: &Network, a: &State, b: &State, size: f64) -> bool {
    let l = &net.model.layout;
    let n = l.n_nodes();
    let anchors: Vec<usize> = (0..8).map(|k| k * n / 8).collect();
    (0..n).all(|i| {
        anchors.iter().all(|&m| {
            let da = dist(&l.position(&a.q, i), &l.position(&a.q, m));
            let db = dist(&l.position(&b.q, i), &l.position(&b.q, m));
            (da - db).abs() <= 1e-6 * size
        })
    })
}

/// `state` with the free node coordinates' displacement from `rest` reversed
/// (x → 2 x_rest − x); twist angles and frames keep theirs.
fn reversed(net: &Network, state: &State, rest: &State) -> State {
    let m = &net.model;
    let mut s = state.clone();
    for v in m.layout.positions() {
        if m.free[v] != crate::variables::FIXED {
            s.q[v] = 2.0 * rest.q[v] - s.q[v];
        }
    }
    s
}

/// `state` with its free nodes mirrored through the plane of the supports (through the three
/// held nodes farthest apart; for supports on a line, the plane through it that the
/// structure's farthest node is farthest from); `None` with fewer than two supported places or
/// a structure on the line of its supports (a column: reversing its deflection is the mirror).
fn mirrored(net: &Network, state: &State, size: f64) -> Option<State> {
    let m = &net.model;
    let l = &m.layout;
    let at = |n: usize| l.position(&state.q, n);
    // Supports that hold their node (a coordinate fixed, or on a roller's plane); an elastic
    // support moves with the structure and says nothing of where it is held.
    let held: Vec<[f64; 3]> = net
        .supports
        .iter()
        .map(|s| s.node)
        .filter(|&n| {
            let v = l.node(n);
            v.iter().any(|&x| m.free[x] == crate::variables::FIXED) || m.rollers.touches(&v)
        })
        .map(at)
        .collect();
    let (a, b) = farthest_pair(&held)?;
    let u = normalize(sub(b, a));
    let off_line = |p: [f64; 3]| {
        let d = sub(p, a);
        sub(d, scale(u, dot(d, u)))
    };
    let third = held
        .iter()
        .map(|&p| off_line(p))
        .max_by(|x, y| norm(*x).total_cmp(&norm(*y)))?;
    let normal = if norm(third) > 1e-6 * norm(sub(b, a)) {
        normalize(cross(u, third))
    } else {
        let far = (0..l.n_nodes())
            .map(|n| off_line(at(n)))
            .max_by(|x, y| norm(*x).total_cmp(&norm(*y)))?;
        if norm(far) <= 1e-6 * size {
            return None;
        }
        normalize(far)
    };
    let mut s = state.clone();
    for n in 0..l.n_nodes() {
        let p = at(n);
        let image = sub(p, scale(normal, 2.0 * dot(sub(p, a), normal)));
        for k in 0..3 {
            let v = l.node_coord(n, k);
            if m.free[v] != crate::variables::FIXED {
                s.q[v] = image[k];
            }
        }
    }
    Some(s)
}

/// The two points farthest apart, if two are apart at all.
fn farthest_pair(points: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let mut best = (0.0, None);
    for (i, p) in points.iter().enumerate() {
        for q in &points[i + 1..] {
            let d = dist(p, q);
            if d > best.0 {
                best = (d, Some((*p, *q)));
            }
        }
    }
    best.1
}

/// Moves the free unknowns along `mode` so that the largest node motion is `amount` (m).
fn push(net: &mut Network, mode: &[f64], amount: f64) {
    let m = &mut net.model;
    let before: Vec<[f64; 3]> = (0..m.layout.n_nodes()).map(|n| m.position(n)).collect();
    m.displace(mode, 1.0);
    let largest = before
        .iter()
        .enumerate()
        .map(|(n, p)| norm(sub(m.position(n), *p)))
        .fold(0.0, f64::max);
    m.displace(mode, -1.0);
    if largest > 0.0 {
        m.displace(mode, amount / largest);
    }
    m.commit();
}

/// The current state and `other` are one equilibrium: no node more than 1e-6 of the
/// structure's size apart.
fn same(net: &Network, other: &State, size: f64) -> bool {
    let m = &net.model;
    (0..m.layout.n_nodes()).all(|n| {
        let p = m.layout.position(&other.q, n);
        dist(&p, &m.position(n)) <= 1e-6 * size
    })
}

fn diagonal(net: &Network) -> f64 {
    let m = &net.model;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for n in 0..m.layout.n_nodes() {
        let p = m.position(n);
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    norm(sub(hi, lo)).max(1e-300)
}
