//! `stages`: names that can name files, and each stage's loads checked in the scene they make
//! (the loads before plus its own), with errors located at `stages[k].loads[j]`.

use std::collections::HashSet;

use super::{loads, RodIndex};
use crate::scene::locate::Item;
use crate::scene::types::Scene;
use crate::scene::FieldError;

pub(super) fn stages(s: &Scene, rods: &RodIndex) -> Result<(), FieldError> {
    let mut names = HashSet::new();
    for (k, st) in s.stages.iter().enumerate() {
        let err = |m: String| Err(FieldError::new("stages", k, "name", m));
        let ok = !st.name.is_empty()
            && st.name.len() <= 64
            && st
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
        if !ok {
            return err(format!(
                "\"{}\": a stage name is 1 to 64 letters, digits, '-' or '_' (it names the \
                 stage's output files)",
                st.name
            ));
        }
        if st.name == "base" {
            return err("\"base\" names the scene's own loads (stage 0); choose another".into());
        }
        if !names.insert(st.name.as_str()) {
            return err(format!("\"{}\" names an earlier stage too", st.name));
        }
    }
    for k in 1..=s.stages.len() {
        let scene = s.stage(k);
        let relocate = |e: FieldError| owner(s, e);
        loads::loads(&scene, rods).map_err(relocate)?;
        loads::unsupported_loads(&scene).map_err(relocate)?;
    }
    Ok(())
}

/// Gravity warnings for the stages' loads, located in their stages.
pub(super) fn warnings(s: &Scene) -> Vec<FieldError> {
    let all = s.all_stages();
    loads::gravity_warnings(&all)
        .into_iter()
        .filter(|w| matches!(w.item, Item::Index(i) if i >= s.loads.len()))
        .map(|w| owner(s, w))
        .collect()
}

/// An error about `loads[i]` of a stage's scene, moved to the stage whose load i is.
fn owner(s: &Scene, e: FieldError) -> FieldError {
    let i = match e.item {
        Item::Index(i) if e.section == "loads" => i,
        _ => return e,
    };
    let Some(mut rest) = i.checked_sub(s.loads.len()) else {
        return e;
    };
    for (k, st) in s.stages.iter().enumerate() {
        if rest < st.loads.len() {
            let field = if e.field.is_empty() {
                format!("loads[{rest}]")
            } else {
                format!("loads[{rest}].{}", e.field)
            };
            return FieldError::new("stages", k, &field, e.message);
        }
        rest -= st.loads.len();
    }
    e
}
