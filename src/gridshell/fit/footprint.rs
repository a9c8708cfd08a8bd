//! The flat footprint of a fitted net as a rodnet [`Scene`]: the net unrolled into a plane.
//!
//! Family-U rod with offset v lies along e1 at height v·e2, from its start parameter to its end
//! parameter; family-V rod with offset u along e2 at u·e1. A footprint point's plane
//! coordinates are its net parameters, so every crossing is at its (u, v) and every rod is as
//! long as its net curve. The plane is normal to the surface at the origin and passes at the
//! mean height of the rod ends, so the ends move about as far up as down on their way to the
//! boundary; `buckle_toward` is the side of the surface the origin stands on.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::compass::Seed;
use super::net::{self, Family, Layout, Net};
use crate::gridshell::footprint::{rod_material, subdivided, JointChoice, MATERIAL};
use crate::math::vec::{add, cross, dot, norm, normalize, scalef, sub};
use crate::scene::types::{
    Joint, LoadedSurface, Rod, Scene, Section, Solver, Support, SupportKind, Target,
};
use crate::surface::Surface;

/// Everything that defines a fitted gridshell.
#[derive(Debug, Clone, PartialEq)]
pub struct FitSpec {
    /// Net spacing a, m.
    pub spacing: f64,
    /// Default: the surface's highest vertex.
    pub origin: Option<[f64; 3]>,
    /// The generators' directions at the origin (projected onto the tangent plane); default x
    /// and y.
    pub directions: Option<([f64; 3], [f64; 3])>,
    pub layout: Layout,
    /// Locking angle, degrees.
    pub min_angle_deg: f64,
    pub subdivide: usize,
    pub joint: JointChoice,
    pub section: Section,
    pub young_modulus: f64,
    pub poisson_ratio: f64,
    pub tolerance: Option<f64>,
    pub max_iterations: usize,
}

impl FitSpec {
    /// The checks the options need beyond their types: the option's name (as on the command
    /// line, without dashes) and what is wrong.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if !positive(self.spacing) {
            return Err(("spacing", format!("must be positive, got {}", self.spacing)));
        }
        if !(self.min_angle_deg.is_finite()
            && self.min_angle_deg > 0.0
            && self.min_angle_deg < 90.0)
        {
            return Err((
                "min-angle",
                format!("must lie in (0, 90) degrees, got {}", self.min_angle_deg),
            ));
        }
        if self.subdivide == 0 || self.subdivide > 64 {
            return Err((
                "subdivide",
                format!("must be in 1..=64, got {}", self.subdivide),
            ));
        }
        let max = crate::scene::validate::MAX_MAGNITUDE;
        if !(positive(self.young_modulus) && self.young_modulus <= max) {
            return Err((
                "young-modulus",
                format!("must be positive and finite, got {}", self.young_modulus),
            ));
        }
        if !(self.poisson_ratio.is_finite()
            && self.poisson_ratio > -1.0
            && self.poisson_ratio <= 0.5)
        {
            return Err((
                "poisson-ratio",
                format!("must lie in (-1, 0.5], got {}", self.poisson_ratio),
            ));
        }
        if let Some(t) = self.tolerance.filter(|t| !positive(*t)) {
            return Err(("tolerance", format!("must be positive, got {t}")));
        }
        let finite = |p: &[f64; 3]| p.iter().all(|x| x.is_finite());
        if self.origin.is_some_and(|o| !finite(&o)) {
            return Err(("origin", "must be finite".into()));
        }
        if self
            .directions
            .is_some_and(|(a, b)| !finite(&a) || !finite(&b))
        {
            return Err(("directions", "must be finite".into()));
        }
        let r = self.section.outer_radius();
        if !positive(r) || r >= 0.5 * self.spacing {
            return Err((
                "section",
                format!(
                    "rods {} m thick do not fit between crossings {} m apart",
                    2.0 * r,
                    self.spacing
                ),
            ));
        }
        Ok(())
    }
}

/// Default locking angle, degrees: beyond about 15° of shear from closed, a timber or steel
/// gridshell's rods touch side by side at realistic spacings (docs/gridshell.md).
pub const DEFAULT_MIN_ANGLE_DEG: f64 = 15.0;

