//! The flat footprint of the hemispherical Chebyshev-net gridshell as a rodnet [`Scene`].
//!
//! Family-u rod `j` is the net curve `v = c_j`; in the plane it lies along x at `y = c_j`, from
//! `x = −L_j` to `x = L_j`. Family-v rod `i` is the curve `u = c_i`, along y at `x = c_i`. The
//! plane coordinates of a footprint point are its net parameters `(u, v)`, so crossing `(i, j)`
//! sits at `(c_i, c_j, 0)`, and every rod is as long as its net curve: the footprint is the net
//! unrolled without stretching any rod. The crossings strictly above the equator are input
//! vertices of both rods and are joined; each rod end is pinned and moved to its equator point.

use std::collections::BTreeMap;

use crate::gridshell::chebyshev::{mirror_uv, HemisphereNet};
pub use crate::scene::types::JointChoice;
use crate::scene::types::{
    Joint, Material, Rod, Scene, Section, Solver, Support, SupportKind, Target,
};
use crate::scene::validate::MAX_NODES;

/// Everything that defines one hemispherical gridshell problem.
#[derive(Debug, Clone, PartialEq)]
pub struct HemisphereSpec {
    /// Sphere radius R, m.
    pub radius: f64,
    /// Rods per family, n.
    pub rods: usize,
    /// Edges per crossing spacing: segments between crossings get `subdivide` equal edges, end
    /// segments as many as keep their edges no longer than that (at least one).
    pub subdivide: usize,
    pub joint: JointChoice,
    /// Rod cross-section, m. Non-circular sections put their first axis (`Ellipse::a`,
    /// `Rectangle::width`) in the footprint plane, i.e. tangent to the shell.
    pub section: Section,
    /// Pa.
    pub young_modulus: f64,
    pub poisson_ratio: f64,
    /// Steps of the boundary motion (see `formfind`).
    pub load_steps: usize,
    /// How the ends travel from the starting cap to the equator.
    pub path: crate::gridshell::formfind::FormPath,
    /// None: automatic (see `scene::types::Solver`).
    pub tolerance: Option<f64>,
    pub max_iterations: usize,
}

/// Radius of the default circular section relative to R (Baek et al. used slender elastomer
/// rods; at r/R = 0.005 stretching is 4/(r/a)² ≈ 1e4–1e5 times stiffer than bending over a
/// crossing spacing a, so the rods are practically inextensible, as Chebyshev's theorem
/// assumes).
pub const DEFAULT_SECTION_RATIO: f64 = 0.005;

/// Nodes of the footprint of `rods` rods with `subdivide` edges per spacing, about: it has
/// 1.3–1.5 n² K nodes (every rod crosses up to n others), so that requests are checked before
/// the footprint is generated and nothing runs away in the generator (saturating).
pub fn estimated_nodes(rods: usize, subdivide: usize) -> usize {
    (3 * rods.saturating_mul(rods) / 2).saturating_mul(subdivide)
}

impl HemisphereSpec {
    /// The default problem for radius `radius`, n rods per family and `subdivide` edges per
    /// crossing spacing: Ball joints, circular rods with r/R = 0.005, E = 1 GPa, ν = 0.3. For a problem
    /// driven only by prescribed motions the equilibrium shape does not depend on E.
    pub fn new(radius: f64, rods: usize, subdivide: usize) -> HemisphereSpec {
        HemisphereSpec {
            radius,
            rods,
            subdivide,
            joint: JointChoice::Ball,
            section: Section::Circle {
                radius: DEFAULT_SECTION_RATIO * radius,
            },
            young_modulus: 1e9,
            poisson_ratio: 0.3,
            load_steps: 1,
            path: Default::default(),
            tolerance: None,
            // The solver's own budget: a scene written with --scene-out must not carry a
            // tighter cap than `rodnet solve` would use by default.
            max_iterations: Solver::default().max_iterations,
        }
    }
}

/// Which net crossing a joint of the scene is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CrossingJoint {
    /// Family-v rod (`u = c_i`).
    pub i: usize,
    /// Family-u rod (`v = c_j`).
    pub j: usize,
}

