//! Target surfaces given as triangle meshes: reading and checking an OBJ mesh (`obj`, `check`),
//! closest points, signed distances and normals (this file, over parry3d's BVH), and the two
//! steps that build curves on the surface: a straightest (geodesic) step and the compass step
//! of a Chebyshev net (`steps`).
//!
//! The mesh is taken as the surface itself: piecewise flat. Normals are the angle-weighted
//! vertex normals interpolated over each triangle, so that the sign of a distance and the
//! planes of the steps turn smoothly from face to face.
pub mod check;
pub mod obj;
pub mod shapes;
pub mod steps;

use std::path::Path;

use parry3d_f64::math::Vector;
use parry3d_f64::query::PointQueryWithLocation;
use parry3d_f64::shape::{TriMesh, TrianglePointLocation};

use crate::math::vec::{add, cross, dot, norm, normalize, scalef, sub};

/// A checked target surface with its search structure.
pub struct Surface {
    /// The file it came from, for messages.
    pub file: String,
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    boundary: Vec<[bool; 3]>,
    boundary_vertex: Vec<bool>,
    vertex_normals: Vec<[f64; 3]>,
    /// Faces whose winding was reversed to agree with the first face's.
    pub flipped: usize,
    /// Bounding-box diagonal of the triangles, m.
    pub size: f64,
    mesh: TriMesh,
}

impl std::fmt::Debug for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Surface({}, {} vertices, {} triangles)",
            self.file,
            self.vertices.len(),
            self.triangles.len()
        )
    }
}

/// A problem with a mesh file: where (1-based line, when known) and what.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceError {
    pub file: String,
    pub line: Option<usize>,
    pub message: String,
}

impl std::fmt::Display for SurfaceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.line {
            Some(l) => write!(f, "{}:{l}: {}", self.file, self.message),
            None => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

/// The point of the surface closest to a query point.
#[derive(Debug, Clone, Copy)]
pub struct Closest {
    pub point: [f64; 3],
    pub triangle: usize,
    pub bary: [f64; 3],
    /// |query − point|, m.
    pub distance: f64,
    /// Unit normal there (interpolated vertex normals).
    pub normal: [f64; 3],
    /// The closest point is on the boundary and the query lies beyond it (off the surface's
    /// edge rather than above or below the surface).
    pub beyond_boundary: bool,
}

/// Barycentric coordinates below this count as zero (the point is on an edge or vertex).
const ON_EDGE: f64 = 1e-12;

impl Surface {
    /// Reads and checks an OBJ mesh file (`v` and `f` records).
    pub fn load(path: &Path, max_bytes: u64) -> Result<Surface, SurfaceError> {
        let file = path.display().to_string();
        let fail = |line, message| SurfaceError {
            file: file.clone(),
            line,
            message,
        };
        let meta = std::fs::metadata(path)
            .map_err(|e| fail(None, format!("cannot read mesh file: {e}")))?;
        if !meta.is_file() {
            return Err(fail(None, "mesh file is not a regular file".into()));
        }
        if meta.len() > max_bytes {
            return Err(fail(
                None,
                format!(
                    "mesh file is {} bytes, above the limit of {max_bytes} bytes",
                    meta.len()
                ),
            ));
        }
        let bytes =
            std::fs::read(path).map_err(|e| fail(None, format!("cannot read mesh file: {e}")))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let line = 1 + e.as_bytes()[..e.utf8_error().valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            fail(Some(line), "mesh file is not UTF-8 text".into())
        })?;
        Surface::from_obj(&file, &text)
    }

    /// Parses and checks OBJ text; `file` names it in errors.
    pub fn from_obj(file: &str, text: &str) -> Result<Surface, SurfaceError> {
        let located = |e: obj::TextError| SurfaceError {
            file: file.to_string(),
            line: Some(e.line),
            message: e.message,
        };
        let raw = obj::parse(text).map_err(located)?;
        let c = check::check(&raw).map_err(located)?;
        Ok(Surface::from_checked(file, c))
    }