/// The plane the footprint lies in.
#[derive(Debug, Clone, Copy)]
pub struct Plane {
    pub base: [f64; 3],
    pub e1: [f64; 3],
    pub e2: [f64; 3],
    /// The side the gridshell rises to (`buckle_toward`).
    pub side: [f64; 3],
}

impl Plane {
    pub fn at(&self, u: f64, v: f64) -> [f64; 3] {
        add(self.base, add(scalef(self.e1, u), scalef(self.e2, v)))
    }
}

pub struct FitFootprint {
    pub net: Net,
    pub scene: Scene,
    pub plane: Plane,
    /// `crossings[k]`: the net crossing that `scene.joints[k]` joins.
    pub crossings: Vec<usize>,
    /// `rods[k]`: the net rod behind `scene.rods[k]`.
    pub rods: Vec<usize>,
    /// Net rods left out because no other rod crosses them.
    pub dropped_rods: usize,
}

/// The seed of the net: the origin on the surface and the generators' tangents.
pub fn seed(s: &Surface, spec: &FitSpec) -> Result<Seed, String> {
    let c = s.closest(spec.origin.unwrap_or_else(|| s.highest_point()));
    if c.beyond_boundary {
        return Err("--origin is off the surface (its closest point is on the boundary)".into());
    }
    let n = c.normal;
    let (a, b) = spec
        .directions
        .unwrap_or(([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
    let tangent = |d: [f64; 3], which: &str| {
        let t = sub(d, scalef(n, dot(d, n)));
        if norm(t) <= 1e-6 * norm(d) {
            Err(format!(
                "--directions: the {which} direction {d:?} is normal to the surface at the \
                 origin, so it has no tangent part"
            ))
        } else {
            Ok(normalize(t))
        }
    };
    let (d1, d2) = (tangent(a, "first")?, tangent(b, "second")?);
    let sin = norm(cross(d1, d2));
    let min = spec.min_angle_deg.to_radians();
    if sin <= min.sin() || dot(d1, d2).abs() >= min.cos() {
        return Err(format!(
            "--directions: the two generators meet at {:.2}° on the surface, within the locking \
             angle of {}°",
            sin.atan2(dot(d1, d2)).to_degrees(),
            spec.min_angle_deg
        ));
    }
    Ok(Seed {
        origin: c.point,
        d1,
        d2,
        min_angle: min,
    })
}

/// Builds the net and its footprint scene; `mesh_path` is written into the scene's target.
/// `memory`: the limit (bytes, `u64::MAX`: none) the construction grid is sized within.
pub fn footprint(
    surface: &Arc<Surface>,
    mesh_path: &str,
    spec: &FitSpec,
    memory: u64,
) -> Result<FitFootprint, String> {
    let max_grid = super::size::check(surface, spec.spacing, spec.subdivide, memory)?;
    let seed = seed(surface, spec)?;
    let net = net::build(
        surface,
        &seed,
        spec.spacing,
        spec.layout,
        net::DEFAULT_STEPS,
        max_grid,
    )
    .map_err(|grid| super::size::grid_refusal(spec.spacing, grid, max_grid))?;
    let finite = |p: &[f64; 3]| p.iter().all(|x| x.is_finite());
    if !(net.crossings.iter().all(|c| finite(&c.point))
        && net
            .rods
            .iter()
            .all(|r| r.ends.iter().all(|e| finite(&e.point))))
    {
        return Err("the net construction produced non-finite points; no net written".into());
    }
    let plane = plane(surface, &net);
    let mut names: BTreeMap<usize, String> = BTreeMap::new();
    let (mut count_u, mut count_v) = (0, 0);
    let mut rods = Vec::new();
    let mut rod_of = Vec::new();
    let mut vertex_at: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let mut supports = Vec::new();
    let mut dropped = 0;
    for (ri, r) in net.rods.iter().enumerate() {
        if r.crossings.is_empty() {
            dropped += 1;
            continue;
        }
        let name = match r.family {
            Family::U => {
                count_u += 1;
                format!("u{}", count_u - 1)
            }
            Family::V => {
                count_v += 1;
                format!("v{}", count_v - 1)
            }
        };
        // Footprint coordinates (u, v) of a parameter t along this rod.
        let uv = |t: f64| match r.family {
            Family::U => [t, r.offset, 0.0],
            Family::V => [r.offset, t, 0.0],
        };
        let along = |c: usize| net.crossings[c].uv[if r.family == Family::U { 0 } else { 1 }];
        let mut keys = vec![uv(r.ends[0].param)];
        keys.extend(r.crossings.iter().map(|&c| uv(along(c))));
        keys.push(uv(r.ends[1].param));
        let (points, at) = subdivided(&keys, spec.subdivide, spec.spacing);
        for (k, &c) in r.crossings.iter().enumerate() {
            vertex_at.insert((ri, c), at[k + 1]);
        }
        let last = points.len() - 1;
        let in_plane = if r.family == Family::U {
            plane.e2
        } else {
            plane.e1
        };
        for (vertex, end) in [(0, &r.ends[0]), (last, &r.ends[1])] {
            supports.push(Support {
                rod: name.clone(),
                vertex,
                kind: SupportKind::Pin,
                move_to: Some(end.point),
                rotate_by: None,
            });
        }
        rods.push(Rod {
            name: name.clone(),
            material: MATERIAL.to_string(),
            points: points.iter().map(|p| plane.at(p[0], p[1])).collect(),
            subdivide: 1,
            closed: false,
            normal: Some(in_plane),
            end_correction: true,
        });
        names.insert(ri, name);
        rod_of.push(ri);
    }
    let mut joints = Vec::new();
    let mut crossings = Vec::new();
    for (ci, c) in net.crossings.iter().enumerate() {
        let (Some(nu), Some(nv)) = (names.get(&c.rods[0]), names.get(&c.rods[1])) else {
            continue;
        };
        joints.push(Joint {
            name: format!("c{}_{}", &nv[1..], &nu[1..]),
            at: vec![
                (nu.clone(), vertex_at[&(c.rods[0], ci)]),
                (nv.clone(), vertex_at[&(c.rods[1], ci)]),
            ],
            kind: spec
                .joint
                .kind(spec.young_modulus, spec.section.outer_radius()),
            normal: None,
        });
        crossings.push(ci);
    }
    if joints.is_empty() {
        return Err(format!(
            "no usable net: no two rods cross on the surface at spacing {} m (the net has {} \
             rods); reduce --spacing or move --origin",
            spec.spacing,
            net.rods.len()
        ));
    }
    let scene = Scene {
        materials: rod_material(spec.young_modulus, spec.poisson_ratio, spec.section),
        rods,
        joints,
        supports,
        loads: Vec::new(),
        obstacles: Vec::new(),
        bounds: Vec::new(),
        target: Some(Target::Mesh {
            path: mesh_path.to_string(),
            surface: LoadedSurface(Some(surface.clone())),
        }),
        reference: None,
        stages: Vec::new(),
        solver: Solver {
            tolerance: spec.tolerance,
            max_iterations: spec.max_iterations,
            load_steps: 1,
            time_limit: None,
            buckle_toward: Some(plane.side),
            continuation: Default::default(),
        },
    };
    Ok(FitFootprint {
        net,
        scene,
        plane,
        crossings,
        rods: rod_of,
        dropped_rods: dropped,
    })
}

/// The footprint plane: normal to the surface at the origin, through the rod ends' mean
/// height; e1 along the first generator, e2 on the second's side.
fn plane(s: &Surface, net: &Net) -> Plane {
    let o = net.seed.origin;
    let n = s.closest(o).normal;
    let ends: Vec<[f64; 3]> = net
        .rods
        .iter()
        .flat_map(|r| r.ends.iter().map(|e| e.point))
        .collect();
    let mean = scalef(
        ends.iter().fold([0.0; 3], |a, p| add(a, *p)),
        1.0 / ends.len().max(1) as f64,
    );
    let height = dot(sub(o, mean), n);
    let side = if height < 0.0 { scalef(n, -1.0) } else { n };
    let e1 = net.seed.d1;
    let e2 = normalize(cross(n, e1));
    let e2 = if dot(e2, net.seed.d2) < 0.0 {
        scalef(e2, -1.0)
    } else {
        e2
    };
    Plane {
        base: sub(o, scalef(n, height)),
        e1,
        e2,
        side,
    }
}