/// The generated problem: the net, the scene, and the crossing behind each joint.
#[derive(Debug, Clone)]
pub struct Footprint {
    pub net: HemisphereNet,
    pub scene: Scene,
    /// `crossings[k]` is the crossing that `scene.joints[k]` joins.
    pub crossings: Vec<CrossingJoint>,
}

pub const MATERIAL: &str = "rod";

pub fn u_rod_name(j: usize) -> String {
    format!("u{j}")
}

pub fn v_rod_name(i: usize) -> String {
    format!("v{i}")
}

/// Builds the footprint scene of `spec`.
///
/// # Panics
/// If `spec.rods == 0` or the radius is not positive and finite (see [`HemisphereNet::new`]).
pub fn footprint(spec: &HemisphereSpec) -> Footprint {
    let net = HemisphereNet::new(spec.radius, spec.rods);
    let n = net.n;
    let c = &net.offsets;
    let inside = |i: usize, j: usize| net.crossing_inside(i, j);

    // Input vertex of each crossing along its two rods.
    let mut u_vertex = vec![vec![None; n]; n];
    let mut v_vertex = vec![vec![None; n]; n];
    let mut rods = Vec::with_capacity(2 * n);
    let mut supports = Vec::with_capacity(4 * n);
    for j in 0..n {
        let l = net.half_lengths[j];
        let crossing: Vec<usize> = (0..n).filter(|&i| inside(i, j)).collect();
        let mut keys = vec![[-l, c[j], 0.0]];
        for &i in &crossing {
            // A crossing above the equator lies inside the rod's span; anything else would
            // make the rod fold back on itself.
            assert!(c[i].abs() < l, "crossing ({i}, {j}) outside rod u{j}");
            keys.push([c[i], c[j], 0.0]);
        }
        keys.push([l, c[j], 0.0]);
        let (points, at) = subdivided(&keys, spec.subdivide, net.spacing);
        for (k, &i) in crossing.iter().enumerate() {
            u_vertex[i][j] = Some(at[k + 1]);
        }
        let last = points.len() - 1;
        rods.push(rod(u_rod_name(j), points, [0.0, 1.0, 0.0]));
        supports.push(pin(u_rod_name(j), 0, net.end_point(j, false)));
        supports.push(pin(u_rod_name(j), last, net.end_point(j, true)));
    }
    for i in 0..n {
        let l = net.half_lengths[i];
        let crossing: Vec<usize> = (0..n).filter(|&j| inside(i, j)).collect();
        let mut keys = vec![[c[i], -l, 0.0]];
        for &j in &crossing {
            assert!(c[j].abs() < l, "crossing ({i}, {j}) outside rod v{i}");
            keys.push([c[i], c[j], 0.0]);
        }
        keys.push([c[i], l, 0.0]);
        let (points, at) = subdivided(&keys, spec.subdivide, net.spacing);
        for (k, &j) in crossing.iter().enumerate() {
            v_vertex[i][j] = Some(at[k + 1]);
        }
        let last = points.len() - 1;
        rods.push(rod(v_rod_name(i), points, [1.0, 0.0, 0.0]));
        // Family-v rod i is the u↔v mirror of family-u rod i.
        supports.push(pin(v_rod_name(i), 0, mirror_uv(net.end_point(i, false))));
        supports.push(pin(v_rod_name(i), last, mirror_uv(net.end_point(i, true))));
    }

    let mut joints = Vec::new();
    let mut crossings = Vec::new();
    for i in 0..n {
        for j in 0..n {
            if let (Some(a), Some(b)) = (u_vertex[i][j], v_vertex[i][j]) {
                joints.push(Joint {
                    name: format!("c{i}_{j}"),
                    at: vec![(u_rod_name(j), a), (v_rod_name(i), b)],
                    kind: spec
                        .joint
                        .kind(spec.young_modulus, spec.section.outer_radius()),
                    normal: None,
                });
                crossings.push(CrossingJoint { i, j });
            }
        }
    }

    let scene = Scene {
        materials: rod_material(spec.young_modulus, spec.poisson_ratio, spec.section),
        rods,
        joints,
        supports,
        loads: Vec::new(),
        obstacles: Vec::new(),
        bounds: Vec::new(),
        target: Some(Target::Sphere {
            center: [0.0; 3],
            radius: spec.radius,
        }),
        reference: None,
        stages: Vec::new(),
        solver: Solver {
            tolerance: spec.tolerance,
            max_iterations: spec.max_iterations,
            load_steps: spec.load_steps,
            time_limit: None,
            buckle_toward: None,
            continuation: Default::default(),
        },
    };
    Footprint {
        net,
        scene,
        crossings,
    }
}

