//! Maps a field of a parsed scene back to its line and column in the RON text, so that semantic
//! errors (unknown material, zero-length segment, …) point at the offending line like syntax
//! errors do. A tiny tokenizer skips strings and comments and tracks bracket depth.

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    Str(String),
    Open,
    Close,
    Comma,
    Colon,
    Other,
}

fn tokenize(src: &str) -> Vec<(Tok, usize, usize)> {
    let mut out = Vec::new();
    let chars: Vec<char> = src.chars().collect();
    let (mut i, mut line, mut col) = (0, 1, 1);
    let adv = |i: &mut usize, line: &mut usize, col: &mut usize, c: char| {
        *i += 1;
        if c == '\n' {
            *line += 1;
            *col = 1;
        } else {
            *col += 1;
        }
    };
    while i < chars.len() {
        let c = chars[i];
        let (l0, c0) = (line, col);
        if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                {
                    let ch = chars[i];
                    adv(&mut i, &mut line, &mut col, ch);
                }
            }
        } else if c == '/' && chars.get(i + 1) == Some(&'*') {
            while i < chars.len() && !(chars[i] == '*' && chars.get(i + 1) == Some(&'/')) {
                {
                    let ch = chars[i];
                    adv(&mut i, &mut line, &mut col, ch);
                }
            }
            for _ in 0..2 {
                if i < chars.len() {
                    {
                        let ch = chars[i];
                        adv(&mut i, &mut line, &mut col, ch);
                    }
                }
            }
        } else if c == '"' {
            let mut s = String::new();
            adv(&mut i, &mut line, &mut col, c);
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' && i + 1 < chars.len() {
                    {
                        let ch = chars[i];
                        adv(&mut i, &mut line, &mut col, ch);
                    }
                }
                s.push(chars[i]);
                {
                    let ch = chars[i];
                    adv(&mut i, &mut line, &mut col, ch);
                }
            }
            if i < chars.len() {
                adv(&mut i, &mut line, &mut col, '"');
            }
            out.push((Tok::Str(s), l0, c0));
        } else if c.is_alphabetic() || c == '_' {
            let mut s = String::new();
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                s.push(chars[i]);
                {
                    let ch = chars[i];
                    adv(&mut i, &mut line, &mut col, ch);
                }
            }
            out.push((Tok::Ident(s), l0, c0));
        } else {
            let t = match c {
                '(' | '[' | '{' => Some(Tok::Open),
                ')' | ']' | '}' => Some(Tok::Close),
                ',' => Some(Tok::Comma),
                ':' => Some(Tok::Colon),
                c if c.is_whitespace() => None,
                _ => Some(Tok::Other),
            };
            if let Some(t) = t {
                out.push((t, l0, c0));
            }
            adv(&mut i, &mut line, &mut col, c);
        }
    }
    out
}

/// Which element of a top-level list (by index) or map (by key).
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    Index(usize),
    Key(String),
    None,
}

/// Line and column (1-based) of `field` inside element `item` of the top-level `section`,
/// falling back to the element, then to the section.
pub fn locate(src: &str, section: &str, item: &Item, field: &str) -> Option<(usize, usize)> {
    let toks = tokenize(src);
    let mut depth = 0usize;
    let mut k = 0;
    // Find `section:` directly inside the outer `Scene(`.
    let mut found = None;
    while k + 1 < toks.len() {
        match &toks[k].0 {
            Tok::Open => depth += 1,
            Tok::Close => depth = depth.saturating_sub(1),
            Tok::Ident(s) if depth == 1 && s == section && toks[k + 1].0 == Tok::Colon => {
                found = Some(k);
                break;
            }
            _ => {}
        }
        k += 1;
    }
    let start = found?;
    let section_pos = (toks[start].1, toks[start].2);
    if *item == Item::None {
        // `field:` sits one level inside the value, so an explicit `Some(` around it is
        // stepped over (`reference: Some(Reference(rod: ..))`).
        let mut k = start + 2;
        if toks.get(k).map(|t| &t.0) == Some(&Tok::Ident("Some".into()))
            && toks.get(k + 1).map(|t| &t.0) == Some(&Tok::Open)
        {
            k += 2;
        }
        return Some(field_in(&toks, k, field).unwrap_or(section_pos));
    }
    // The section's value must be a bracketed list or map.
    let k = start + 2;
    if k >= toks.len() || toks[k].0 != Tok::Open {
        return Some(section_pos);
    }
    match element_start(&toks, k + 1, item) {
        Some(e) => Some(field_in(&toks, e, field).unwrap_or((toks[e].1, toks[e].2))),
        None => Some(section_pos),
    }
}

/// The first token of element `item` of the list or map whose first token is `k`.
fn element_start(toks: &[(Tok, usize, usize)], mut k: usize, item: &Item) -> Option<usize> {
    let mut index = 0;
    let mut d = 0usize;
    let mut elem_start = k;
    while k < toks.len() {
        if d == 0 && k == elem_start {
            let hit = match item {
                Item::Index(i) => *i == index,
                Item::Key(key) => toks[k].0 == Tok::Str(key.clone()),
                Item::None => false,
            };
            if hit {
                return Some(k);
            }
        }
        match toks[k].0 {
            Tok::Open => d += 1,
            Tok::Close => {
                if d == 0 {
                    return None;
                }
                d -= 1;
            }
            Tok::Comma if d == 0 => {
                index += 1;
                elem_start = k + 1;
            }
            _ => {}
        }
        k += 1;
    }
    None
}

