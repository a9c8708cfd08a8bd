//! Scenes: the RON format ([`types`]), reading with located errors, and validation.
pub mod locate;
pub mod types;
pub mod validate;

use std::fmt;
use std::path::Path;

pub use types::Scene;

/// A semantic error in one field of a scene, before it is located in the text.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    pub section: &'static str,
    pub item: locate::Item,
    pub field: String,
    pub message: String,
}

impl FieldError {
    pub fn new(section: &'static str, index: usize, field: &str, message: String) -> Self {
        FieldError {
            section,
            item: locate::Item::Index(index),
            field: field.to_string(),
            message,
        }
    }
    pub fn keyed(section: &'static str, key: &str, field: &str, message: String) -> Self {
        FieldError {
            section,
            item: locate::Item::Key(key.to_string()),
            field: field.to_string(),
            message,
        }
    }
    pub fn global(section: &'static str, field: &str, message: String) -> Self {
        FieldError {
            section,
            item: locate::Item::None,
            field: field.to_string(),
            message,
        }
    }

    /// `section[index].field` or `section["key"].field`.
    pub fn path(&self) -> String {
        let item = match &self.item {
            locate::Item::Index(i) => format!("[{i}]"),
            locate::Item::Key(k) => format!("[\"{k}\"]"),
            locate::Item::None => String::new(),
        };
        if self.field.is_empty() {
            format!("{}{item}", self.section)
        } else {
            format!("{}{item}.{}", self.section, self.field)
        }
    }
}

/// An error reading a scene, located in its file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    pub file: String,
    pub line: Option<usize>,
    pub column: Option<usize>,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.line, self.column) {
            (Some(l), Some(c)) => write!(f, "{}:{l}:{c}: {}", self.file, self.message),
            _ => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

impl std::error::Error for SceneError {}

impl SceneError {
    pub fn from_field(file: &str, src: &str, e: &FieldError) -> Self {
        let pos = locate::locate(src, e.section, &e.item, &e.field);
        SceneError {
            file: file.to_string(),
            line: pos.map(|p| p.0),
            column: pos.map(|p| p.1),
            message: format!("{}: {}", e.path(), e.message),
        }
    }
}

/// Parses and validates a scene from text; `file` names it in errors.
pub fn parse(file: &str, src: &str) -> Result<Scene, SceneError> {
    // Implicit `Some` lets scenes write `poisson_ratio: 0.5` as the contract does, while
    // `Some(..)` and `None` are still accepted. (UNWRAP_VARIANT_NEWTYPES would also unwrap
    // `Some((x, y, z))` and break the contract's `move_to` syntax, so `Elastic` is a struct
    // variant instead.)
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let scene: Scene = options.from_str(src).map_err(|e| SceneError {
        file: file.to_string(),
        line: Some(e.span.start.line),
        column: Some(e.span.start.col),
        message: e.code.to_string(),
    })?;
    validate::validate(&scene).map_err(|e| SceneError::from_field(file, src, &e))?;
    Ok(scene)
}

/// Reads, parses and validates a scene file.
pub fn load(path: &Path) -> Result<(Scene, String), SceneError> {
    let file = path.display().to_string();
    let src = std::fs::read_to_string(path).map_err(|e| SceneError {
        file: file.clone(),
        line: None,
        column: None,
        message: format!("cannot read scene file: {e}"),
    })?;
    Ok((parse(&file, &src)?, src))
}