/// The one weightless material every gridshell rod is made of, named [`MATERIAL`].
pub(crate) fn rod_material(
    young_modulus: f64,
    poisson_ratio: f64,
    section: Section,
) -> BTreeMap<String, Material> {
    BTreeMap::from([(
        MATERIAL.to_string(),
        Material {
            young_modulus,
            poisson_ratio: Some(poisson_ratio),
            shear_modulus: None,
            density: 0.0,
            section,
            yield_strength: None,
        },
    )])
}

/// The polyline through `keys` with every segment split into equal edges no longer than
/// `spacing / per_spacing`, and the index of each key in it.
///
/// Segments between crossings are exactly one spacing long and get `per_spacing` edges. End
/// segments can be much shorter (at n = 12 the last crossing before the equator is 0.094
/// spacings from the rod end): splitting them into as many edges as a full spacing would make
/// edges a tenth as long, with ten times the round-off floor of the residual (stretching
/// stiffness over edge length), enough to stall Newton at fine subdivisions (docs/gridshell.md).
pub(crate) fn subdivided(
    keys: &[[f64; 3]],
    per_spacing: usize,
    spacing: f64,
) -> (Vec<[f64; 3]>, Vec<usize>) {
    let mut points = Vec::new();
    let mut at = Vec::with_capacity(keys.len());
    for w in keys.windows(2) {
        let (a, b) = (w[0], w[1]);
        let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        // The relative slack keeps a spacing computed with round-off at `per_spacing` edges.
        let edges = ((per_spacing as f64 * length / spacing) * (1.0 - 1e-9))
            .ceil()
            .max(1.0);
        // The options are checked so that this stays small. Were it beyond the node limit
        // (or not finite: the points are then not finite either), the scene's validation
        // refuses the rod rather than this loop running away.
        let edges = if edges.is_finite() {
            edges.min((MAX_NODES + 1) as f64) as usize
        } else {
            1
        };
        at.push(points.len());
        points.push(a);
        for k in 1..edges {
            let f = k as f64 / edges as f64;
            points.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), 0.0]);
        }
    }
    at.push(points.len());
    points.push(keys[keys.len() - 1]);
    (points, at)
}

fn rod(name: String, points: Vec<[f64; 3]>, normal: [f64; 3]) -> Rod {
    Rod {
        name,
        material: MATERIAL.to_string(),
        points,
        // Subdivision is explicit in the points: segments have different lengths.
        subdivide: 1,
        closed: false,
        normal: Some(normal),
        end_correction: true,
    }
}

fn pin(rod: String, vertex: usize, to: [f64; 3]) -> Support {
    Support {
        rod,
        vertex,
        kind: SupportKind::Pin,
        move_to: Some(to),
        rotate_by: None,
    }
}