/// The first key that repeats an earlier key of the top-level map `section`, with its line and
/// column. Deserializing into a map keeps only the last value of a repeated key, so a repeated
/// material name would silently replace the first definition.
pub fn duplicate_key(src: &str, section: &str) -> Option<(String, usize, usize)> {
    let toks = tokenize(src);
    let mut depth = 0usize;
    let mut k = 0;
    while k + 2 < toks.len() {
        match &toks[k].0 {
            Tok::Open => depth += 1,
            Tok::Close => depth = depth.saturating_sub(1),
            Tok::Ident(s) if depth == 1 && s == section && toks[k + 1].0 == Tok::Colon => break,
            _ => {}
        }
        k += 1;
    }
    k += 2;
    if k >= toks.len() || toks[k].0 != Tok::Open {
        return None;
    }
    let mut seen = std::collections::HashSet::new();
    let mut d = 0usize;
    let mut at_start = true;
    for (i, (t, line, col)) in toks.iter().enumerate().skip(k + 1) {
        match t {
            Tok::Str(key) if d == 0 && at_start => {
                if toks.get(i + 1).map(|t| &t.0) == Some(&Tok::Colon) && !seen.insert(key.clone()) {
                    return Some((key.clone(), *line, *col));
                }
                at_start = false;
            }
            Tok::Open => {
                d += 1;
                at_start = false;
            }
            Tok::Close => {
                if d == 0 {
                    return None;
                }
                d -= 1;
            }
            Tok::Comma if d == 0 => at_start = true,
            _ => at_start = false,
        }
    }
    None
}

/// Position of `field:` one level inside the element starting at token `k`. A nested path
/// `list[i].field` (a stage's `loads[2].force`) goes on into element i of that list.
fn field_in(toks: &[(Tok, usize, usize)], k: usize, field: &str) -> Option<(usize, usize)> {
    field_token(toks, k, field).map(|t| (toks[t].1, toks[t].2))
}

fn field_token(toks: &[(Tok, usize, usize)], mut k: usize, field: &str) -> Option<usize> {
    if field.is_empty() {
        return None;
    }
    if let Some((head, tail)) = field.split_once('[') {
        let t = field_token(toks, k, head)?;
        let (index, rest) = tail.split_once(']')?;
        let index: usize = index.parse().ok()?;
        let rest = rest.strip_prefix('.').unwrap_or(rest);
        let open = t + 2;
        if toks.get(open).map(|x| &x.0) != Some(&Tok::Open) {
            return Some(t);
        }
        let Some(e) = element_start(toks, open + 1, &Item::Index(index)) else {
            return Some(t);
        };
        return Some(field_token(toks, e, rest).unwrap_or(e));
    }
    let mut d = 0usize;
    while k + 1 < toks.len() {
        match &toks[k].0 {
            Tok::Open => d += 1,
            Tok::Close => {
                if d <= 1 {
                    return None;
                }
                d -= 1;
            }
            Tok::Comma if d == 0 => return None,
            Tok::Ident(s) if d == 1 && s == field && toks[k + 1].0 == Tok::Colon => {
                return Some(k);
            }
            _ => {}
        }
        k += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_fields_in_lists_and_maps() {
        let src = r#"Scene(
    materials: { "steel": Material(young_modulus: 1.0, section: Circle(radius: 0.1)) },
    rods: [
        Rod(name: "a", material: "x", points: [(0,0,0), (1,0,0)]), // "material: here"
        Rod(name: "b",
            material: "steel", points: []),
    ],
)"#;
        assert_eq!(
            locate(src, "rods", &Item::Index(1), "points"),
            Some((6, 32))
        );
        assert_eq!(
            locate(src, "rods", &Item::Index(0), "material"),
            Some((4, 24))
        );
        assert_eq!(
            locate(src, "materials", &Item::Key("steel".into()), "section"),
            Some((2, 56))
        );
        assert_eq!(locate(src, "rods", &Item::Index(7), "x"), Some((3, 5)));
    }

    #[test]
    fn finds_nested_fields_of_list_elements() {
        let src = r#"Scene(
    stages: [
        Stage(name: "a", loads: [Gravity(g: (0, 0, -9.8))]),
        Stage(name: "b",
              loads: [Force(rod: "r", vertex: 0, force: (1, 0, 0)),
                      Force(rod: "r", vertex: 9, force: (0, 0, 1))]),
    ],
)"#;
        let at = |field: &str| locate(src, "stages", &Item::Index(1), field);
        assert_eq!(at("loads[1].vertex"), Some((6, 39)));
        assert_eq!(at("loads[0]"), Some((5, 23)));
        // Missing pieces fall back to the nearest enclosing item found.
        assert_eq!(at("loads[5].force"), Some((5, 15)));
        assert_eq!(at("loads[0].nothing"), Some((5, 23)));
    }

    #[test]
    fn finds_fields_of_optional_sections_with_or_without_some() {
        for (value, col) in [
            ("Some((rod: \"a\", vertex: 1))", 32),
            ("Some(Reference(rod: \"a\", vertex: 1))", 41),
            ("Reference(rod: \"a\", vertex: 1)", 36),
        ] {
            let src = format!("Scene(\n    reference: {value},\n)");
            assert_eq!(
                locate(&src, "reference", &Item::None, "vertex"),
                Some((2, col)),
                "{value}"
            );
        }
    }

    #[test]
    fn finds_repeated_map_keys() {
        let src = r#"Scene(
    materials: {
        "a": Material(section: Circle(radius: 0.1), tag: { "a": 1 }), // "a": in a comment
        "b": Material(),
        "a": Material(),
    },
)"#;
        assert_eq!(duplicate_key(src, "materials"), Some(("a".into(), 5, 9)));
        let unique = src.replace(r#""a": Material(),"#, r#""c": Material(),"#);
        assert_eq!(duplicate_key(&unique, "materials"), None);
    }
}
