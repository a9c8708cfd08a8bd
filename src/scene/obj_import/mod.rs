//! Rod networks drawn in a 3-D tool and saved as OBJ: `l` polylines become rods, vertices
//! shared by several polylines become joints, and simple selectors choose the supports.
//!
//! rodnet reads `v`, `l`, `p`, `o` and `g` itself instead of using `tobj`: tobj parses `l` in
//! the same branch as `f`, so a polyline comes back as a polygon (`l 1 2 3` is indistinguishable
//! from a triangle, and `triangulate` fans it), 2-vertex lines are dropped by its GPU options,
//! and positions are re-indexed per object, which loses the vertices that rods share
//! (checked when the dependencies were chosen). Polylines need the raw element lists.
//!
//! Tools write networks in two ways, and both are read:
//! - one `l` element per curve (Rhino, most CAD exporters), each curve usually in its own `o`
//!   or `g` with its own copies of shared points;
//! - one 2-vertex `l` per edge (Blender's mesh edges). Within one object these are chained
//!   back into rods: through every vertex where exactly two edges meet, and where more meet,
//!   through the straightest pairs (turning less than 45°); a joint sits wherever chains meet.
//!
//! Points closer than the weld tolerance are one point, so duplicated copies of a shared point
//! (one per object) still make a joint.

mod graph;
mod parse;
pub mod size;
mod to_scene;

use std::fmt;

pub use parse::{parse, Element, ElementKind, ObjFile};
pub use to_scene::{to_scene, Generated, NetworkOptions, MATERIAL};

/// An error in an OBJ file (`line` set) or in the options that turn it into a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjError {
    pub line: Option<usize>,
    pub message: String,
}

impl ObjError {
    fn at(line: usize, message: String) -> Self {
        ObjError {
            line: Some(line),
            message,
        }
    }
    fn global(message: String) -> Self {
        ObjError {
            line: None,
            message,
        }
    }
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "{l}: {}", self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::types::{JointKind, Rod, Solver, SupportKind};
    use std::collections::HashMap;

    fn opts() -> NetworkOptions {
        NetworkOptions {
            young_modulus: 1e9,
            poisson_ratio: Some(0.3),
            shear_modulus: None,
            density: 0.0,
            radius: 0.01,
            joint: JointKind::Rigid,
            subdivide: 1,
            pin_below: None,
            clamp_below: None,
            pin_groups: vec![],
            clamp_groups: vec![],
            weld: None,
            chain: true,
            gravity: None,
            solver: Solver::default(),
        }
    }

    #[test]
    fn polylines_with_duplicated_shared_points_make_joints() {
        // Two objects, each with its own copy of the crossing point (as Rhino writes them).
        let src = "o a\nv 0 0 0\nv 1 0 0\nv 2 0 0\nl 1 2 3\n\
                   o b\nv 1 -1 0\nv 1 0 0\nv 1 1 0\nl 4 5 6\n";
        let g = to_scene(&parse(src).unwrap(), &opts()).unwrap();
        let s = &g.scene;
        assert_eq!(s.rods.len(), 2);
        assert_eq!(
            (s.rods[0].name.as_str(), s.rods[1].name.as_str()),
            ("a", "b")
        );
        assert_eq!(s.joints.len(), 1);
        assert_eq!(
            s.joints[0].at,
            vec![("a".to_string(), 1), ("b".to_string(), 1)]
        );
        assert_eq!(g.rod_lines, vec![5, 10]);
        assert_eq!(g.joint_lines, vec![3]);
    }