/// The scene as RON text that `rodnet solve` reads back (see docs/scene-format.md).
pub fn to_ron(scene: &Scene) -> String {
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(3)
        .struct_names(true)
        .separate_tuple_members(false)
        .enumerate_arrays(false);
    ron::ser::to_string_pretty(scene, config).expect("a scene serializes to RON")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    }

    fn polyline_length(p: &[[f64; 3]]) -> f64 {
        p.windows(2).map(|w| dist(w[0], w[1])).sum()
    }

    #[test]
    fn footprint_rods_have_their_net_lengths_and_crossings_are_one_spacing_apart() {
        for n in [1, 2, 7, 8, 12] {
            let fp = footprint(&HemisphereSpec::new(1.3, n, 2));
            let net = &fp.net;
            assert_eq!(fp.scene.rods.len(), 2 * n);
            assert_eq!(fp.scene.supports.len(), 4 * n);
            for (k, rod) in fp.scene.rods.iter().enumerate() {
                let l = net.half_lengths[k % n];
                assert!((polyline_length(&rod.points) - 2.0 * l).abs() < 1e-12);
                for w in rod.points.windows(2) {
                    assert!(dist(w[0], w[1]) <= net.spacing / 2.0 * (1.0 + 1e-12));
                }
                // Neighbouring crossings on the rod, in order along it, are one spacing apart.
                let mut on_rod: Vec<usize> = fp
                    .scene
                    .joints
                    .iter()
                    .flat_map(|j| j.at.iter())
                    .filter(|(r, _)| *r == rod.name)
                    .map(|(_, v)| *v)
                    .collect();
                on_rod.sort_unstable();
                for w in on_rod.windows(2) {
                    assert_eq!(w[1] - w[0], 2, "subdivide 2 between crossings");
                    let d = dist(rod.points[w[0]], rod.points[w[1]]);
                    assert!((d - net.spacing).abs() < 1e-12);
                }
            }
            let inside = (0..n)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .filter(|&(i, j)| net.crossing_inside(i, j))
                .count();
            assert_eq!(fp.scene.joints.len(), inside);
            assert_eq!(fp.crossings.len(), inside);
            crate::scene::validate::validate(&fp.scene).unwrap();
        }
    }

    #[test]
    fn short_end_segments_keep_edges_near_the_requested_length() {
        // n = 12 has end segments 0.094 spacings long; subdivide 16 asks for edges of a/16.
        let fp = footprint(&HemisphereSpec::new(1.0, 12, 16));
        let h = fp.net.spacing / 16.0;
        let edges: Vec<f64> = fp
            .scene
            .rods
            .iter()
            .flat_map(|r| r.points.windows(2).map(|w| dist(w[0], w[1])))
            .collect();
        let longest = edges.iter().cloned().fold(0.0, f64::max);
        let shortest = edges.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!(longest <= h * (1.0 + 1e-12), "{longest} > {h}");
        assert!(shortest >= 0.5 * h, "{shortest} < {h}/2");
    }

    #[test]
    fn joints_join_coinciding_vertices_at_the_crossing_parameters() {
        let fp = footprint(&HemisphereSpec::new(1.0, 12, 1));
        let rod = |name: &str| fp.scene.rods.iter().find(|r| r.name == name).unwrap();
        for (joint, cj) in fp.scene.joints.iter().zip(&fp.crossings) {
            let want = [fp.net.offsets[cj.i], fp.net.offsets[cj.j], 0.0];
            for (r, v) in &joint.at {
                assert_eq!(rod(r).points[*v], want, "{}", joint.name);
            }
        }
        // n = 12 has 112 crossings above the equator (see the net's documentation).
        assert_eq!(fp.scene.joints.len(), 112);
    }

    #[test]
    fn every_rod_end_moves_to_the_equator_at_its_own_net_end() {
        let fp = footprint(&HemisphereSpec::new(2.0, 9, 1));
        for s in &fp.scene.supports {
            let to = s.move_to.unwrap();
            assert_eq!(to[2], 0.0);
            assert!((dist(to, [0.0; 3]) - 2.0).abs() < 1e-13);
            let rod = fp.scene.rods.iter().find(|r| r.name == s.rod).unwrap();
            let from = rod.points[s.vertex];
            // The end keeps its net parameters: (±L, c) for family u, (c, ±L) for family v.
            let expect = fp.net.point(from[0], from[1]);
            assert!(dist(to, expect) < 1e-12, "{} {:?}", s.rod, to);
        }
    }

    #[test]
    fn ron_round_trip_preserves_the_scene() {
        let mut spec = HemisphereSpec::new(1.0, 4, 3);
        spec.joint = JointChoice::Hinge;
        let fp = footprint(&spec);
        let text = to_ron(&fp.scene);
        let back = crate::scene::parse("footprint.ron", &text).unwrap();
        assert_eq!(back, fp.scene);
    }
}