    fn from_checked(file: &str, c: check::Checked) -> Surface {
        let points: Vec<Vector> = c
            .vertices
            .iter()
            .map(|p| Vector::new(p[0], p[1], p[2]))
            .collect();
        let mesh = TriMesh::new(points, c.triangles.clone())
            .expect("a checked mesh has triangles with valid indices");
        // Over the triangles' corners only: a stray vertex no face uses is not part of the
        // surface, and the size scales its tolerances and the net's step limits.
        let (lo, hi) = c
            .triangles
            .iter()
            .flatten()
            .map(|&k| &c.vertices[k as usize])
            .fold(
                ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |(lo, hi), p| {
                    (
                        [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                        [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
                    )
                },
            );
        Surface {
            file: file.to_string(),
            vertex_normals: vertex_normals(&c.vertices, &c.triangles),
            vertices: c.vertices,
            triangles: c.triangles,
            boundary: c.boundary,
            boundary_vertex: c.boundary_vertex,
            flipped: c.flipped,
            size: norm(sub(hi, lo)),
            mesh,
        }
    }

    /// Total area of the triangles, m².
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|k| self.vertices[k as usize]);
                0.5 * norm(cross(sub(b, a), sub(c, a)))
            })
            .sum()
    }

    pub fn closest(&self, p: [f64; 3]) -> Closest {
        let (proj, (tri, location)) = self
            .mesh
            .project_local_point_and_get_location(Vector::new(p[0], p[1], p[2]), false);
        let t = tri as usize;
        let bary = match location {
            TrianglePointLocation::OnSolid => [1.0 / 3.0; 3],
            l => l.barycentric_coordinates().unwrap_or([1.0 / 3.0; 3]),
        };
        let point = [proj.point.x, proj.point.y, proj.point.z];
        let normal = self.normal_at(t, bary);
        let off = sub(p, point);
        let distance = norm(off);
        // Beyond the boundary: the closest point is on a boundary edge or vertex and the query
        // leaves it sideways, not along the normal.
        let on_boundary = self.on_boundary(t, bary);
        let sideways = norm(sub(off, scalef(normal, dot(off, normal))));
        let beyond_boundary = on_boundary && sideways > 1e-9 * (self.size + distance);
        Closest {
            point,
            triangle: t,
            bary,
            distance,
            normal,
            beyond_boundary,
        }
    }

    /// Distance along the normal: positive on the side the normals point to.
    pub fn signed_distance(&self, p: [f64; 3]) -> f64 {
        let c = self.closest(p);
        dot(sub(p, c.point), c.normal)
    }

    fn normal_at(&self, t: usize, b: [f64; 3]) -> [f64; 3] {
        let tri = self.triangles[t];
        let mut n = [0.0; 3];
        for k in 0..3 {
            n = add(n, scalef(self.vertex_normals[tri[k] as usize], b[k]));
        }
        normalize(n)
    }

    fn on_boundary(&self, t: usize, b: [f64; 3]) -> bool {
        let tri = self.triangles[t];
        (0..3).any(|e| {
            // Edge e joins corners e and e + 1; it holds the point when the opposite
            // corner's weight vanishes.
            (self.boundary[t][e] && b[(e + 2) % 3] <= ON_EDGE)
                || (self.boundary_vertex[tri[e] as usize] && b[e] >= 1.0 - ON_EDGE)
        })
    }

    /// The vertex with the largest z, m.
    pub fn highest_point(&self) -> [f64; 3] {
        *self
            .vertices
            .iter()
            .max_by(|a, b| a[2].total_cmp(&b[2]))
            .expect("a checked mesh has vertices")
    }

    /// Mean of the boundary vertices, m.
    pub fn boundary_centroid(&self) -> [f64; 3] {
        let (sum, count) = self
            .vertices
            .iter()
            .zip(&self.boundary_vertex)
            .filter(|(_, &b)| b)
            .fold(([0.0; 3], 0usize), |(s, c), (p, _)| (add(s, *p), c + 1));
        scalef(sum, 1.0 / count.max(1) as f64)
    }

    /// Mean edge length, m: the mesh's resolution.
    pub fn mean_edge(&self) -> f64 {
        let mut sum = 0.0;
        for t in &self.triangles {
            for e in 0..3 {
                let (a, b) = (t[e] as usize, t[(e + 1) % 3] as usize);
                sum += norm(sub(self.vertices[a], self.vertices[b]));
            }
        }
        sum / (3 * self.triangles.len()) as f64
    }

    /// Discrete Gauss–Bonnet: the angle defect of each interior vertex (2π minus its corner
    /// angles), the integral of the Gaussian curvature concentrated there; 0 on the boundary.
    pub fn angle_defects(&self) -> Vec<f64> {
        let mut sum = vec![0.0; self.vertices.len()];
        for t in &self.triangles {
            for k in 0..3 {
                let p = self.vertices[t[k] as usize];
                let a = sub(self.vertices[t[(k + 1) % 3] as usize], p);
                let b = sub(self.vertices[t[(k + 2) % 3] as usize], p);
                sum[t[k] as usize] += norm(cross(a, b)).atan2(dot(a, b));
            }
        }
        sum.iter()
            .zip(&self.boundary_vertex)
            .map(|(s, &b)| {
                if b {
                    0.0
                } else {
                    2.0 * std::f64::consts::PI - s
                }
            })
            .collect()
    }
}

/// Angle-weighted vertex normals (the pseudo-normals of Thürrner and Wüthrich).
fn vertex_normals(v: &[[f64; 3]], tris: &[[u32; 3]]) -> Vec<[f64; 3]> {
    let mut n = vec![[0.0; 3]; v.len()];
    for t in tris {
        let p = t.map(|i| v[i as usize]);
        let face = normalize(cross(sub(p[1], p[0]), sub(p[2], p[0])));
        for k in 0..3 {
            let a = sub(p[(k + 1) % 3], p[k]);
            let b = sub(p[(k + 2) % 3], p[k]);
            let angle = norm(cross(a, b)).atan2(dot(a, b));
            let i = t[k] as usize;
            n[i] = add(n[i], scalef(face, angle));
        }
    }
    n.into_iter()
        .map(|x| if norm(x) > 0.0 { normalize(x) } else { x })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Surface {
        Surface::from_obj(
            "sq.obj",
            "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n",
        )
        .unwrap()
    }

    #[test]
    fn closest_points_signs_and_the_boundary() {
        let s = square();
        let c = s.closest([0.2, 0.3, 0.5]);
        assert!((c.distance - 0.5).abs() < 1e-15);
        assert_eq!(c.normal, [0.0, 0.0, 1.0]);
        assert!(!c.beyond_boundary);
        assert!((s.signed_distance([0.2, 0.3, -0.25]) + 0.25).abs() < 1e-15);
        let c = s.closest([1.5, 0.0, 0.1]);
        assert!(c.beyond_boundary);
        assert!((c.point[0] - 1.0).abs() < 1e-15);
        // Above a boundary point, straight along the normal: on the surface's side.
        assert!(!s.closest([1.0, 0.0, 0.3]).beyond_boundary);
        assert_eq!(s.highest_point()[2], 0.0);
        assert!(s.angle_defects().iter().all(|&d| d == 0.0));
    }
}
