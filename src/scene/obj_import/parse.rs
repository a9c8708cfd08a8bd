//! OBJ text to vertices and polyline elements.

use std::collections::BTreeMap;

use super::ObjError;

/// A parsed OBJ file: only what networks need.
#[derive(Debug, Clone, Default)]
pub struct ObjFile {
    pub vertices: Vec<[f64; 3]>,
    /// 1-based source line of each vertex.
    pub vertex_lines: Vec<usize>,
    pub elements: Vec<Element>,
    /// Elements that are read but not used for rods (faces, free-form curves), by keyword.
    pub ignored: BTreeMap<String, usize>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementKind {
    Line,
    Point,
}

#[derive(Debug, Clone)]
pub struct Element {
    pub kind: ElementKind,
    /// Name of the enclosing `o` or `g` (the later of the two), empty before any.
    pub group: String,
    /// 0-based vertex indices.
    pub vertices: Vec<usize>,
    /// 1-based source line.
    pub line: usize,
}

/// A positive vertex index of an element, checked once every vertex is known: (raw index,
/// source line).
type Forward = (i64, usize);

/// Parses the OBJ elements rodnet uses. Positive indices may refer to vertices defined later
/// (some exporters write elements first); negative ones count back from the vertices so far.
pub fn parse(src: &str) -> Result<ObjFile, ObjError> {
    let mut obj = ObjFile::default();
    let mut group = String::new();
    let mut forward: Vec<Forward> = Vec::new();
    for (line, stmt) in statements(src) {
        let mut toks = stmt.split_whitespace();
        let Some(key) = toks.next() else { continue };
        match key {
            "v" => {
                obj.vertices.push(vertex(line, toks.collect())?);
                obj.vertex_lines.push(line);
            }
            "o" | "g" => {
                group = toks.collect::<Vec<_>>().join(" ");
            }
            "l" | "p" => {
                let kind = if key == "l" {
                    ElementKind::Line
                } else {
                    ElementKind::Point
                };
                let mut vertices = Vec::new();
                for tok in toks {
                    vertices.push(index(line, tok, obj.vertices.len(), &mut forward)?);
                }
                if kind == ElementKind::Line && vertices.len() < 2 {
                    return Err(ObjError::at(
                        line,
                        format!(
                            "a line element needs at least 2 vertices, got {}",
                            vertices.len()
                        ),
                    ));
                }
                obj.elements.push(Element {
                    kind,
                    group: group.clone(),
                    vertices,
                    line,
                });
            }
            "f" | "curv" | "curv2" | "surf" => {
                *obj.ignored.entry(key.to_string()).or_default() += 1;
            }
            _ => {}
        }
    }
    let n = obj.vertices.len();
    for (idx, line) in forward {
        if idx as usize > n {
            return Err(ObjError::at(
                line,
                format!("vertex index {idx} is out of range: the file defines {n} vertices"),
            ));
        }
    }
    Ok(obj)
}

/// The statements of an OBJ file without comments, each with its 1-based first line: a
/// trailing backslash continues a statement on the next line.
fn statements(src: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut pending = String::new();
    let mut pending_line = 0;
    for (i, raw) in src.lines().enumerate() {
        let text = raw.split('#').next().unwrap_or("");
        if pending.is_empty() {
            pending_line = i + 1;
        }
        if let Some(head) = text.trim_end().strip_suffix('\\') {
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        pending.push_str(text);
        out.push((pending_line, std::mem::take(&mut pending)));
    }
    // A continuation on the last line has no next line to join: the statement ends there.
    if !pending.is_empty() {
        out.push((pending_line, pending));
    }
    out
}

/// The position of a `v` statement from its numbers.
fn vertex(line: usize, nums: Vec<&str>) -> Result<[f64; 3], ObjError> {
    if nums.len() < 3 {
        return Err(ObjError::at(
            line,
            format!("`v` needs x, y and z, got {} number(s)", nums.len()),
        ));
    }
    let mut p = [0.0; 3];
    for k in 0..3 {
        p[k] = match nums[k].parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => {
                return Err(ObjError::at(
                    line,
                    format!(
                        "vertex coordinate {} is `{}`, not a finite number",
                        ["x", "y", "z"][k],
                        nums[k]
                    ),
                ))
            }
        };
    }
    Ok(p)
}

/// The 0-based vertex of one index token of an element, `n` vertices having been defined so
/// far; a positive index is recorded in `forward` for the check at the end of the file.
fn index(line: usize, tok: &str, n: usize, forward: &mut Vec<Forward>) -> Result<usize, ObjError> {
    let first = tok.split('/').next().unwrap_or("");
    let idx: i64 = first
        .parse()
        .map_err(|_| ObjError::at(line, format!("`{tok}` is not a vertex index")))?;
    let n = n as i64;
    if idx == 0 {
        Err(ObjError::at(
            line,
            "vertex index 0 is invalid (OBJ indices start at 1)".into(),
        ))
    } else if idx < 0 {
        if -idx > n {
            return Err(ObjError::at(
                line,
                format!(
                    "relative vertex index {idx} reaches before the first vertex \
                     ({n} defined so far)"
                ),
            ));
        }
        Ok((n + idx) as usize)
    } else {
        forward.push((idx, line));
        Ok((idx - 1) as usize)
    }
}
