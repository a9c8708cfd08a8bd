//! Triangle meshes from Wavefront OBJ text: `v` and `f` records, everything else ignored.
//! Polygons are split into fans; every vertex and triangle remembers its line, so that the
//! checks in `check.rs` can name the element a user has to fix.

/// A mesh as read, before any check.
#[derive(Debug, Clone, Default)]
pub struct RawMesh {
    pub vertices: Vec<[f64; 3]>,
    /// 1-based line of each vertex.
    pub vertex_lines: Vec<usize>,
    pub triangles: Vec<[u32; 3]>,
    /// 1-based line of the `f` record each triangle comes from.
    pub triangle_lines: Vec<usize>,
}

/// A located problem in the text: 1-based line and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct TextError {
    pub line: usize,
    pub message: String,
}

/// Above this many vertices or triangles a mesh is refused before its index is built.
pub const MAX_ELEMENTS: usize = 20_000_000;

pub fn parse(text: &str) -> Result<RawMesh, TextError> {
    let mut m = RawMesh::default();
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let fail = |message: String| Err(TextError { line, message });
        let body = raw.split('#').next().unwrap_or("");
        let mut words = body.split_whitespace();
        match words.next() {
            Some("v") => {
                let xs: Vec<&str> = words.collect();
                if xs.len() < 3 {
                    return fail(format!("vertex needs 3 coordinates, found {}", xs.len()));
                }
                let mut p = [0.0; 3];
                for (c, w) in p.iter_mut().zip(&xs) {
                    *c = match w.parse::<f64>() {
                        Ok(x) if x.is_finite() => x,
                        Ok(_) => return fail("a vertex coordinate is not finite".into()),
                        Err(_) => return fail("a vertex coordinate is not a number".into()),
                    };
                }
                m.vertices.push(p);
                m.vertex_lines.push(line);
            }
            Some("f") => {
                let mut corners = Vec::new();
                for w in words {
                    corners.push(
                        index(w, m.vertices.len())
                            .map_err(|message| TextError { line, message })?,
                    );
                }
                if corners.len() < 3 {
                    return fail(format!("face needs 3 vertices, found {}", corners.len()));
                }
                for c in 1..corners.len() - 1 {
                    m.triangles.push([corners[0], corners[c], corners[c + 1]]);
                    m.triangle_lines.push(line);
                }
            }
            _ => {}
        }
        if m.vertices.len() > MAX_ELEMENTS || m.triangles.len() > MAX_ELEMENTS {
            return fail(format!(
                "more than {MAX_ELEMENTS} vertices or triangles: above rodnet's limit for a target"
            ));
        }
    }
    Ok(m)
}

/// A face corner `i`, `i/t`, `i//n` or `i/t/n`; negative indices count back from the last vertex
/// read so far, as the format says.
fn index(word: &str, read: usize) -> Result<u32, String> {
    let head = word.split('/').next().unwrap_or("");
    let i: i64 = head
        .parse()
        .map_err(|_| "a face corner is not a vertex index".to_string())?;
    let zero_based = if i > 0 {
        i - 1
    } else if i < 0 {
        read as i64 + i
    } else {
        return Err("face corner 0: OBJ indices start at 1".into());
    };
    if zero_based < 0 || zero_based >= read as i64 {
        return Err(format!(
            "face corner {i} refers to no vertex defined before it ({read} so far)"
        ));
    }
    Ok(zero_based as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_become_fans_and_indices_may_be_relative() {
        let m = parse(
            "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 -2//1 -1//1\n",
        )
        .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.triangle_lines, vec![7, 7]);
        assert_eq!(m.vertex_lines, vec![2, 3, 4, 5]);
    }

    #[test]
    fn bad_records_are_located() {
        let e = parse("v 0 0 0\nv 1 nan 0\n").unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("not finite"), "{}", e.message);
        let e = parse("v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap_err();
        assert_eq!(e.line, 3);
        assert!(e.message.contains("refers to no vertex"), "{}", e.message);
        let e = parse("v 0 0\n").unwrap_err();
        assert!(e.message.contains("3 coordinates"));
    }
}
