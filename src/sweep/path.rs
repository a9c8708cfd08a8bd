//! Parameter and quantity paths: places in a scene or a results JSON, written as in their text.
//!
//! `materials.steel.young_modulus`, `rods[0].subdivide`, `rods.arc.points[-1][2]`: names of
//! fields and map keys separated by `.`, list elements by index (`[i]` or `.i`, negative from
//! the end) or by their `name` (`rods.arc`), and an enum's variant may be left out
//! (`materials.steel.section.radius` reaches `section: Circle(radius: ...)`).

use serde_json::Value as Json;

/// The segments of a path, or why it is not one.
pub fn segments(path: &str) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (head, mut rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !head.is_empty() {
            out.push(head.to_string());
        } else if rest.is_empty() {
            return Err(format!("`{path}`: empty name between dots"));
        }
        while !rest.is_empty() {
            let close = rest
                .find(']')
                .filter(|_| rest.starts_with('['))
                .ok_or_else(|| format!("`{path}`: unbalanced brackets"))?;
            let inner = rest[1..close].trim_matches('"');
            if inner.is_empty() {
                return Err(format!("`{path}`: empty brackets"));
            }
            out.push(inner.to_string());
            rest = &rest[close + 1..];
        }
    }
    if out.is_empty() {
        return Err("empty path".into());
    }
    Ok(out)
}

/// Where one segment leads from `v`, descending through an enum's variant when the segment is
/// not the variant's name.
fn step<'a>(v: &'a Json, seg: &str) -> Option<&'a Json> {
    match v {
        Json::Object(m) => m.get(seg).or_else(|| match variant(m) {
            Some(inner) => step(inner, seg),
            None => None,
        }),
        Json::Array(a) => index(a, seg).map(|i| &a[i]),
        _ => None,
    }
}

/// The content of an externally tagged enum value (`{"Circle": {...}}`).
fn variant(m: &serde_json::Map<String, Json>) -> Option<&Json> {
    let mut it = m.iter();
    match (it.next(), it.next()) {
        (Some((k, v)), None) if k.starts_with(|c: char| c.is_ascii_uppercase()) => Some(v),
        _ => None,
    }
}

fn index(a: &[Json], seg: &str) -> Option<usize> {
    match seg.parse::<i64>() {
        Ok(i) if i < 0 => a.len().checked_sub(i.unsigned_abs() as usize),
        Ok(i) => Some(i as usize).filter(|&i| i < a.len()),
        Err(_) => a
            .iter()
            .position(|e| e.get("name").and_then(Json::as_str) == Some(seg)),
    }
}

/// The value at `path`, if there is one.
pub fn get<'a>(root: &'a Json, path: &str) -> Option<&'a Json> {
    let segs = segments(path).ok()?;
    segs.iter().try_fold(root, |v, s| step(v, s))
}

/// Replaces the value at `path` (which must exist: a sweep varies what the scene has), or says
/// which segment does not lead anywhere and what is there instead.
pub fn set(root: &mut Json, path: &str, value: Json) -> Result<(), String> {
    let segs = segments(path)?;
    let mut v = root;
    for (k, seg) in segs.iter().enumerate() {
        if step(v, seg).is_none() {
            let here = segs[..k].join(".");
            let at = if here.is_empty() {
                "the top level".to_string()
            } else {
                format!("`{here}`")
            };
            return Err(format!("no `{seg}` at {at} ({})", offer(v)));
        }
        v = locate_mut(v, seg).expect("found above");
    }
    *v = value;
    Ok(())
}

fn locate_mut<'a>(v: &'a mut Json, seg: &str) -> Option<&'a mut Json> {
    match v {
        Json::Object(m) => {
            if m.contains_key(seg) {
                return m.get_mut(seg);
            }
            if variant(m).is_some() {
                let inner = m.values_mut().next()?;
                return locate_mut(inner, seg);
            }
            None
        }
        Json::Array(a) => {
            let i = index(a, seg)?;
            a.get_mut(i)
        }
        _ => None,
    }
}

/// What a segment could have named at `v`, for the error message.
fn offer(v: &Json) -> String {
    match v {
        Json::Object(m) => match variant(m) {
            Some(inner) => offer(inner),
            None if m.is_empty() => "nothing there".into(),
            None => format!(
                "there: {}",
                m.keys()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        },
        Json::Array(a) => format!(
            "a list of {} element(s): an index{}",
            a.len(),
            if a.iter().any(|e| e.get("name").is_some()) {
                " or a name"
            } else {
                ""
            }
        ),
        Json::Null => "an unset value".into(),
        _ => "a single value".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn paths_reach_fields_elements_names_and_variant_contents() {
        let mut v = json!({"materials": {"steel": {"young_modulus": 2e11,
            "section": {"Circle": {"radius": 0.01}}}},
            "rods": [{"name": "arc", "subdivide": 4}, {"name": "b", "subdivide": 2}]});
        set(&mut v, "materials.steel.young_modulus", json!(1e9)).unwrap();
        set(&mut v, "materials.steel.section.radius", json!(0.02)).unwrap();
        set(&mut v, "rods[1].subdivide", json!(8)).unwrap();
        set(&mut v, "rods.arc.subdivide", json!(6)).unwrap();
        assert_eq!(get(&v, "materials.steel.young_modulus"), Some(&json!(1e9)));
        assert_eq!(
            get(&v, "materials.steel.section.Circle.radius"),
            Some(&json!(0.02))
        );
        assert_eq!(get(&v, "rods[-1].subdivide"), Some(&json!(8)));
        assert_eq!(get(&v, "rods.arc.subdivide"), Some(&json!(6)));
        let e = set(&mut v, "materials.steel.young_modulu", json!(1)).unwrap_err();
        assert!(e.contains("`young_modulus`"), "{e}");
        assert!(set(&mut v, "rods[2].subdivide", json!(1)).is_err());
        assert!(segments("a..b").is_err());
        assert!(segments("a[0").is_err());
    }
}
