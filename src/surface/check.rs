//! What a target mesh must be: one connected, orientable, manifold sheet of non-degenerate
//! triangles with a boundary (where the rods of a gridshell end). Vertices at identical
//! positions are welded first, because CAD exports often repeat them per face.

use std::collections::HashMap;

use super::obj::{RawMesh, TextError};

/// A checked mesh: welded, consistently oriented, with its boundary edges marked.
#[derive(Debug, Clone)]
pub struct Checked {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// `boundary[t][e]`: edge e of triangle t (corners e and e + 1 mod 3) has no neighbour.
    pub boundary: Vec<[bool; 3]>,
    /// Whether each vertex lies on the boundary.
    pub boundary_vertex: Vec<bool>,
    /// Triangles whose winding was reversed to agree with the first one.
    pub flipped: usize,
}

/// Relative area below which a triangle counts as degenerate: area < ε · (longest edge)².
const DEGENERATE: f64 = 1e-12;

pub fn check(raw: &RawMesh) -> Result<Checked, TextError> {
    if raw.triangles.is_empty() {
        return Err(TextError {
            line: raw.vertex_lines.last().copied().unwrap_or(1),
            message: "the mesh has no faces (`f` records): a target surface needs triangles".into(),
        });
    }
    let (vertices, welded) = weld(&raw.vertices);
    let mut triangles: Vec<[u32; 3]> = raw
        .triangles
        .iter()
        .map(|t| t.map(|i| welded[i as usize]))
        .collect();
    let at = |t: usize| raw.triangle_lines[t];
    for (t, tri) in triangles.iter().enumerate() {
        degenerate(&vertices, tri).map_err(|m| TextError {
            line: at(t),
            message: format!("face {}: {m}", t + 1),
        })?;
    }
    // Each undirected edge and the triangles (with the edge's slot) that use it.
    let mut edges: HashMap<(u32, u32), Vec<(usize, usize)>> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (tri[e], tri[(e + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push((t, e));
        }
    }
    if let Some(((a, b), users)) = edges.iter().find(|(_, u)| u.len() > 2) {
        return Err(TextError {
            line: at(users[2].0),
            message: format!(
                "non-manifold edge between vertices {} and {}: used by {} faces (lines {})",
                a + 1,
                b + 1,
                users.len(),
                users
                    .iter()
                    .map(|u| at(u.0).to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        });
    }
    let flipped = orient(&mut triangles, &edges, &at)?;
    let mut boundary = vec![[false; 3]; triangles.len()];
    let mut boundary_vertex = vec![false; vertices.len()];
    for users in edges.values() {
        if let [(t, e)] = users[..] {
            boundary[t][e] = true;
            boundary_vertex[triangles[t][e] as usize] = true;
            boundary_vertex[triangles[t][(e + 1) % 3] as usize] = true;
        }
    }
    if !boundary.iter().flatten().any(|&b| b) {
        return Err(TextError {
            line: at(0),
            message: "the mesh is closed (every edge has two faces): a gridshell target needs a \
                      boundary where its rods end"
                .into(),
        });
    }
    Ok(Checked {
        vertices,
        triangles,
        boundary,
        boundary_vertex,
        flipped,
    })
}

/// Merges vertices at bit-identical positions; returns the kept vertices and the map from the
/// file's indices to them.
fn weld(points: &[[f64; 3]]) -> (Vec<[f64; 3]>, Vec<u32>) {
    let mut seen: HashMap<[u64; 3], u32> = HashMap::new();
    let mut kept = Vec::new();
    let map = points
        .iter()
        .map(|p| {
            // +0.0 and −0.0 are the same point.
            let key = p.map(|x| (x + 0.0).to_bits());
            *seen.entry(key).or_insert_with(|| {
                kept.push(*p);
                (kept.len() - 1) as u32
            })
        })
        .collect();
    (kept, map)
}

fn degenerate(v: &[[f64; 3]], t: &[u32; 3]) -> Result<(), String> {
    if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
        return Err(format!(
            "degenerate triangle: a vertex repeats ({}, {}, {} after welding equal positions)",
            t[0] + 1,
            t[1] + 1,
            t[2] + 1
        ));
    }
    let p = t.map(|i| v[i as usize]);
    let d = |a: [f64; 3], b: [f64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (e1, e2, e3) = (d(p[0], p[1]), d(p[0], p[2]), d(p[1], p[2]));
    let c = crate::math::vec::cross(e1, e2);
    let area2 = crate::math::vec::norm(c);
    let longest = [e1, e2, e3]
        .iter()
        .map(|e| crate::math::vec::dot(*e, *e))
        .fold(0.0, f64::max);
    if area2 <= 2.0 * DEGENERATE * longest {
        return Err(format!(
            "degenerate triangle: its corners are collinear (area {:.3e} m² with a longest \
             edge of {:.3e} m)",
            0.5 * area2,
            longest.sqrt()
        ));
    }
    Ok(())
}

/// Flood fill over shared edges: every triangle gets the winding that runs each shared edge
/// opposite to its neighbour's. Fails when the sheet is not connected or not orientable.
fn orient(
    tris: &mut [[u32; 3]],
    edges: &HashMap<(u32, u32), Vec<(usize, usize)>>,
    at: &dyn Fn(usize) -> usize,
) -> Result<usize, TextError> {
    let n = tris.len();
    let mut state = vec![None::<bool>; n];
    state[0] = Some(false);
    let mut stack = vec![0];
    let mut flipped = 0;
    let directed = |tri: &[u32; 3], e: usize, flip: bool| {
        let (a, b) = (tri[e], tri[(e + 1) % 3]);
        if flip {
            (b, a)
        } else {
            (a, b)
        }
    };
    while let Some(t) = stack.pop() {
        let ft = state[t].expect("visited");
        for e in 0..3 {
            let (a, b) = directed(&tris[t], e, ft);
            for &(u, eu) in &edges[&(a.min(b), a.max(b))] {
                if u == t {
                    continue;
                }
                // The neighbour must run the edge from b to a.
                let want = directed(&tris[u], eu, false) != (b, a);
                match state[u] {
                    None => {
                        state[u] = Some(want);
                        flipped += usize::from(want);
                        stack.push(u);
                    }
                    Some(f) if f != want => {
                        return Err(TextError {
                            line: at(u),
                            message: format!(
                                "face {}: the surface is not orientable (a Möbius-like band): \
                                 no winding of its faces agrees across every edge",
                                u + 1
                            ),
                        });
                    }
                    _ => {}
                }
            }
        }
    }
    if let Some(t) = state.iter().position(|s| s.is_none()) {
        return Err(TextError {
            line: at(t),
            message: format!(
                "face {} is not connected to face 1 through shared edges: the mesh has several \
                 components, and a target must be one surface",
                t + 1
            ),
        });
    }
    for (t, s) in state.iter().enumerate() {
        if *s == Some(true) {
            tris[t].swap(1, 2);
        }
    }
    Ok(flipped)
}

#[cfg(test)]
mod tests {
    use super::super::obj::parse;
    use super::*;

    const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

    #[test]
    fn a_square_with_one_face_flipped_is_oriented_and_has_four_boundary_edges() {
        let c = check(&parse(&format!("{SQUARE}f 1 2 3\nf 1 4 3\n")).unwrap()).unwrap();
        assert_eq!(c.flipped, 1);
        assert_eq!(c.triangles[1], [0, 2, 3]);
        assert_eq!(c.boundary.iter().flatten().filter(|&&b| b).count(), 4);
    }

    #[test]
    fn bad_meshes_are_refused_at_the_face_that_shows_it() {
        let bad = |s: &str| check(&parse(s).unwrap()).unwrap_err();
        let e = bad(&format!("{SQUARE}f 1 2 3\nf 1 2 2\n"));
        assert_eq!(e.line, 6);
        assert!(e.message.contains("degenerate"), "{}", e.message);
        let e = bad(&format!("{SQUARE}v 2 2 2\nf 1 2 3\nf 1 2 5\nf 1 2 4\n"));
        assert!(e.message.contains("non-manifold"), "{}", e.message);
        let e = bad(&format!(
            "{SQUARE}v 5 5 0\nv 6 5 0\nv 5 6 0\nf 1 2 3\nf 5 6 7\n"
        ));
        assert_eq!(e.line, 9);
        assert!(e.message.contains("several components"), "{}", e.message);
        // A tetrahedron's surface has no boundary.
        let e = bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
        assert!(e.message.contains("closed"), "{}", e.message);
        let e = bad(&format!("{SQUARE}v 2 0 0\nf 1 2 5\n"));
        assert!(e.message.contains("collinear"), "{}", e.message);
    }

    #[test]
    fn repeated_positions_are_welded() {
        let c = check(
            &parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n")
                .unwrap(),
        )
        .unwrap();
        assert_eq!(c.vertices.len(), 4);
        assert_eq!(c.boundary.iter().flatten().filter(|&&b| b).count(), 4);
    }
}