    #[test]
    fn edges_are_chained_through_straight_continuations() {
        // A plus sign drawn edge by edge (Blender style) plus a closed triangle of edges.
        let src = "o plus\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 -1 0\nv 1 1 0\n\
                   l 1 2\nl 2 3\nl 4 2\nl 2 5\n\
                   o tri\nv 5 0 0\nv 6 0 0\nv 5 1 0\nl 6 7\nl 8 7\nl 6 8\n";
        let s = to_scene(&parse(src).unwrap(), &opts()).unwrap().scene;
        let by_name: HashMap<&str, &Rod> = s.rods.iter().map(|r| (r.name.as_str(), r)).collect();
        assert_eq!(s.rods.len(), 3, "{:?}", by_name.keys());
        let h = by_name["plus.1"];
        assert_eq!(
            h.points,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
        );
        let v = by_name["plus.2"];
        assert_eq!(
            v.points,
            vec![[1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]
        );
        let t = by_name["tri"];
        assert!(t.closed);
        assert_eq!(t.points.len(), 3);
        assert_eq!(s.joints.len(), 1);
        // Without chaining every edge is its own rod.
        let mut o = opts();
        o.chain = false;
        let s = to_scene(&parse(src).unwrap(), &o).unwrap().scene;
        assert_eq!(s.rods.len(), 7);
    }

    #[test]
    fn supports_from_height_and_groups() {
        let src = "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nl 1 2 3 4\n\
                   g anchors\np 3\n";
        let mut o = opts();
        o.pin_below = Some(0.0);
        o.clamp_groups = vec!["anchors".into()];
        let s = to_scene(&parse(src).unwrap(), &o).unwrap().scene;
        let got: Vec<(usize, SupportKind)> =
            s.supports.iter().map(|s| (s.vertex, s.kind)).collect();
        assert_eq!(
            got,
            vec![
                (0, SupportKind::Pin),
                (2, SupportKind::Clamp),
                (3, SupportKind::Pin)
            ]
        );
        o.pin_below = Some(-1.0);
        let e = to_scene(&parse(src).unwrap(), &o).unwrap_err();
        assert!(e.message.contains("the lowest is at z = 0"), "{e}");
    }

    #[test]
    fn located_errors() {
        let cases = [
            ("v 0 0 0\nv 1 0\n", 2, "needs x, y and z"),
            ("v 0 0 0\nv 1 0 nan\n", 2, "not a finite number"),
            ("v 0 0 0\nv 1 0 0\nl 1 3\n", 3, "out of range"),
            ("v 0 0 0\nl 1 0\n", 2, "index 0"),
            ("v 0 0 0\nl -2 1\n", 2, "reaches before the first vertex"),
            ("v 0 0 0\nl 1\n", 2, "at least 2 vertices"),
            ("v 0 0 0\nv 1 0 0\nl 1 x\n", 3, "not a vertex index"),
        ];
        for (src, line, needle) in cases {
            let e = parse(src).unwrap_err();
            assert_eq!(e.line, Some(line), "{src:?}: {e}");
            assert!(e.message.contains(needle), "{src:?}: {e}");
        }
        let gen = |src: &str| to_scene(&parse(src).unwrap(), &opts()).unwrap_err();
        let e = gen("v 0 0 0\nv 0 0 0\nv 1 0 0\nl 1 2 3\n");
        assert_eq!(e.line, Some(4));
        assert!(e.message.contains("zero-length"), "{e}");
        let e = gen("v 0 0 0\nv 1 0 0\nf 1 2 1\n");
        assert!(
            e.message.contains("no `l` polylines") && e.message.contains("1 `f`"),
            "{e}"
        );
        let e = gen("v 0 0 0\nv 1 0 0\nl 1 2\nl 2 1\n");
        assert_eq!(e.line, Some(4));
        assert!(e.message.contains("repeats the edge on line 3"), "{e}");
    }

    #[test]
    fn continuation_lines_and_forward_references() {
        let src = "l 1 2 \\\n  3\nv 0 0 0\nv 1 0 0\nv 2 1 0\n";
        let obj = parse(src).unwrap();
        assert_eq!(obj.elements[0].vertices, vec![0, 1, 2]);
        assert_eq!(obj.elements[0].line, 1);
        assert_eq!(obj.vertex_lines, vec![3, 4, 5]);
    }
}
