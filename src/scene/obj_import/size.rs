//! The size of the network an OBJ file asks for, from one streaming pass over its text before
//! anything is parsed or generated: every polyline edge becomes at least `subdivide` rod
//! segments, so a file whose edges pass the node limit (or whose nodes' memory lower bound
//! passes `--max-memory`) is refused at the line where it does, instead of after the parser
//! and the generator have allocated gigabytes for it (issue 39).

use super::ObjError;
use crate::scene::validate::MAX_NODES;

/// Refuses, at the line where it happens, a network with more than [`MAX_NODES`] nodes or with
/// more than `memory_limit` bytes at `per_node` bytes a node (`u64::MAX`: no limit); the
/// solver's layer gives the bound and writes bytes in messages (`bytes_text`).
pub fn check(
    src: &str,
    subdivide: usize,
    memory_limit: u64,
    per_node: u64,
    bytes_text: fn(u64) -> String,
) -> Result<(), ObjError> {
    let subdivide = subdivide.max(1) as u64;
    let mut edges: u64 = 0;
    // The polyline statement being read (continued with a trailing backslash): its vertices.
    let mut refs: Option<u64> = None;
    let mut continued = false;
    for (i, raw) in src.lines().enumerate() {
        let text = raw.split('#').next().unwrap_or("").trim_end();
        let (text, more) = match text.strip_suffix('\\') {
            Some(head) => (head, true),
            None => (text, false),
        };
        let mut toks = text.split_whitespace();
        if !continued {
            refs = (toks.next() == Some("l")).then_some(0);
        }
        if let Some(r) = refs.as_mut() {
            *r += toks.count() as u64;
        }
        continued = more;
        if more {
            continue;
        }
        let Some(r) = refs.take() else { continue };
        edges = edges.saturating_add(r.saturating_sub(1));
        let nodes = edges.saturating_mul(subdivide);
        if nodes > MAX_NODES as u64 {
            return Err(ObjError::at(
                i + 1,
                format!(
                    "the network would have more than {MAX_NODES} nodes by this line \
                     ({edges} polyline edges × --subdivide {subdivide}); split the file or \
                     reduce --subdivide (limit in docs/scene-format.md)"
                ),
            ));
        }
        let bytes = nodes.saturating_mul(per_node);
        if bytes > memory_limit {
            return Err(ObjError::at(
                i + 1,
                format!(
                    "the network needs at least {} by this line ({nodes} nodes from {edges} \
                     polyline edges × --subdivide {subdivide}), above --max-memory {}",
                    bytes_text(bytes),
                    bytes_text(memory_limit)
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(src: &str, subdivide: usize, limit: u64) -> Result<(), ObjError> {
        super::check(src, subdivide, limit, 4000, |b| format!("{b} B"))
    }

    /// Edges are counted across continuation lines and comments; the refusal names the line
    /// where the count passes the limit.
    #[test]
    fn edges_are_counted_per_statement_and_refused_at_their_line() {
        let src = "v 0 0 0\nv 1 0 0\nv 2 0 0\nl 1 2 \\\n 3 # comment\nl 1 3\np 1\n";
        // 3 edges × 2 = 6 nodes at 4 KB: within 24 000 bytes, not within 23 999.
        assert!(check(src, 2, 24_000).is_ok());
        let e = check(src, 2, 23_999).unwrap_err();
        assert_eq!(e.line, Some(6), "{e}");
        assert!(e.message.contains("3 polyline edges"), "{e}");
        let e = check(src, MAX_NODES / 2, u64::MAX).unwrap_err();
        assert_eq!(e.line, Some(6), "{e}");
        assert!(check(src, MAX_NODES / 3, u64::MAX).is_ok());
    }
}
